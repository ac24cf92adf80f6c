// The scene's environment light as the device reads it (kernels/common/environment_light.h):
// the map's texels with their sampling density and the marginal and conditional CDFs of its
// luminance x sin(theta) distribution (kernels/common/environment_map.h), its launch
// parameters, the bounding sphere photons are emitted from, and the power photon mapping shares
// photons by. Built once per renderer (the environment does not move). Pure host code.
#pragma once

#include <cstdint>
#include <vector>

#include "render/kernel_abi.h"
#include "render/scene.h"
#include "render/scene_scale.h"

namespace pm {

struct EnvironmentDistribution {
  uint32_t type = PM_ENVIRONMENT_NONE;  // PM_ENVIRONMENT_*; NONE for a map without light
  uint32_t width = 0, height = 0;
  std::vector<float4> texels;  // map: rgb radiance, w = pdf_uv (W H texels, top row first)
  std::vector<float> cdf;      // map: H entries of the marginal CDF, then W per row (conditional)
};

// The map's distribution (in double precision, stored as float with every CDF ending at 1), or
// the constant environment's type alone. A map without light gives type NONE.
EnvironmentDistribution build_environment_distribution(const EnvironmentDesc& environment);

// Integral of the radiance over the sphere, int L(w) dw, per channel (W m^-2), exact for the
// piecewise-constant map: a texel of row j covers (2 pi / W)(cos theta_j - cos theta_j+1) sr.
Float3 environment_radiance_integral(const EnvironmentDesc& environment);

// The sphere photons of the environment start outside of: the centre of the scene's bounds and
// half their diagonal, grown by 1 % so that no vertex lies on it (xyz centre, w radius).
float4 environment_bounding_sphere(const SceneMeasures& measures);

// The environment's flux through the scene's bounding sphere, summed over RGB:
// pi R^2 int (L_r + L_g + L_b) dw, the measure photon mapping shares photons by (as
// SceneEmitters::power_rgb_sum for area lights). 0 without an environment.
double environment_power_rgb_sum(const EnvironmentDesc& environment, const SceneMeasures& measures);

// Sets LaunchParams' environment fields for this distribution.
void set_environment_params(const EnvironmentDistribution& distribution, const EnvironmentDesc& environment,
                            const SceneMeasures& measures, LaunchParams* params);

}  // namespace pm

// The scene's area lights as the device reads them (kernels/common/area_lights.h): one record
// per triangle whose material emits, with the cumulative power share that light sampling and
// photon emission choose emitters by, and the emitted radiance per material. Built once per
// renderer from the static geometry (emitters do not move). Pure host code.
#pragma once

#include <cstdint>
#include <vector>

#include "render/kernel_abi.h"
#include "render/scene.h"

namespace pm {

struct SceneEmitters {
  std::vector<float4> records;            // PM_EMITTER_FLOAT4S per emitter (area_lights.h)
  std::vector<float4> material_emission;  // per material: rgb L_e, w = mean; empty without emitters
  uint32_t count = 0;                     // emitting triangles
  double power = 0;                       // sum of pi A mean(L_e): LaunchParams::emitter_power
  double power_rgb_sum = 0;               // sum of pi A (L_r + L_g + L_b): the photon share's measure
};

// Emitters in triangle order; triangles of zero area are left out.
SceneEmitters build_scene_emitters(const Scene& scene);

}  // namespace pm

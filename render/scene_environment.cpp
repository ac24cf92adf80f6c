// Builds the environment map's sampling distribution and launch parameters of
// render/scene_environment.h in double precision, and defines EnvironmentDesc::emits of
// render/scene.h.
#include "render/scene_environment.h"

#include <cmath>

namespace pm {

namespace {

// The weights of kernels/common/vec3.h's vec3_luminance (Rec. 709).
double luminance(const float* rgb) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

// A CDF from non-negative weights, ending at exactly 1; all-zero weights give the uniform CDF
// (such a row is never chosen by the marginal, but its entries must stay ordered).
void append_cdf(const std::vector<double>& weights, std::vector<float>* cdf) {
  double total = 0;
  for (double w : weights) total += w;
  double running = 0;
  for (size_t k = 0; k < weights.size(); ++k) {
    running += total > 0 ? weights[k] : 1.0;
    const double share = running / (total > 0 ? total : double(weights.size()));
    cdf->push_back(k + 1 == weights.size() ? 1.0f : float(share));
  }
}

}  // namespace

bool EnvironmentDesc::emits() const {
  if (type == EnvironmentType::constant) return radiance.x > 0 || radiance.y > 0 || radiance.z > 0;
  if (type != EnvironmentType::map) return false;
  for (float v : texels)
    if (v > 0) return true;
  return false;
}

EnvironmentDistribution build_environment_distribution(const EnvironmentDesc& environment) {
  EnvironmentDistribution out;
  if (!environment.emits()) return out;
  if (environment.type == EnvironmentType::constant) {
    out.type = PM_ENVIRONMENT_CONSTANT;
    return out;
  }
  const size_t width = size_t(environment.width), height = size_t(environment.height);
  // f_ij = luminance x sin(theta) at the row's centre: the density over (u, v) that makes the
  // density per solid angle follow the luminance (d omega = 2 pi^2 sin theta du dv).
  std::vector<double> weight(width * height);
  std::vector<double> row_sum(height, 0.0);
  double total = 0;
  for (size_t j = 0; j < height; ++j) {
    const double sin_theta = std::sin(M_PI * (double(j) + 0.5) / double(height));
    for (size_t i = 0; i < width; ++i) {
      const double f = luminance(&environment.texels[3 * (j * width + i)]) * sin_theta;
      weight[j * width + i] = f;
      row_sum[j] += f;
    }
    total += row_sum[j];
  }
  if (!(total > 0)) return out;  // light in channels luminance does not see cannot happen (weights > 0)
  out.type = PM_ENVIRONMENT_MAP;
  out.width = uint32_t(width);
  out.height = uint32_t(height);
  out.texels.resize(width * height);
  const double texel_count = double(width) * double(height);
  for (size_t t = 0; t < width * height; ++t) {
    const float* rgb = &environment.texels[3 * t];
    out.texels[t] = float4{rgb[0], rgb[1], rgb[2], float(weight[t] * texel_count / total)};
  }
  out.cdf.reserve(height + width * height);
  append_cdf(row_sum, &out.cdf);
  for (size_t j = 0; j < height; ++j)
    append_cdf(std::vector<double>(weight.begin() + long(j * width), weight.begin() + long((j + 1) * width)), &out.cdf);
  return out;
}

Float3 environment_radiance_integral(const EnvironmentDesc& environment) {
  if (environment.type == EnvironmentType::constant) {
    const double sphere = 4 * M_PI;
    return Float3{float(sphere * environment.radiance.x), float(sphere * environment.radiance.y),
                  float(sphere * environment.radiance.z)};
  }
  if (environment.type != EnvironmentType::map) return Float3{0, 0, 0};
  const size_t width = size_t(environment.width), height = size_t(environment.height);
  double sum[3] = {0, 0, 0};
  for (size_t j = 0; j < height; ++j) {
    const double solid_angle = 2 * M_PI / double(width) *
                               (std::cos(M_PI * double(j) / double(height)) - std::cos(M_PI * double(j + 1) / double(height)));
    for (size_t i = 0; i < width; ++i)
      for (int c = 0; c < 3; ++c) sum[c] += solid_angle * environment.texels[3 * (j * width + i) + size_t(c)];
  }
  return Float3{float(sum[0]), float(sum[1]), float(sum[2])};
}

float4 environment_bounding_sphere(const SceneMeasures& measures) {
  const Float3& lo = measures.bounds.lo;
  const Float3& hi = measures.bounds.hi;
  const double radius = 0.5 * measures.diagonal * 1.01;
  return float4{0.5f * (lo.x + hi.x), 0.5f * (lo.y + hi.y), 0.5f * (lo.z + hi.z), float(radius > 0 ? radius : 1.0)};
}

double environment_power_rgb_sum(const EnvironmentDesc& environment, const SceneMeasures& measures) {
  if (!environment.emits()) return 0;
  const Float3 integral = environment_radiance_integral(environment);
  const double radius = environment_bounding_sphere(measures).w;
  return M_PI * radius * radius * (double(integral.x) + integral.y + integral.z);
}

void set_environment_params(const EnvironmentDistribution& distribution, const EnvironmentDesc& environment,
                            const SceneMeasures& measures, LaunchParams* params) {
  params->environment = distribution.type;
  params->environment_width = distribution.width;
  params->environment_height = distribution.height;
  params->environment_rotation = float(environment.rotation_degrees * M_PI / 180.0);
  const Float3& l = environment.radiance;
  params->environment_radiance = float4{l.x, l.y, l.z, float((double(l.x) + l.y + l.z) / 3.0)};
  params->environment_sphere = environment_bounding_sphere(measures);
}

}  // namespace pm

// The environment light's kernel functions on the host: the lat-long parameterisation and its
// inverse under a turn, the map's sampling distribution (texels drawn in proportion to luminance
// x sin(theta), a density per solid angle that integrates to 1 and follows the luminance, one
// bright texel taking every sample), the constant environment's sampling, the radiance integral
// and photon emission from the disk outside the bounding sphere.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "kernels/common/compat_host.h"
#include "kernels/common/environment_light.h"
#include "render/scene_environment.h"

namespace pm {
namespace {

constexpr double kPi = 3.14159265358979323846;

EnvironmentDesc make_map(int width, int height, unsigned seed) {
  EnvironmentDesc env;
  env.type = EnvironmentType::map;
  env.width = width;
  env.height = height;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(0.05f, 4.0f);
  for (int t = 0; t < width * height * 3; ++t) env.texels.push_back(value(rng));
  return env;
}

// The device's view of a distribution: its buffers bound in a KernelGlobals, its parameters.
struct BoundEnvironment {
  EnvironmentDistribution distribution;
  KernelGlobals kg{};
  LaunchParams p{};
  explicit BoundEnvironment(const EnvironmentDesc& env) : distribution(build_environment_distribution(env)) {
    kg.environment_texels = distribution.texels.data();
    kg.environment_cdf = distribution.cdf.data();
    SceneMeasures measures;
    measures.bounds.lo = {-1, -1, -1};
    measures.bounds.hi = {1, 3, 1};
    measures.diagonal = std::sqrt(4.0 + 16.0 + 4.0);
    set_environment_params(distribution, env, measures, &p);
  }
};

double texel_luminance(const EnvironmentDesc& env, size_t t) {
  return 0.2126 * env.texels[3 * t] + 0.7152 * env.texels[3 * t + 1] + 0.0722 * env.texels[3 * t + 2];
}

TEST(EnvironmentMap, DirectionAndUvAreInverseUnderATurn) {
  for (float rotation : {0.0f, 0.7f, -2.5f}) {
    for (float u : {0.03f, 0.25f, 0.5f, 0.81f}) {
      for (float v : {0.1f, 0.5f, 0.93f}) {
        const Vec3 d = environment_direction(u, v, rotation);
        EXPECT_NEAR(vec3_length(d), 1.0f, 1e-6f);
        float u2, v2;
        environment_uv(d, rotation, &u2, &v2);
        EXPECT_NEAR(u2, u, 1e-5f) << rotation;
        EXPECT_NEAR(v2, v, 1e-5f) << rotation;
      }
    }
  }
  // The documented orientation: top row up, centre column towards -z, u = 3/4 towards +x.
  EXPECT_NEAR(environment_direction(0.3f, 0.0f, 0.0f).y, 1.0f, 1e-6f);
  EXPECT_NEAR(environment_direction(0.5f, 0.5f, 0.0f).z, -1.0f, 1e-6f);
  EXPECT_NEAR(environment_direction(0.75f, 0.5f, 0.0f).x, 1.0f, 1e-6f);
  // A quarter turn about +y takes -z to -x (right-handed).
  EXPECT_NEAR(environment_direction(0.5f, 0.5f, float(kPi / 2)).x, -1.0f, 1e-6f);
}

TEST(EnvironmentMap, SamplesFollowLuminanceTimesSinTheta) {
  const EnvironmentDesc env = make_map(16, 8, 7);
  BoundEnvironment b(env);
  ASSERT_EQ(b.p.environment, PM_ENVIRONMENT_MAP);
  const size_t texels = 16 * 8;
  std::vector<double> expected(texels);
  double total = 0;
  for (size_t t = 0; t < texels; ++t) {
    expected[t] = texel_luminance(env, t) * std::sin(kPi * (double(t / 16) + 0.5) / 8);
    total += expected[t];
  }
  const int n = 400000;
  std::vector<int> count(texels, 0);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  int pdf_mismatches = 0;
  for (int k = 0; k < n; ++k) {
    const EnvironmentSample s = environment_sample(&b.kg, &b.p, uniform(rng), uniform(rng));
    ASSERT_GT(s.pdf, 0.0f);
    float u, v;
    environment_uv(s.wi, b.p.environment_rotation, &u, &v);
    ++count[environment_texel(u, v, 16, 8)];
    // The density a sampled direction reports is the density looked up for it.
    if (std::fabs(environment_pdf(&b.kg, &b.p, s.wi) / s.pdf - 1.0f) > 1e-3f) ++pdf_mismatches;
  }
  EXPECT_LT(pdf_mismatches, n / 1000);  // only samples on a texel's edge may round across it
  double chi2 = 0;
  for (size_t t = 0; t < texels; ++t) {
    const double e = n * expected[t] / total;
    chi2 += (count[t] - e) * (count[t] - e) / e;
  }
  // 127 degrees of freedom: the 99.9 % quantile is about 181.
  std::printf("environment sampling: chi^2 = %.1f over %zu texels\n", chi2, texels);
  EXPECT_LT(chi2, 181.0);
}

TEST(EnvironmentMap, DensityIntegratesToOneAndFollowsLuminance) {
  const EnvironmentDesc env = make_map(32, 16, 11);
  BoundEnvironment b(env);
  // Sum over texels of pdf_uv du dv.
  double sum_uv = 0;
  for (const float4& t : b.distribution.texels) sum_uv += t.w / (32.0 * 16.0);
  EXPECT_NEAR(sum_uv, 1.0, 1e-5);
  // The density per solid angle, integrated over the sphere by uniform Monte Carlo.
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  const int n = 1000000;
  double integral = 0;
  for (int k = 0; k < n; ++k)
    integral += environment_pdf(&b.kg, &b.p, environment_uniform_direction(uniform(rng), uniform(rng))) * 4 * kPi;
  integral /= n;
  std::printf("environment density over the sphere: %.5f\n", integral);
  EXPECT_NEAR(integral, 1.0, 0.01);
  // At texel centres pdf / luminance is one constant: the density follows the luminance.
  double lo = 1e30, hi = 0;
  for (int j = 0; j < 16; ++j) {
    for (int i = 0; i < 32; ++i) {
      const Vec3 d = environment_direction((i + 0.5f) / 32, (j + 0.5f) / 16, b.p.environment_rotation);
      const double ratio = environment_pdf(&b.kg, &b.p, d) / texel_luminance(env, size_t(j * 32 + i));
      lo = std::min(lo, ratio);
      hi = std::max(hi, ratio);
    }
  }
  EXPECT_NEAR(hi / lo, 1.0, 1e-4);
}

TEST(EnvironmentMap, OneBrightTexelTakesEverySample) {
  EnvironmentDesc env;
  env.type = EnvironmentType::map;
  env.width = 24;
  env.height = 12;
  env.rotation_degrees = 30;
  env.texels.assign(24 * 12 * 3, 0.0f);
  const size_t bright = 5 * 24 + 17;
  env.texels[3 * bright] = env.texels[3 * bright + 1] = env.texels[3 * bright + 2] = 100.0f;
  BoundEnvironment b(env);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  int elsewhere = 0;
  for (int k = 0; k < 20000; ++k) {
    const EnvironmentSample s = environment_sample(&b.kg, &b.p, uniform(rng), uniform(rng));
    float u, v;
    environment_uv(s.wi, b.p.environment_rotation, &u, &v);
    if (environment_texel(u, v, 24, 12) != bright) ++elsewhere;
    EXPECT_FLOAT_EQ(s.radiance.x, 100.0f);
  }
  EXPECT_LE(elsewhere, 20);  // edge rounding at most
  // Directions elsewhere have no density and no light.
  const Vec3 dark = environment_direction(0.1f, 0.9f, b.p.environment_rotation);
  EXPECT_EQ(environment_pdf(&b.kg, &b.p, dark), 0.0f);
  EXPECT_EQ(environment_radiance(&b.kg, &b.p, dark).x, 0.0f);
}

TEST(EnvironmentMap, ConstantEnvironmentAndIntegrals) {
  EnvironmentDesc env;
  env.type = EnvironmentType::constant;
  env.radiance = {0.5f, 1.0f, 2.0f};
  BoundEnvironment b(env);
  ASSERT_EQ(b.p.environment, PM_ENVIRONMENT_CONSTANT);
  const EnvironmentSample s = environment_sample(&b.kg, &b.p, 0.3f, 0.6f);
  EXPECT_FLOAT_EQ(s.pdf, float(1 / (4 * kPi)));
  EXPECT_FLOAT_EQ(s.radiance.z, 2.0f);
  EXPECT_NEAR(environment_radiance_integral(env).y, 4 * kPi, 1e-5);
  // A map of one value integrates to 4 pi times it; a black map is no light.
  EnvironmentDesc flat;
  flat.type = EnvironmentType::map;
  flat.width = 7;
  flat.height = 5;
  flat.texels.assign(7 * 5 * 3, 0.25f);
  EXPECT_NEAR(environment_radiance_integral(flat).x, kPi, 1e-5);
  flat.texels.assign(7 * 5 * 3, 0.0f);
  EXPECT_FALSE(flat.emits());
  EXPECT_EQ(build_environment_distribution(flat).type, PM_ENVIRONMENT_NONE);
}

TEST(EnvironmentMap, PhotonsStartOnTheDiskOutsideTheBoundingSphere) {
  const EnvironmentDesc env = make_map(16, 8, 13);
  BoundEnvironment b(env);
  const Vec3 centre = vec3_from_float4(b.p.environment_sphere);
  const float radius = b.p.environment_sphere.w;
  EXPECT_NEAR(radius, 0.5 * std::sqrt(24.0) * 1.01, 1e-5);
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (int k = 0; k < 1000; ++k) {
    const float u1 = uniform(rng), u2 = uniform(rng);
    PhotonRay ray;
    Vec3 flux;
    ASSERT_TRUE(photon_emit_environment(&b.kg, &b.p, u1, u2, uniform(rng), uniform(rng), 1000u, &ray, &flux));
    const EnvironmentSample s = environment_sample(&b.kg, &b.p, u1, u2);
    const Vec3 w = vec3_neg(ray.direction);
    const Vec3 rel = vec3_sub(ray.origin, centre);
    EXPECT_NEAR(vec3_dot(rel, w), radius, 1e-4f * radius);  // in the plane tangent to the sphere
    EXPECT_LE(vec3_length(vec3_madd(rel, w, -radius)), radius * 1.0001f);  // within the disk
    EXPECT_NEAR(flux.y / (s.radiance.y * kPi * radius * radius / (s.pdf * 1000.0)), 1.0, 1e-5);
    EXPECT_NEAR(vec3_length(ray.dp_u), radius / 2, 1e-5f);
    EXPECT_NEAR(vec3_dot(ray.dp_u, ray.dp_v), 0.0f, 1e-5f);
    EXPECT_NEAR(vec3_dot(ray.dp_u, w), 0.0f, 1e-5f);
    EXPECT_EQ(vec3_length(ray.dd_u), 0.0f);
  }
}

}  // namespace
}  // namespace pm

// glTF animation math (scene_io/gltf_animation.h): TRS matrices, samplers with STEP, LINEAR
// (slerp for rotations) and CUBICSPLINE interpolation, holds outside the keys.
#include <gtest/gtest.h>

#include <cmath>

#include "scene_io/gltf_animation.h"

namespace pm::gltf {
namespace {

TEST(GltfAnimation, TrsAppliesScaleThenRotationThenTranslation) {
  const double s = std::sqrt(0.5);
  // 90 degrees about +z maps +x to +y.
  const Mat4 m = mat4_from_trs({1, 2, 3}, {0, 0, s, s}, {2, 2, 2});
  const Vec3d p = transform_point(m, {1, 0, 0});
  EXPECT_NEAR(p[0], 1.0, 1e-12);
  EXPECT_NEAR(p[1], 4.0, 1e-12);
  EXPECT_NEAR(p[2], 3.0, 1e-12);
  const Vec3d d = transform_direction(m, {0, 1, 0});
  EXPECT_NEAR(d[0], -2.0, 1e-12);
  EXPECT_NEAR(d[1], 0.0, 1e-12);
  // Products compose like the node hierarchy: parent * child.
  const Mat4 parent = mat4_from_trs({10, 0, 0}, {0, 0, 0, 1}, {1, 1, 1});
  const Vec3d q = transform_point(parent * m, {1, 0, 0});
  EXPECT_NEAR(q[0], 11.0, 1e-12);
  EXPECT_NEAR(q[1], 4.0, 1e-12);
}

TEST(GltfAnimation, UnnormalisedRotationsAreNormalised) {
  const Mat4 m = mat4_from_trs({0, 0, 0}, {0, 0, 3, 3}, {1, 1, 1});
  const Vec3d p = transform_point(m, {1, 0, 0});
  EXPECT_NEAR(p[1], 1.0, 1e-12);
}

Sampler translation(SamplerInterpolation mode) {
  Sampler s;
  s.interpolation = mode;
  s.times = {1.0, 2.0, 4.0};
  s.values = {0, 0, 0, 10, 0, 0, 10, 20, 0};
  return s;
}

TEST(GltfAnimation, LinearAndStepSamplers) {
  const Sampler linear = translation(SamplerInterpolation::linear);
  EXPECT_EQ(linear.evaluate(0.0), (std::vector<double>{0, 0, 0}));   // hold before
  EXPECT_EQ(linear.evaluate(1.5), (std::vector<double>{5, 0, 0}));
  EXPECT_EQ(linear.evaluate(3.0), (std::vector<double>{10, 10, 0}));
  EXPECT_EQ(linear.evaluate(9.0), (std::vector<double>{10, 20, 0}));  // hold after
  const Sampler step = translation(SamplerInterpolation::step);
  EXPECT_EQ(step.evaluate(1.99), (std::vector<double>{0, 0, 0}));
  EXPECT_EQ(step.evaluate(2.0), (std::vector<double>{10, 0, 0}));
  EXPECT_EQ(step.evaluate(3.99), (std::vector<double>{10, 0, 0}));
}

TEST(GltfAnimation, CubicSplineUsesTheTangents) {
  Sampler s;
  s.interpolation = SamplerInterpolation::cubic_spline;
  s.components = 3;
  s.times = {0.0, 2.0};
  // (in-tangent, value, out-tangent) per key.
  s.values = {0, 0, 0, /**/ 0, 0, 0, /**/ 1, 0, 0,
              3, 0, 0, /**/ 4, 0, 0, /**/ 0, 0, 0};
  EXPECT_EQ(s.evaluate(0.0)[0], 0.0);
  EXPECT_EQ(s.evaluate(2.0)[0], 4.0);
  // Hermite at s = 0.5 with h = 2: 0.5 * 0 + 0.125 * 2 * 1 + 0.5 * 4 - 0.125 * 2 * 3.
  EXPECT_NEAR(s.evaluate(1.0)[0], 0.25 + 2.0 - 0.75, 1e-12);
  // Outside the keys: the key values, not the tangents.
  EXPECT_EQ(s.evaluate(-1.0)[0], 0.0);
  EXPECT_EQ(s.evaluate(5.0)[0], 4.0);
}

TEST(GltfAnimation, RotationsUseSlerpOnTheShorterArc) {
  Sampler s;
  s.components = 4;
  s.times = {0.0, 1.0};
  const double h = std::sqrt(0.5);
  s.values = {0, 0, 0, 1, /**/ 0, h, 0, h};  // identity to 90 degrees about +y
  std::vector<double> q = s.evaluate(0.5);     // 45 degrees
  EXPECT_NEAR(q[1], std::sin(M_PI / 8), 1e-12);
  EXPECT_NEAR(q[3], std::cos(M_PI / 8), 1e-12);
  // The same end rotation written as -q: still the 45-degree midpoint, not the long way round.
  s.values = {0, 0, 0, 1, /**/ 0, -h, 0, -h};
  q = s.evaluate(0.5);
  EXPECT_NEAR(std::fabs(q[1]), std::sin(M_PI / 8), 1e-12);
  EXPECT_NEAR(std::fabs(q[3]), std::cos(M_PI / 8), 1e-12);
  // A quarter of the way: a constant angular speed, unlike normalised linear interpolation.
  s.values = {0, 0, 0, 1, /**/ 0, 1, 0, 0};  // 180 degrees about +y
  q = s.evaluate(0.25);
  EXPECT_NEAR(q[1], std::sin(M_PI / 8), 1e-12);
}

TEST(GltfAnimation, CubicSplineRotationsAreNormalised) {
  Sampler s;
  s.components = 4;
  s.interpolation = SamplerInterpolation::cubic_spline;
  s.times = {0.0, 1.0};
  const double h = std::sqrt(0.5);
  s.values = {0, 0, 0, 0, /**/ 0, 0, 0, 1, /**/ 0, 0, 0, 0,
              0, 0, 0, 0, /**/ 0, h, 0, h, /**/ 0, 0, 0, 0};
  const std::vector<double> q = s.evaluate(0.5);
  EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1.0, 1e-12);
}

}  // namespace
}  // namespace pm::gltf

// The orthonormal basis around a normal (vec3_onb, kernels/common/vec3.h): orthonormal and
// right-handed for random and axis-aligned normals, and continuous where scenes put their normals:
// +0 and -0 components, and perturbations at float rounding, give the same frame. (Duff's method
// on the raw normal flips its frame between n.z = +0 and n.z = -0, so two compilers that round a
// wall's normal to different signed zeros sampled different directions from the same numbers.)
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

// clang-format off
#include "kernels/common/compat_host.h"
#include "kernels/common/vec3.h"
// clang-format on

namespace {

void expect_orthonormal_frame(Vec3 n) {
  Vec3 t, b;
  vec3_onb(n, &t, &b);
  EXPECT_NEAR(vec3_length(t), 1.0f, 2e-6f);
  EXPECT_NEAR(vec3_length(b), 1.0f, 2e-6f);
  EXPECT_NEAR(vec3_dot(t, b), 0.0f, 2e-6f);
  EXPECT_NEAR(vec3_dot(t, n), 0.0f, 2e-6f);
  EXPECT_NEAR(vec3_dot(b, n), 0.0f, 2e-6f);
  const Vec3 handed = vec3_cross(t, b);  // t x b = n: right-handed
  EXPECT_NEAR(vec3_dot(handed, n), 1.0f, 4e-6f) << n.x << " " << n.y << " " << n.z;
}

float frame_distance(Vec3 n, Vec3 m) {
  Vec3 tn, bn, tm, bm;
  vec3_onb(n, &tn, &bn);
  vec3_onb(m, &tm, &bm);
  return std::fmax(vec3_max_abs(vec3_sub(tn, tm)), vec3_max_abs(vec3_sub(bn, bm)));
}

// Normals with components in {0, +-1/2, +-1}, normalised: walls, floors, 45-degree roofs.
std::vector<Vec3> architectural_normals() {
  std::vector<Vec3> normals;
  const float values[] = {-1.0f, -0.5f, 0.0f, 0.5f, 1.0f};
  for (float x : values)
    for (float y : values)
      for (float z : values)
        if (x != 0.0f || y != 0.0f || z != 0.0f) normals.push_back(vec3_normalize(vec3(x, y, z)));
  return normals;
}

TEST(OrthonormalBasis, OrthonormalAndRightHanded) {
  std::mt19937 rng(7);
  std::normal_distribution<float> gauss;
  for (int i = 0; i < 10000; ++i) expect_orthonormal_frame(vec3_normalize(vec3(gauss(rng), gauss(rng), gauss(rng))));
  for (Vec3 n : architectural_normals()) expect_orthonormal_frame(n);
}

TEST(OrthonormalBasis, SignedZerosAndRoundingDoNotFlipTheFrame) {
  for (Vec3 n : architectural_normals()) {
    // Every zero component as +0 and as -0.
    Vec3 flipped = vec3(n.x == 0.0f ? -n.x : n.x, n.y == 0.0f ? -n.y : n.y, n.z == 0.0f ? -n.z : n.z);
    EXPECT_EQ(frame_distance(n, flipped), 0.0f) << n.x << " " << n.y << " " << n.z;
    // A nudge of a few ulps in each component, as FMA contraction gives.
    for (int axis = 0; axis < 3; ++axis) {
      Vec3 nudged = n;
      float* c = axis == 0 ? &nudged.x : (axis == 1 ? &nudged.y : &nudged.z);
      *c += (*c == 0.0f) ? -1e-7f : *c * 4e-7f;
      EXPECT_LT(frame_distance(n, vec3_normalize(nudged)), 1e-5f) << n.x << " " << n.y << " " << n.z << " axis " << axis;
    }
  }
}

}  // namespace

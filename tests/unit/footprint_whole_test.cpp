// Unit tests of footprints wholly on their own surface (kernels/common/footprint_whole.h) on the
// host, with the scene BVH the device uses: a footprint on its flat surface with nothing over it
// is whole, also across an edge its triangle shares with another of the plane; one over the
// surface's rim, at a wall, over a hole or with a plate standing in it is not; surfaces below the
// photon's plane or above the probes do not matter; and over the built-in
// Cornell box, every footprint the proof calls whole is one whose probes all count
// (footprint_covered_share returns exactly 1): the shortcut never changes a result.
#include "kernels/common/compat_host.h"
#include "kernels/common/footprint_coverage.h"
#include "kernels/common/footprint_whole.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "scene_io/cornell_box.h"
#include "support/host_scene.h"
#include "support/room_scenes.h"

namespace pm {
namespace {

constexpr float kOffset = 1e-5f;

// A circle of `radius` on a floor (normal +y), thickness as the pd footprints have it.
Footprint floor_circle(float radius) {
  Footprint f;
  f.axis_u = vec3(radius, 0, 0);
  f.axis_v = vec3(0, 0, radius);
  f.axis_n = vec3(0, PM_FOOTPRINT_NORMAL_RATIO * radius, 0);
  return f;
}

// The triangle a photon coming down onto `at` hits (leaf-order index), as the photon trace records it.
int triangle_under(const test::HostScene& scene, Vec3 at) {
  const Ray ray = ray_make(vec3_add(at, vec3(0, 0.25f, 0)), vec3(0, -1, 0));
  return scene_trace(&scene.kg, &ray, 0.0f, 1.0f, 0).triangle;
}

bool whole(const test::HostScene& scene, Vec3 at, float radius) {
  const Footprint f = floor_circle(radius);
  return footprint_wholly_on_own_surface(&scene.kg, &f, at, vec3(0, 1, 0), kOffset, triangle_under(scene, at)) != 0;
}

float probed_share(const test::HostScene& scene, Vec3 at, float radius, float turn) {
  const Footprint f = floor_circle(radius);
  const FootprintCut cut = footprint_uncut();
  return footprint_covered_share(&scene.kg, &f, &cut, at, vec3(0, 1, 0), kOffset, turn, PM_KERNEL_CONSTANT,
                                 PM_COVERAGE_CELLS, vec3(0, 1, 0));
}

// A floor y = 0 of two triangles (their shared edge along x = z) and a wall x = 0 standing on it.
Scene floor_and_wall() {
  Scene s;
  s.materials = {MaterialDesc{}};
  test::add_quad(s, {-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, {5, 0, -5});
  test::add_quad(s, {0, 0, -5}, {0, 2, -5}, {0, 2, 5}, {0, 0, 5});
  return s;
}

TEST(FootprintWhole, InsideItsTriangleWithNothingOverItIsWhole) {
  const test::HostScene scene(floor_and_wall());
  // 3 from the wall, 3.5 from the shared edge, 2 from the floor's rim: a unit circle fits.
  EXPECT_TRUE(whole(scene, vec3(3, 0, -2), 1.0f));
  for (float turn : {0.0f, 1.0f, 2.5f}) EXPECT_EQ(probed_share(scene, vec3(3, 0, -2), 1.0f, turn), 1.0f);
}

TEST(FootprintWhole, OverASharedEdgeItIsWholeOverTheRimOrAWallNot) {
  const test::HostScene scene(floor_and_wall());
  EXPECT_TRUE(whole(scene, vec3(2, 0, 1.5f), 1.0f)) << "over the floor's shared edge x = z, 0.35 away";
  EXPECT_EQ(probed_share(scene, vec3(2, 0, 1.5f), 1.0f, 0.4f), 1.0f);
  // (The floor goes on behind the wall, so the probes find it covered there; walls are the clip's
  // to cut. The proof stays on the safe side and leaves the footprint to the probes.)
  EXPECT_FALSE(whole(scene, vec3(0.5f, 0, -2), 1.0f)) << "the wall is 0.5 away";
  EXPECT_FALSE(whole(scene, vec3(4.5f, 0, -2), 1.0f)) << "the floor ends 0.5 away";
  EXPECT_TRUE(whole(scene, vec3(2.5f, 0, -2), 1.0f)) << "the wall 1.5 away, outside the circle";
}

TEST(FootprintWhole, OnAFinelyTiledFloorItIsWholeOverAHoleNot) {
  // A floor of 0.25-wide tiles (two triangles each) around (0, 0, 0), one tile left out at
  // (0.5 ... 0.75, 0 ... 0.25).
  Scene s;
  s.materials = {MaterialDesc{}};
  for (int i = -8; i < 8; ++i)
    for (int k = -8; k < 8; ++k) {
      if (i == 2 && k == 0) continue;
      const float x = 0.25f * float(i), z = 0.25f * float(k);
      test::add_quad(s, {x, 0, z}, {x, 0, z + 0.25f}, {x + 0.25f, 0, z + 0.25f}, {x + 0.25f, 0, z});
    }
  const test::HostScene scene(s);
  EXPECT_TRUE(whole(scene, vec3(-0.6f, 0, -0.5f), 0.8f)) << "over about 40 tiles";
  EXPECT_EQ(probed_share(scene, vec3(-0.6f, 0, -0.5f), 0.8f, 1.1f), 1.0f);
  EXPECT_FALSE(whole(scene, vec3(0.1f, 0, 0.1f), 0.8f)) << "the hole is inside the circle";
  EXPECT_LT(probed_share(scene, vec3(0.1f, 0, 0.1f), 0.8f, 1.1f), 1.0f);
}

TEST(FootprintWhole, ASteepPlateStandingInItIsSeenAsTheProbesSeeIt) {
  Scene s = floor_and_wall();
  // A plate leaning at 72 degrees, lower than the footprint is thick, inside the circle about
  // (3, 0, -2): a probe through it crosses it first, and the floor under it is inside a solid.
  test::add_quad(s, {3.2f, 0, -2.6f}, {3.3f, 0.3f, -2.6f}, {3.3f, 0.3f, -1.4f}, {3.2f, 0, -1.4f});
  const test::HostScene scene(s);
  EXPECT_FALSE(whole(scene, vec3(3, 0, -2), 1.0f));
  EXPECT_LT(probed_share(scene, vec3(3, 0, -2), 1.0f, 0.0f), 1.0f);
}

TEST(FootprintWhole, SurfacesBelowThePlaneOrAboveTheProbesDoNotMatter) {
  Scene s = floor_and_wall();
  test::add_quad(s, {2, -0.3f, -3}, {2, -0.3f, -1}, {4, -0.3f, -1}, {4, -0.3f, -3});  // a slab below
  test::add_quad(s, {2, 0.9f, -3}, {4, 0.9f, -3}, {4, 0.9f, -1}, {2, 0.9f, -1});      // a shelf above
  const test::HostScene scene(s);
  // The probes start at most the normal half-axis (0.5) above the floor.
  EXPECT_TRUE(whole(scene, vec3(3, 0, -2), 1.0f));
  EXPECT_EQ(probed_share(scene, vec3(3, 0, -2), 1.0f, 0.7f), 1.0f);
}

// Footprints of many sizes on the built-in box's surfaces, found by rays from inside it: the
// proof must never call whole what the probes would find partly covered, and must call some whole.
TEST(FootprintWhole, InTheCornellBoxWholeFootprintsAreThoseWhoseProbesAllCount) {
  const test::HostScene scene(builtin_cornell_box());
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  int footprints = 0, proven = 0, fully_probed = 0;
  for (int i = 0; i < 4000; ++i) {
    const float z = 2 * unit(rng) - 1, phi = 2 * float(M_PI) * unit(rng), s = std::sqrt(1 - z * z);
    const Ray ray = ray_make(vec3(0.278f, 0.274f, 0.28f), vec3(s * std::cos(phi), s * std::sin(phi), z));
    const SceneHit hit = scene_trace(&scene.kg, &ray, 0.0f, 1e30f, 0);
    if (hit.triangle < 0) continue;
    const Vec3 at = vec3_madd(ray.origin, ray.direction, hit.t);
    Vec3 n = scene_triangle_normal(scene.kg.triangles, hit.triangle);
    if (vec3_dot(n, ray.direction) > 0) n = vec3_neg(n);
    Vec3 t, b;
    vec3_onb(n, &t, &b);
    const float radius = 0.005f + 0.1f * unit(rng) * unit(rng);
    Footprint f;
    f.axis_u = vec3_scale(t, radius);
    f.axis_v = vec3_scale(b, 0.6f * radius);
    f.axis_n = vec3_scale(n, PM_FOOTPRINT_NORMAL_RATIO * 0.6f * radius);
    const FootprintCut cut = footprint_uncut();
    const float share = footprint_covered_share(&scene.kg, &f, &cut, at, n, kOffset, 6.0f * unit(rng),
                                                PM_KERNEL_CONSTANT, PM_COVERAGE_CELLS, vec3_neg(ray.direction));
    const bool is_whole = footprint_wholly_on_own_surface(&scene.kg, &f, at, n, kOffset, hit.triangle) != 0;
    ++footprints;
    proven += is_whole;
    fully_probed += share == 1.0f;
    if (is_whole) {
      EXPECT_EQ(share, 1.0f) << "footprint " << i << " at (" << at.x << ", " << at.y << ", " << at.z << ")";
    }
  }
  std::printf("%d footprints: %d proven whole, %d with every probe covered\n", footprints, proven, fully_probed);
  EXPECT_GT(proven, footprints / 4);
}

}  // namespace
}  // namespace pm

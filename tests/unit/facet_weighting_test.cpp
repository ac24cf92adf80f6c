// Unit tests of facet weighting (--facet-weighting, docs/accuracy.md "Bias at bends") on the host,
// with the scene BVH the device uses: the gather's tilt gain (gather_reach.h) against the cosine
// law of a beam's irradiance, and the footprint coverage's lit area (footprint_coverage.h) on a
// floor that bends down into a slope, with the photon's light arriving above both surfaces or
// below the slope.
#include "kernels/common/compat_host.h"
#include "kernels/common/footprint_coverage.h"

#include <gtest/gtest.h>

#include <cmath>

#include "support/host_scene.h"
#include "support/room_scenes.h"

namespace pm {
namespace {

Vec3 unit(float x, float y, float z) { return vec3_normalize(vec3(x, y, z)); }

// The normal axis row of a footprint whose normal half-axis is `length` along n: n / length.
float4 row_of(Vec3 n, float length) { return vec3_to_float4(vec3_scale(n, 1.0f / length), 0.0f); }

TEST(TiltGain, IsTheRatioOfTheBeamsCosinesOnTheFacetAndOnItsOwnSurface) {
  const Vec3 up = vec3(0, 1, 0);
  const Vec3 wi = unit(0.5f, 1.0f, 0.2f);
  // On its own surface the photon counts in full, whatever the length of the normal axis row.
  EXPECT_NEAR(gather_tilt_gain(row_of(up, 0.37f), wi, up), 1.0f, 1e-6f);
  // A facet tilted by 30 degrees towards the beam receives more of it, one tilted away less.
  for (float tilt : {-0.5f, -0.25f, 0.25f, 0.5f}) {
    const Vec3 facet = vec3(std::sin(tilt), std::cos(tilt), 0);
    const float expected = vec3_dot(wi, facet) / vec3_dot(wi, up);
    EXPECT_NEAR(gather_tilt_gain(row_of(up, 2.0f), wi, facet), expected, 1e-5f) << "tilt " << tilt;
  }
  // A facet the beam reaches from behind gets nothing; a photon that grazed its own surface is
  // capped rather than counted without bound.
  EXPECT_EQ(gather_tilt_gain(row_of(up, 1.0f), unit(-1.0f, 0.05f, 0), unit(0.6f, 0.8f, 0)), 0.0f);
  EXPECT_EQ(gather_tilt_gain(row_of(up, 1.0f), unit(1.0f, 0.01f, 0), unit(0.6f, 0.8f, 0)), PM_GATHER_MAX_TILT_GAIN);
}

// A footprint of radius 0.5 m at the origin with normal n, `thickness` metres thick along it.
Footprint disc(Vec3 n, float thickness) {
  Vec3 t, b;
  vec3_onb(n, &t, &b);
  Footprint f;
  f.axis_u = vec3_scale(t, 0.5f);
  f.axis_v = vec3_scale(b, 0.5f);
  f.axis_n = vec3_scale(n, thickness);
  return f;
}

float covered_share(const test::HostScene& scene, const Footprint& f, Vec3 n, uint mode, Vec3 wi) {
  const FootprintCut cut = footprint_uncut();
  return footprint_covered_share(&scene.kg, &f, &cut, vec3(0, 0, 0), n, 1e-4f, 0.3f, PM_KERNEL_CONSTANT, mode, wi);
}

TEST(LitArea, IsTheSurfaceAreaUnderTheFootprintWhereThePhotonsLightArrivesAboveIt) {
  // A footprint tilted 20 degrees from the floor it lies on (thick enough that every probe reaches
  // the floor): each probe's cell covers 1 / cos 20 degrees of floor.
  Scene floor_only = test::bent_floor_scene();
  floor_only.positions.resize(4);
  floor_only.indices.resize(6);
  floor_only.triangle_material.resize(2);
  for (Float3& p : floor_only.positions) p.x = 4 * p.x + 4;  // [-4, 4] x [-2, 2]
  const test::HostScene scene(floor_only);
  const Vec3 n = vec3(std::sin(0.349066f), std::cos(0.349066f), 0);
  const Footprint f = disc(n, 4.0f);
  const Vec3 from_above = unit(0.2f, 1.0f, 0.1f), from_below = unit(0.9f, -0.1f, 0.0f);
  ASSERT_GT(vec3_dot(from_below, n), 0.0f);  // above the footprint's own plane, below the floor
  EXPECT_NEAR(covered_share(scene, f, n, PM_COVERAGE_CELLS, from_above), 1.0f, 1e-6f);
  EXPECT_NEAR(covered_share(scene, f, n, PM_COVERAGE_SURFACE_AREA, from_above), 1.0f / std::cos(0.349066f), 1e-4f);
  EXPECT_NEAR(covered_share(scene, f, n, PM_COVERAGE_LIT_AREA, from_above), 1.0f / std::cos(0.349066f), 1e-4f);
  // Light from below the floor lights none of it: only the hit's own half cell is left.
  EXPECT_LT(covered_share(scene, f, n, PM_COVERAGE_LIT_AREA, from_below), 0.05f);
}

TEST(LitArea, LeavesOutTheFacetsThePhotonsLightDoesNotReach) {
  // A footprint at the bend: light from under the slope lights the floor's half of the disc only.
  const test::HostScene scene(test::bent_floor_scene());
  const Vec3 n = vec3(0, 1, 0);
  const Footprint f = disc(n, 0.5f);
  const Vec3 from_above = unit(0.2f, 1.0f, 0.1f), under_slope = unit(-1.0f, 0.2f, 0.0f);
  ASSERT_LT(vec3_dot(under_slope, vec3(std::sin(0.349066f), std::cos(0.349066f), 0)), 0.0f);
  EXPECT_FLOAT_EQ(covered_share(scene, f, n, PM_COVERAGE_LIT_AREA, from_above),
                  covered_share(scene, f, n, PM_COVERAGE_SURFACE_AREA, from_above));
  EXPECT_NEAR(covered_share(scene, f, n, PM_COVERAGE_LIT_AREA, under_slope), 0.5f, 0.04f);
}

}  // namespace
}  // namespace pm

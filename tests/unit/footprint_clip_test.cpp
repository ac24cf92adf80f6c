// Unit tests of footprints that stop at walls (kernels/common/footprint_clip.h) on the host, with
// the scene BVH the device uses: the kept kernel mass of a cut disc against numerical
// integration; a footprint next to a wall cut at the wall and nothing else; uniform photons on a
// floor giving the density profile at a wall's foot predicted by the cut; coplanar neighbours,
// walls lower than the lifted plane and gently curved concave surfaces leaving footprints alone.
#include "kernels/common/compat_host.h"
#include "kernels/common/footprint_clip.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "support/host_scene.h"
#include "support/analytic_scenes.h"
#include "support/room_scenes.h"

namespace pm {
namespace {

Footprint circle(float radius) {
  Footprint f;
  f.axis_u = vec3(radius, 0, 0);
  f.axis_v = vec3(0, 0, radius);
  f.axis_n = vec3(0, PM_FOOTPRINT_NORMAL_RATIO * radius, 0);
  return f;
}

// Whether x lies in the clipped footprint of a hit at `center`: in the ellipse and on the hit's
// side of every cut, as the gather tests it.
bool reaches(const Footprint& f, const FootprintCut& cut, Vec3 center, Vec3 x) {
  float r2 = 0;
  if (!footprint_contains(f, center, x, &r2)) return false;
  // Disc coordinates of x - center: x - center = lu a_u + lv a_v + ln a_n.
  const Vec3 d = vec3_sub(x, center);
  const float det = vec3_dot(f.axis_u, vec3_cross(f.axis_v, f.axis_n));
  const float lu = vec3_dot(vec3_cross(f.axis_v, f.axis_n), d) / det;
  const float lv = vec3_dot(vec3_cross(f.axis_n, f.axis_u), d) / det;
  for (int k = 0; k < PM_FOOTPRINT_CUTS; ++k)
    if (cut.mu[k] * lu + cut.mv[k] * lv > cut.t[k]) return false;
  return true;
}

// Kernel mass fraction of the unit disc where m_k . q <= t_k for every cut, by the midpoint rule
// on a fine grid: the independent reference.
double numerical_kept(const std::vector<std::array<double, 3>>& cuts, uint32_t shape) {
  const int n = 1500;
  double kept = 0, all = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = -1 + (i + 0.5) * 2.0 / n, y = -1 + (j + 0.5) * 2.0 / n, r2 = x * x + y * y;
      if (r2 > 1) continue;
      const double k = shape == PM_KERNEL_EPANECHNIKOV ? 2 * (1 - r2) : 1.0;
      all += k;
      bool in = true;
      for (const auto& c : cuts) in = in && c[0] * x + c[1] * y <= c[2];
      kept += in ? k : 0.0;
    }
  return kept / all;
}

TEST(FootprintClip, KeptKernelMassMatchesNumericalIntegration) {
  const double c30 = std::cos(M_PI / 6), s30 = std::sin(M_PI / 6);
  const std::vector<std::vector<std::array<double, 3>>> cases = {
      {},
      {{1, 0, 0}},
      {{1, 0, 0.5}},
      {{0.6, 0.8, 0.95}},
      {{1, 0, 0.3}, {0, 1, 0.4}},        // a corner
      {{1, 0, 0.0}, {0, -1, 0.0}},       // a corner through the hit: a quarter disc
      {{1, 0, 0.2}, {-1, 0, 0.6}},       // a gap between two walls
      {{c30, s30, 0.2}, {-c30, s30, 0.7}},
      {{1, 0, 0.5}, {0.7071, 0.7071, 0.9}},  // the second cut inside the first one's segment
      {{0, 1, 0.99}, {1, 0, 1.0}}};
  for (uint32_t shape : {uint32_t(PM_KERNEL_CONSTANT), uint32_t(PM_KERNEL_EPANECHNIKOV)}) {
    for (const auto& cuts : cases) {
      float mu[2] = {0, 0}, mv[2] = {0, 0}, t[2] = {1, 1};
      for (size_t k = 0; k < cuts.size(); ++k) {
        mu[k] = float(cuts[k][0]);
        mv[k] = float(cuts[k][1]);
        t[k] = float(cuts[k][2]);
      }
      const double expected = numerical_kept(cuts, shape);
      EXPECT_NEAR(footprint_kept_fraction(mu, mv, t, int(cuts.size()), shape), expected, 3e-4)
          << "kernel " << shape << ", " << cuts.size() << " cuts, first t " << t[0] << ", second t " << t[1];
    }
  }
}

// A floor y = 0 (two triangles) and a wall x = 0 standing on it, facing +x.
Scene floor_and_wall(float wall_height) {
  Scene s;
  s.materials = {MaterialDesc{}};
  test::add_quad(s, {-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, {5, 0, -5});
  test::add_quad(s, {0, 0, -5}, {0, wall_height, -5}, {0, wall_height, 5}, {0, 0, 5});
  return s;
}

TEST(FootprintClip, AFootprintNextToAWallIsCutAtTheWall) {
  test::HostScene scene(floor_and_wall(2.0f));
  const Vec3 hit = vec3(0.3f, 0, 0.1f), up = vec3(0, 1, 0);
  Footprint f = circle(1.0f);
  const FootprintCut cut = footprint_clip(&scene.kg, &f, hit, up, 1e-6f, PM_KERNEL_CONSTANT);
  EXPECT_FLOAT_EQ(f.axis_u.x, 1.0f) << "one wall: no shrink";
  EXPECT_EQ(cut.count, 1);
  EXPECT_NEAR(cut.t[0], 0.3f, 1e-5f);
  EXPECT_NEAR(cut.kept, numerical_kept({{1, 0, 0.3}}, PM_KERNEL_CONSTANT), 3e-4);
  for (float x : {-0.9f, -0.3f, -0.01f}) EXPECT_FALSE(reaches(f, cut, hit, vec3(x, 0, 0.1f))) << x;
  for (float x : {0.001f, 0.3f, 1.2f}) EXPECT_TRUE(reaches(f, cut, hit, vec3(x, 0, 0.1f))) << x;
  // Far from the wall: untouched.
  Footprint g = circle(1.0f);
  const FootprintCut none = footprint_clip(&scene.kg, &g, vec3(2.5f, 0, 0), up, 1e-6f, PM_KERNEL_CONSTANT);
  EXPECT_EQ(none.kept, 1.0f);
  EXPECT_EQ(none.count, 0);
}

// Walls 0.2, 0.3, 0.4, ... away from the hit in N directions 360 / N degrees apart, each one
// vertical triangle: the two nearest are the cuts and the third nearest shrinks the disc, whichever
// wall is nearest. The scan reads a leaf's triangles two at a time (footprint_clip_scan); with the
// nearest wall turned through every position of 1 to 8 triangles, a triangle it skipped would show
// (skipping the second of each pair fails 95 of the checks).
TEST(FootprintClip, EveryTriangleOfALeafIsScanned) {
  const Vec3 hit = vec3(0, 0, 0), up = vec3(0, 1, 0);
  for (int walls = 1; walls <= 8; ++walls) {
    for (int nearest = 0; nearest < walls; ++nearest) {
      Scene s;
      s.materials = {MaterialDesc{}};
      for (int i = 0; i < walls; ++i) {
        const float angle = 2.0f * float(M_PI) * float(i) / float(walls);
        const float d = 0.2f + 0.1f * float((i - nearest + walls) % walls);
        const Float3 foot{d * std::cos(angle), 0.0f, d * std::sin(angle)};
        const Float3 along{-std::sin(angle), 0.0f, std::cos(angle)};
        const uint32_t base = uint32_t(s.positions.size());
        s.positions.push_back({foot.x - 1.5f * along.x, -1.0f, foot.z - 1.5f * along.z});
        s.positions.push_back({foot.x + 1.5f * along.x, -1.0f, foot.z + 1.5f * along.z});
        s.positions.push_back({foot.x, 3.0f, foot.z});
        s.indices.insert(s.indices.end(), {base, base + 1, base + 2});
        s.triangle_material.push_back(0);
      }
      test::HostScene scene(s);
      Footprint f = circle(1.0f);
      const FootprintCut cut = footprint_clip(&scene.kg, &f, hit, up, 1e-6f, PM_KERNEL_CONSTANT);
      const float shrink = walls >= 3 ? 0.4f : 1.0f;
      const std::string where = std::to_string(walls) + " walls, the nearest " + std::to_string(nearest);
      EXPECT_EQ(cut.count, std::min(walls, 2)) << where;
      EXPECT_NEAR(f.axis_u.x, shrink, 1e-5f) << where;
      const float first = std::min(cut.t[0], cut.t[1]), second = std::max(cut.t[0], cut.t[1]);
      EXPECT_NEAR(first, 0.2f / shrink, 1e-4f) << where;
      if (walls >= 2) {
        EXPECT_NEAR(second, 0.3f / shrink, 1e-4f) << where;
      }
    }
  }
}

TEST(FootprintClip, UniformPhotonsKeepTheirDensityUpToTheWall) {
  // Photons on a grid over the floor in front of the wall, each with a unit circle clipped there;
  // the density estimate at distance e from the wall (sum of 1 / (area * kept) over footprints
  // reaching it, times the area per photon) against the one-dimensional profile of a cut disc
  // kernel: 0.693 (ln 2) at the wall's foot, 1 beyond two radii. Unclipped it would be 0.5.
  test::HostScene scene(floor_and_wall(2.0f));
  const float spacing = 0.02f;
  struct Clipped {
    Vec3 hit;
    Footprint f;
    FootprintCut cut;
  };
  std::vector<Clipped> photons;
  for (float x = spacing / 2; x < 3.6f; x += spacing)
    for (float z = -1.5f; z < 1.5f; z += spacing) {
      Clipped c{vec3(x, 0, z), circle(1.0f), {}};
      c.cut = footprint_clip(&scene.kg, &c.f, c.hit, vec3(0, 1, 0), 1e-6f, PM_KERNEL_CONSTANT);
      photons.push_back(c);
    }
  auto density = [&](float e) {
    double sum = 0;
    for (const Clipped& c : photons)
      if (reaches(c.f, c.cut, c.hit, vec3(e, 0, 0))) sum += 1.0 / (footprint_area(c.f) * c.cut.kept);
    return sum * spacing * spacing;
  };
  EXPECT_NEAR(density(0.001f), std::log(2.0), 0.02);
  EXPECT_NEAR(density(2.5f), 1.0, 0.02);
  EXPECT_EQ(density(-0.05f), 0.0) << "behind the wall";
  // The gather's rule (gather_reach.h): each photon divided by the kept mass of its footprint
  // moved to the shading point. The cut line m . q <= t lies t - m . q from the point q: a
  // uniform density comes out exact at the wall's foot too.
  auto density_about = [&](float e) {
    double sum = 0;
    const Vec3 x = vec3(e, 0, 0);
    for (const Clipped& c : photons) {
      if (!reaches(c.f, c.cut, c.hit, x)) continue;
      const Vec3 d = vec3_sub(x, c.hit);
      const float qu = vec3_dot(d, c.f.axis_u) / vec3_dot(c.f.axis_u, c.f.axis_u);
      const float qv = vec3_dot(d, c.f.axis_v) / vec3_dot(c.f.axis_v, c.f.axis_v);
      float t[2];
      for (int k = 0; k < 2; ++k) t[k] = std::max(0.0f, c.cut.t[k] - (c.cut.mu[k] * qu + c.cut.mv[k] * qv));
      sum += 1.0 / (footprint_area(c.f) * footprint_kept_fraction(c.cut.mu, c.cut.mv, t, 2, PM_KERNEL_CONSTANT));
    }
    return sum * spacing * spacing;
  };
  // Measured: 0.9995 at the foot, 0.960 / 0.952 / 0.972 at 0.25 / 0.5 / 0.75 radii (walls
  // beyond a footprint's own radius are not among its cuts, so the footprints a radius or more
  // from the wall count in full), 1.000 from one radius on; each footprint's own kept mass gives
  // 0.693 / 0.856 / 0.999 / 1.099 / 1.122 at 0 / 0.25 / 0.5 / 0.75 / 1 radii.
  for (float e : {0.001f, 0.25f, 0.5f, 0.75f, 1.0f, 1.25f, 1.5f, 2.5f}) {
    std::printf("uniform density %.3f radii from the wall: %.4f (each footprint's own kept mass: %.4f)\n", e,
                density_about(e), density(e));
    EXPECT_NEAR(density_about(e), 1.0, 0.05) << e << " radii from the wall";
  }
  EXPECT_NEAR(density_about(0.001f), 1.0, 0.02);
}

TEST(FootprintClip, OneCutInClosedFormEqualsTheGreenIntegral) {
  for (uint32_t shape : {uint32_t(PM_KERNEL_CONSTANT), uint32_t(PM_KERNEL_EPANECHNIKOV)})
    for (float t = 0.0f; t < 1.0f; t += 0.03125f) {
      float mu[2] = {0.6f, 0}, mv[2] = {0.8f, 0}, tt[2] = {t, 1};
      EXPECT_NEAR(footprint_kept_one_cut(t, shape), footprint_kept_fraction(mu, mv, tt, 2, shape), 2e-5)
          << "kernel " << shape << ", t " << t;
    }
  EXPECT_NEAR(footprint_kept_one_cut(0.0f, PM_KERNEL_CONSTANT), 0.5f, 1e-6);
  EXPECT_NEAR(footprint_kept_one_cut(1.0f, PM_KERNEL_EPANECHNIKOV), 1.0f, 1e-6);
}

TEST(FootprintClip, CoplanarNeighboursLowWallsAndGentleCurvesLeaveFootprintsAlone) {
  // A floor of many small triangles: none crosses the lifted plane.
  Scene tiles;
  tiles.materials = {MaterialDesc{}};
  for (int i = -10; i < 10; ++i)
    for (int j = -10; j < 10; ++j)
      test::add_quad(tiles, {i * 0.1f, 0, j * 0.1f}, {i * 0.1f, 0, (j + 1) * 0.1f}, {(i + 1) * 0.1f, 0, (j + 1) * 0.1f},
                     {(i + 1) * 0.1f, 0, j * 0.1f});
  test::HostScene tiled(tiles);
  Footprint f = circle(0.5f);
  EXPECT_EQ(footprint_clip(&tiled.kg, &f, vec3(0.05f, 0, 0.02f), vec3(0, 1, 0), 1e-6f, PM_KERNEL_CONSTANT).kept, 1.0f);
  // A wall lower than the lifted plane (half of the normal half-axis: 0.125 here) is not seen.
  test::HostScene low(floor_and_wall(0.05f));
  Footprint g = circle(0.5f);
  EXPECT_EQ(footprint_clip(&low.kg, &g, vec3(0.2f, 0, 0), vec3(0, 1, 0), 1e-6f, PM_KERNEL_CONSTANT).kept, 1.0f);
  // Inside a sphere of radius R = 2 the surface rises into the lifted plane (height h = half the
  // normal half-axis, a quarter of the footprint's radius) at about sqrt(2 R h) from the hit: a
  // footprint of radius 0.3 (0.55, beyond its rim) is left whole; one of 1.5 (1.22) is cut.
  static_assert(PM_FOOTPRINT_NORMAL_RATIO == 0.5f && PM_FOOTPRINT_CLIP_HEIGHT == 0.5f, "distances above assume these");
  test::HostScene sphere(test::diffuse_sphere(2.0f, 0.5f, 5, {1, 1, 1}));
  const Vec3 bottom = vec3(0, -1.9995f, 0), in = vec3(0, 1, 0);
  Footprint small = circle(0.3f), large = circle(1.5f);
  EXPECT_EQ(footprint_clip(&sphere.kg, &small, bottom, in, 1e-6f, PM_KERNEL_CONSTANT).kept, 1.0f);
  const FootprintCut cut = footprint_clip(&sphere.kg, &large, bottom, in, 1e-6f, PM_KERNEL_CONSTANT);
  EXPECT_TRUE(cut.kept < 1.0f || large.axis_u.x < 1.5f);
}

}  // namespace
}  // namespace pm

// Unit tests of the footprint coverage's probes (kernels/common/footprint_coverage.h) on the host,
// with the scene BVH the device uses: probes that test only the scene leaves found in the
// footprint's box (scene_box_leaves, scene_traverse.h) meet exactly what probes traversing the
// whole BVH meet, for footprints of every size at random points of real geometry, and the box
// query finds every triangle a ray inside the box can hit.
#include "kernels/common/compat_host.h"
#include "kernels/common/footprint_coverage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "render/scene_bvh.h"
#include "scene_io/cornell_box.h"
#include "support/analytic_scenes.h"
#include "support/room_scenes.h"

namespace pm {
namespace {

struct HostScene {
  SceneBvh bvh;
  KernelGlobals kg{};
  explicit HostScene(const Scene& scene) : bvh(build_scene_bvh(scene)) {
    kg.scene_nodes = bvh.nodes.data();
    kg.triangles = bvh.triangles.data();
  }
  int triangle_count() const { return int(bvh.triangles.size() / 3); }
};

// A random point on triangle t (leaf order) and its unit normal.
void random_surface_point(const HostScene& s, int t, std::mt19937& rng, Vec3* p, Vec3* n) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  float a = u(rng), b = u(rng);
  if (a + b > 1) {
    a = 1 - a;
    b = 1 - b;
  }
  const Vec3 v0 = scene_triangle_vertex(s.kg.triangles, t, 0), v1 = scene_triangle_vertex(s.kg.triangles, t, 1),
             v2 = scene_triangle_vertex(s.kg.triangles, t, 2);
  *p = vec3_add(v0, vec3_add(vec3_scale(vec3_sub(v1, v0), a), vec3_scale(vec3_sub(v2, v0), b)));
  *n = vec3_normalize(scene_triangle_normal(s.kg.triangles, t));
}

// Checks the probes of random footprints on `scene`: covered and kept weights from the leaves in
// the box equal those from whole-BVH traversals. Returns how many boxes held few enough leaves.
int check_probes_in_box(const Scene& scene, float smallest, float largest) {
  const HostScene s(scene);
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> pick(0, s.triangle_count() - 1);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int in_box = 0;
  for (int i = 0; i < 400; ++i) {
    Vec3 center, n, t, b;
    random_surface_point(s, pick(rng), rng, &center, &n);
    vec3_onb(n, &t, &b);
    const float radius = smallest * std::pow(largest / smallest, u(rng));
    Footprint f;
    f.axis_u = vec3_scale(t, radius * (0.5f + u(rng)));
    f.axis_v = vec3_scale(b, radius);
    f.axis_n = vec3_scale(n, radius * (u(rng) < 0.5f ? 0.5f : 1.0f));
    const float offset = 1e-4f, turn = 6.283f * u(rng);
    const Vec3 wi = vec3_normalize(vec3_add(n, vec3(0.3f * u(rng), 0.3f * u(rng), 0.3f * u(rng))));
    const FootprintCut cut = footprint_uncut();
    Vec3 thick = vec3_scale(n, vec3_length(f.axis_n) + offset);
    Vec3 ext = vec3(std::sqrt(f.axis_u.x * f.axis_u.x + f.axis_v.x * f.axis_v.x) + std::fabs(thick.x) + offset,
                    std::sqrt(f.axis_u.y * f.axis_u.y + f.axis_v.y * f.axis_v.y) + std::fabs(thick.y) + offset,
                    std::sqrt(f.axis_u.z * f.axis_u.z + f.axis_v.z * f.axis_v.z) + std::fabs(thick.z) + offset);
    const SceneBoxLeaves box = scene_box_leaves(&s.kg, vec3_sub(center, ext), vec3_add(center, ext));
    SceneBoxLeaves whole;
    whole.count = -1;
    in_box += box.count >= 0;
    for (uint mode : {PM_COVERAGE_CELLS, PM_COVERAGE_SURFACE_AREA, PM_COVERAGE_LIT_AREA}) {
      float kept_box, covered_box, kept_all, covered_all;
      uint probes_box, probes_all;
      footprint_probe_pattern(&s.kg, &box, &f, &cut, center, n, offset, turn, PM_KERNEL_CONSTANT, mode, wi,
                              PM_FOOTPRINT_EDGE_PROBES, &kept_box, &covered_box, &probes_box);
      footprint_probe_pattern(&s.kg, &whole, &f, &cut, center, n, offset, turn, PM_KERNEL_CONSTANT, mode, wi,
                              PM_FOOTPRINT_EDGE_PROBES, &kept_all, &covered_all, &probes_all);
      EXPECT_EQ(kept_box, kept_all);
      EXPECT_EQ(covered_box, covered_all) << "footprint " << i << " of radius " << radius << ", mode " << mode
                                          << ", " << box.count << " leaves in its box";
    }
  }
  return in_box;
}

TEST(FootprintProbes, TheLeavesInTheFootprintsBoxMeetWhatTheWholeBvhMeets) {
  // The Cornell box (large walls, two blocks) with footprints from 1 cm to 40 cm, the room (a block
  // on the floor, walls meeting at corners) from 5 cm to 1.5 m, and the inside of a finely
  // tessellated sphere, whose larger footprints find more than PM_SCENE_BOX_LEAVES leaves in
  // their box and traverse the BVH instead.
  const int cornell = check_probes_in_box(builtin_cornell_box(), 0.01f, 0.4f);
  const int room = check_probes_in_box(test::closed_room(), 0.05f, 1.5f);
  const int sphere = check_probes_in_box(test::diffuse_sphere(1.0f, 0.5f, 4, {1, 1, 1}), 0.01f, 0.5f);
  EXPECT_GT(cornell, 100);
  EXPECT_GT(room, 100);
  EXPECT_GT(sphere, 50);
  EXPECT_LT(sphere, 350) << "few footprints fell back to the whole BVH";
}

}  // namespace
}  // namespace pm

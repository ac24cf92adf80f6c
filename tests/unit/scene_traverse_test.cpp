// Host tests of the shared ray kernels (kernels/common/ray.h, scene_traverse.h): the
// watertight triangle test against a double-precision reference, no cracks along shared edges,
// robust offsets, and BVH traversal against brute force over the same triangles.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "render/kernel_abi.h"
#include "render/scene_bvh.h"
#include "render/scene_scale.h"
#include "kernels/common/scene_traverse.h"

namespace pm {
namespace {

// Moeller-Trumbore in double precision: an independent reference for hit distances.
bool reference_hit(Vec3 o, Vec3 d, Vec3 a, Vec3 b, Vec3 c, double* t_out) {
  double e1[3] = {double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z};
  double e2[3] = {double(c.x) - a.x, double(c.y) - a.y, double(c.z) - a.z};
  double dd[3] = {d.x, d.y, d.z};
  double p[3] = {dd[1] * e2[2] - dd[2] * e2[1], dd[2] * e2[0] - dd[0] * e2[2], dd[0] * e2[1] - dd[1] * e2[0]};
  double det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
  if (std::fabs(det) < 1e-12) return false;
  double s[3] = {double(o.x) - a.x, double(o.y) - a.y, double(o.z) - a.z};
  double u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) / det;
  double q[3] = {s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2], s[0] * e1[1] - s[1] * e1[0]};
  double v = (dd[0] * q[0] + dd[1] * q[1] + dd[2] * q[2]) / det;
  double t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
  if (u < 0 || v < 0 || u + v > 1 || t <= 0) return false;
  *t_out = t;
  return true;
}

Vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<float> n(0.0f, 1.0f);
  return vec3_normalize(vec3(n(rng), n(rng), n(rng)));
}

TEST(RayTriangle, MatchesDoublePrecisionReferenceAwayFromEdges) {
  // Rays aimed at barycentric points clearly inside must hit at the reference distance; rays
  // aimed clearly outside one edge must miss. Both sides of the triangle are tested.
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), w(0.05f, 0.9f);
  for (int i = 0; i < 20000; ++i) {
    Vec3 a = vec3(u(rng), u(rng), u(rng)), b = vec3(u(rng), u(rng), u(rng)), c = vec3(u(rng), u(rng), u(rng));
    float wa = w(rng), wb = w(rng), wc = w(rng);
    bool inside = i % 2 == 0;
    if (!inside) wa = -wa;  // beyond the edge bc
    float sum = wa + wb + wc;
    Vec3 target = vec3_scale(vec3_add(vec3_scale(a, wa), vec3_add(vec3_scale(b, wb), vec3_scale(c, wc))), 1.0f / sum);
    Vec3 o = vec3_scale(vec3(u(rng), u(rng), u(rng)), 3.0f);
    Vec3 to = vec3_sub(target, o);
    if (vec3_length(to) < 0.1f) continue;
    Ray ray = ray_make(o, vec3_normalize(to));
    double t_ref = 0;
    bool ref = reference_hit(o, ray.direction, a, b, c, &t_ref);
    float t = 0;
    bool got = ray_triangle(&ray, a, b, c, 0.0f, 1e30f, &t);
    ASSERT_EQ(got, ref) << "ray " << i;
    if (inside && std::fabs(vec3_dot(vec3_normalize(vec3_cross(vec3_sub(b, a), vec3_sub(c, a))), ray.direction)) > 0.05f) {
      ASSERT_TRUE(got) << "ray " << i;
    }
    if (got) {
      EXPECT_NEAR(t, t_ref, 1e-4 * (1.0 + t_ref));
    }
  }
}

TEST(RayTriangle, NoRayPassesThroughTheSharedEdgeOfTwoTriangles) {
  // A quad split along its diagonal; rays aimed exactly at points of the diagonal.
  Vec3 a = vec3(0, 0, 0), b = vec3(1, 0, 0), c = vec3(1, 1, 0), d = vec3(0, 1, 0);
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 20000; ++i) {
    float s = u(rng);
    Vec3 target = vec3(s, s, 0.0f);
    Vec3 origin = vec3(u(rng) * 4 - 2, u(rng) * 4 - 2, 1.0f + u(rng));
    Ray ray = ray_make(origin, vec3_normalize(vec3_sub(target, origin)));
    float t;
    bool first = ray_triangle(&ray, a, b, c, 0.0f, 1e30f, &t);
    bool second = ray_triangle(&ray, a, c, d, 0.0f, 1e30f, &t);
    ASSERT_TRUE(first || second) << "crack at s=" << s;
  }
}

// Secondary rays leave the surface a hit was computed on (o + t d, with its rounding) and never
// hit it again: on a plane through the world origin (where an absolute offset is too small for a
// large scene) and on tilted triangles far from it, at scene sizes from 1e-4 to 1e6 m; and the
// offset stays a negligible fraction of the scene.
TEST(RayOffset, SecondaryRaysDoNotHitTheirOwnSurfaceAtAnyScale) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (float size : {1e-4f, 1e-2f, 1.0f, 1e3f, 1e6f}) {
    struct Case {
      Vec3 a, b, c;
    };
    const Case cases[] = {
        {vec3(-size, 0, -size), vec3(size, 0, -size), vec3(0, 0, 2 * size)},  // on y = 0, around the origin
        {vec3(0, 0, 0), vec3(size, 0.1f * size, 0), vec3(0.2f * size, size, 0.3f * size)},
        {vec3(7 * size, 3 * size, 11 * size), vec3(8 * size, 3.1f * size, 11 * size),
         vec3(7.2f * size, 4 * size, 11.3f * size)}};
    for (const Case& tri : cases) {
      Scene scene;
      scene.positions = {{tri.a.x, tri.a.y, tri.a.z}, {tri.b.x, tri.b.y, tri.b.z}, {tri.c.x, tri.c.y, tri.c.z}};
      scene.indices = {0, 1, 2};
      const float scene_epsilon = scene_ray_epsilon(scene);
      Vec3 n = vec3_normalize(vec3_cross(vec3_sub(tri.b, tri.a), vec3_sub(tri.c, tri.a)));
      int hits = 0;
      for (int i = 0; i < 2000; ++i) {
        // A target inside the triangle, half of them within 1e-3 of its size of a vertex.
        float s = u(rng) * 0.5f, t = u(rng) * 0.5f;
        if (i % 2) s *= 1e-3f, t *= 1e-3f;
        Vec3 target = vec3_add(tri.a, vec3_add(vec3_scale(vec3_sub(tri.b, tri.a), s), vec3_scale(vec3_sub(tri.c, tri.a), t)));
        Vec3 from = vec3_add(target, vec3_scale(random_unit(rng), size * (0.1f + 2.0f * u(rng))));
        Ray eye = ray_make(from, vec3_normalize(vec3_sub(target, from)));
        float hit_t;
        if (!ray_triangle(&eye, tri.a, tri.b, tri.c, 0.0f, 1e30f, &hit_t)) continue;
        ++hits;
        Vec3 p = vec3_madd(eye.origin, eye.direction, hit_t);
        Vec3 side = vec3_dot(n, eye.direction) < 0 ? n : vec3_neg(n);
        const float offset = ray_offset_distance(eye.origin, hit_t, scene_epsilon);
        EXPECT_LT(offset, 2e-4f * (size + vec3_max_abs(p))) << "size " << size;
        Vec3 dir = random_unit(rng);
        if (vec3_dot(dir, side) < 0) dir = vec3_neg(dir);
        Ray secondary = ray_make(offset_ray_origin(p, side, offset), dir);
        ASSERT_FALSE(ray_triangle(&secondary, tri.a, tri.b, tri.c, 0.0f, 1e30f, &hit_t))
            << "size " << size << ", target " << target.x << " " << target.y << " " << target.z;
      }
      EXPECT_GT(hits, 1500) << "size " << size;
    }
  }
}

Scene random_soup(int triangles, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos(-10.0f, 10.0f), off(-1.0f, 1.0f);
  Scene scene;
  for (int i = 0; i < triangles; ++i) {
    Float3 centre{pos(rng), pos(rng), pos(rng)};
    for (int k = 0; k < 3; ++k) {
      scene.positions.push_back({centre.x + off(rng), centre.y + off(rng), centre.z + off(rng)});
      scene.indices.push_back(uint32_t(scene.positions.size() - 1));
    }
    scene.triangle_material.push_back(uint32_t(i % 3));
  }
  return scene;
}

// The kernels' view of a BVH's geometry: no material has a mask, so traversal reads nothing else.
KernelGlobals geometry_of(SceneBvh& bvh) {
  KernelGlobals kg{};
  kg.scene_nodes = bvh.nodes.data();
  kg.triangles = bvh.triangles.data();
  return kg;
}

// The textbook traversal in one loop, a node's leaf children intersected as soon as they are met:
// the order scene_trace_from's two loops must keep.
SceneHit one_loop_trace(const KernelGlobals& kg, const Ray& ray, float t_max, bool any_hit) {
  SceneHit hit{t_max, -1};
  std::vector<int> stack;
  int node = 0;
  for (;;) {
    const float4* n = &kg.scene_nodes[4 * node];
    const int child[2] = {PM_AS_INT(n[3].x), PM_AS_INT(n[3].y)}, count[2] = {PM_AS_INT(n[3].z), PM_AS_INT(n[3].w)};
    const float t[2] = {ray_box_entry(&ray, vec3(n[0].x, n[0].z, n[2].x), vec3(n[0].y, n[0].w, n[2].y), hit.t),
                        ray_box_entry(&ray, vec3(n[1].x, n[1].z, n[2].z), vec3(n[1].y, n[1].w, n[2].w), hit.t)};
    bool visit[2];
    for (int c = 0; c < 2; ++c) {
      visit[c] = t[c] < 1e38f && child[c] >= 0;
      if (visit[c] && count[c] > 0) {
        if (scene_intersect_leaf(&kg, &ray, child[c], count[c], 0.0f, &hit) && any_hit) return hit;
        visit[c] = false;
      }
    }
    for (int c = 0; c < 2; ++c) visit[c] = visit[c] && t[c] < hit.t;
    if (visit[0] && visit[1]) {
      const int near_side = t[0] <= t[1] ? 0 : 1;
      stack.push_back(child[1 - near_side]);
      node = child[near_side];
    } else if (visit[0] || visit[1]) {
      node = child[visit[0] ? 0 : 1];
    } else {
      if (stack.empty()) break;
      node = stack.back();
      stack.pop_back();
    }
  }
  return hit;
}

TEST(SceneTraverse, ClosestHitEqualsBruteForceInTheOrderOfOneLoop) {
  // The closest hit is brute force's; and scene_trace_from, which walks inner nodes until one has
  // a leaf to intersect (scene_traverse.h), meets the leaves in the order of one loop: the same
  // closest hit to the bit and, for shadow rays, the same first hit, which tells the order (an
  // any-hit traversal returns the first triangle it meets).
  Scene scene = random_soup(3000, 4);
  SceneBvh bvh = build_scene_bvh(scene);
  const KernelGlobals kg = geometry_of(bvh);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> pos(-12.0f, 12.0f);
  int hits = 0, first_hit_not_closest = 0;
  for (int i = 0; i < 3000; ++i) {
    Ray ray = ray_make(vec3(pos(rng), pos(rng), pos(rng)), random_unit(rng));
    SceneHit traversed = scene_trace(&kg, &ray, 0.0f, 1e30f, 0);
    SceneHit brute;
    brute.t = 1e30f;
    brute.triangle = -1;
    scene_intersect_leaf(&kg, &ray, 0, int(bvh.triangle_count()), 0.0f, &brute);
    ASSERT_EQ(traversed.triangle, brute.triangle) << "ray " << i;
    if (brute.triangle >= 0) {
      EXPECT_EQ(traversed.t, brute.t);
      ++hits;
    }
    const SceneHit one_loop = one_loop_trace(kg, ray, 1e30f, false);
    ASSERT_EQ(traversed.triangle, one_loop.triangle) << "ray " << i;
    EXPECT_EQ(traversed.t, one_loop.t) << "ray " << i;
    SceneHit any = scene_trace(&kg, &ray, 0.0f, 1e30f, 1);
    EXPECT_EQ(any.triangle >= 0, brute.triangle >= 0);
    ASSERT_EQ(any.triangle, one_loop_trace(kg, ray, 1e30f, true).triangle) << "ray " << i;
    first_hit_not_closest += any.triangle != traversed.triangle;
  }
  EXPECT_GT(hits, 500);
  EXPECT_GT(first_hit_not_closest, 20);  // shadow rays that stop before the closest hit: the order shows
}

TEST(SceneTraverse, ShortRaysFindFromTheNodeHoldingTheirBoxWhatTheyFindFromTheRoot) {
  // Segments of random direction inside small boxes about random points of a dense soup: traced
  // from scene_node_holding's node, the closest hit is the root's, bit for bit, and the node is
  // below the root for most boxes.
  Scene scene = random_soup(20000, 6);
  SceneBvh bvh = build_scene_bvh(scene);
  const KernelGlobals kg = geometry_of(bvh);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> pos(-10.0f, 10.0f), unit(0.0f, 1.0f);
  int hits = 0, below_root = 0;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 centre = vec3(pos(rng), pos(rng), pos(rng));
    const float half = 0.05f + 0.5f * unit(rng);
    const Vec3 lo = vec3_sub(centre, vec3_splat(half)), hi = vec3_add(centre, vec3_splat(half));
    const int node = scene_node_holding(&kg, lo, hi);
    below_root += node != 0;
    // A segment from one point of the box to another.
    const Vec3 a = vec3(lo.x + 2 * half * unit(rng), lo.y + 2 * half * unit(rng), lo.z + 2 * half * unit(rng));
    const Vec3 b = vec3(lo.x + 2 * half * unit(rng), lo.y + 2 * half * unit(rng), lo.z + 2 * half * unit(rng));
    const float length = vec3_length(vec3_sub(b, a));
    if (!(length > 0.0f)) continue;
    Ray ray = ray_make(a, vec3_scale(vec3_sub(b, a), 1.0f / length));
    const SceneHit from_root = scene_trace(&kg, &ray, 0.0f, length, 0);
    const SceneHit from_node = scene_trace_from(&kg, node, &ray, 0.0f, length, 0);
    ASSERT_EQ(from_node.triangle, from_root.triangle) << "segment " << i << " from node " << node;
    EXPECT_EQ(from_node.t, from_root.t);
    hits += from_root.triangle >= 0;
  }
  EXPECT_GT(hits, 200);
  EXPECT_GT(below_root, 3000);
}

TEST(SceneTraverse, AxisAlignedRaysHitFlatWalls) {
  // A wall in the plane z = 5, hit by rays with exactly zero x and y direction components.
  Scene scene;
  scene.positions = {{-1, -1, 5}, {1, -1, 5}, {1, 1, 5}, {-1, 1, 5}};
  scene.indices = {0, 1, 2, 0, 2, 3};
  scene.triangle_material = {0, 0};
  SceneBvh bvh = build_scene_bvh(scene);
  const KernelGlobals kg = geometry_of(bvh);
  for (float x = -0.9f; x < 0.9f; x += 0.1f) {
    Ray ray = ray_make(vec3(x, 0.3f, 0.0f), vec3(0.0f, 0.0f, 1.0f));
    SceneHit hit = scene_trace(&kg, &ray, 0.0f, 1e30f, 0);
    ASSERT_GE(hit.triangle, 0) << "x=" << x;
    EXPECT_FLOAT_EQ(hit.t, 5.0f);
  }
}

}  // namespace
}  // namespace pm

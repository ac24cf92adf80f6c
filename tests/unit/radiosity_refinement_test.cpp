// Host tests of the radiosity mesh refinement (render/radiosity/mesh_refinement.h) and of the
// device's point location in it (kernels/common/radiosity_mesh.h radiosity_locate): every edge
// within max_edge, area and winding kept, no T-junctions, and every point of an original
// triangle found in the refined triangle that contains it.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "kernels/common/compat_host.h"
#include "kernels/common/radiosity_mesh.h"
#include "render/errors.h"
#include "render/radiosity/mesh_refinement.h"
#include "support/analytic_scenes.h"
#include "support/radiosity_meshes.h"

namespace pm {
namespace {

double edge_length(const Float3& a, const Float3& b) {
  return std::sqrt(double(a.x - b.x) * (a.x - b.x) + double(a.y - b.y) * (a.y - b.y) + double(a.z - b.z) * (a.z - b.z));
}

Vec3 v3(const Float3& p) { return vec3(p.x, p.y, p.z); }

double area_of(const Float3& a, const Float3& b, const Float3& c) {
  return 0.5 * vec3_length(vec3_cross(vec3_sub(v3(b), v3(a)), vec3_sub(v3(c), v3(a))));
}

// A long thin triangle, a large right triangle and a small one that needs no refinement.
Scene mixed_triangles() {
  Scene s;
  s.name = "mixed";
  s.source = "test";
  s.positions = {{0, 0, 0}, {4, 0, 0}, {0, 0.3f, 0}, {0, 0, 1}, {2, 0, 1}, {0, 2, 1}, {5, 5, 5}, {5.1f, 5, 5}, {5, 5.1f, 5}};
  s.indices = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  s.triangle_material.assign(3, 0);
  s.materials = {test::grey_material(0.5f)};
  return s;
}

TEST(RadiosityRefinement, EdgesAreaWindingAndConformity) {
  for (const Scene& scene : {mixed_triangles(), test::folded_sheet(2.0f, 1.5f, 90.0f), test::closed_cube(1.0f)}) {
    const double max_edge = 0.23;
    RefinedMesh mesh = refine_mesh(scene, max_edge);
    ASSERT_EQ(mesh.source.size(), mesh.triangle_count());
    std::vector<double> area(scene.triangle_count(), 0.0);
    std::map<std::pair<uint32_t, uint32_t>, int> edges;
    for (size_t r = 0; r < mesh.triangle_count(); ++r) {
      const uint32_t* v = &mesh.indices[3 * r];
      const uint32_t t = mesh.source[r];
      for (int k = 0; k < 3; ++k) {
        EXPECT_LE(edge_length(mesh.positions[v[k]], mesh.positions[v[(k + 1) % 3]]), max_edge * (1 + 1e-6));
        edges[std::minmax(v[k], v[(k + 1) % 3])]++;
      }
      area[t] += area_of(mesh.positions[v[0]], mesh.positions[v[1]], mesh.positions[v[2]]);
      // Same winding as the original triangle.
      const Float3* o[3] = {&scene.positions[scene.indices[3 * t]], &scene.positions[scene.indices[3 * t + 1]],
                            &scene.positions[scene.indices[3 * t + 2]]};
      Vec3 n_orig = vec3_cross(vec3_sub(v3(*o[1]), v3(*o[0])), vec3_sub(v3(*o[2]), v3(*o[0])));
      Vec3 n_ref = vec3_cross(vec3_sub(v3(mesh.positions[v[1]]), v3(mesh.positions[v[0]])),
                              vec3_sub(v3(mesh.positions[v[2]]), v3(mesh.positions[v[0]])));
      EXPECT_GT(vec3_dot(n_orig, n_ref), 0.0f);
    }
    for (size_t t = 0; t < scene.triangle_count(); ++t) {
      const double a = area_of(scene.positions[scene.indices[3 * t]], scene.positions[scene.indices[3 * t + 1]],
                               scene.positions[scene.indices[3 * t + 2]]);
      EXPECT_NEAR(area[t], a, 1e-5 * a) << scene.name << " triangle " << t;
    }
    // Conforming: an edge is shared by at most two triangles, and no vertex lies inside another
    // triangle's edge (a T-junction).
    for (const auto& [edge, count] : edges) {
      EXPECT_LE(count, 2);
      const Float3 &a = mesh.positions[edge.first], &b = mesh.positions[edge.second];
      const double len = edge_length(a, b);
      for (size_t v = 0; v < mesh.positions.size(); ++v) {
        if (v == edge.first || v == edge.second) continue;
        const double detour = edge_length(a, mesh.positions[v]) + edge_length(mesh.positions[v], b) - len;
        EXPECT_GT(detour, 1e-6 * len) << scene.name << ": vertex " << v << " on edge " << edge.first << "-" << edge.second;
      }
    }
    EXPECT_LE(double(mesh.triangle_count()), estimate_refined_triangles(scene, max_edge));
  }
}

TEST(RadiosityRefinement, UnrefinedMeshIsWeldedAndUnchanged) {
  Scene cube = test::closed_cube(1.0f);
  // Unweld it: every triangle its own three vertices.
  Scene split = cube;
  split.positions.clear();
  split.indices.clear();
  for (uint32_t i : cube.indices) {
    split.indices.push_back(uint32_t(split.positions.size()));
    split.positions.push_back(cube.positions[i]);
  }
  RefinedMesh mesh = refine_mesh(split, 10.0);
  EXPECT_EQ(mesh.welded_vertices, 8u);
  EXPECT_EQ(mesh.positions.size(), 8u);
  EXPECT_EQ(mesh.triangle_count(), 12u);
  EXPECT_EQ(mesh.depth, 0);
}

TEST(RadiosityRefinement, LocateFindsTheRefinedTriangleHoldingThePoint) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (const Scene& scene : {mixed_triangles(), test::diffuse_sphere(1.0f, 0.5f, 1, {1, 1, 1})}) {
    RefinedMesh mesh = refine_mesh(scene, 0.17);
    ASSERT_GT(mesh.triangle_count(), scene.triangle_count());
    for (size_t t = 0; t < scene.triangle_count(); ++t) {
      const Vec3 a = v3(scene.positions[scene.indices[3 * t]]), b = v3(scene.positions[scene.indices[3 * t + 1]]),
                 c = v3(scene.positions[scene.indices[3 * t + 2]]);
      for (int i = 0; i < 200; ++i) {
        float u = uniform(rng), v = uniform(rng);
        if (u + v > 1) { u = 1 - u; v = 1 - v; }
        if (i == 0) { u = 0.5f; v = 0.0f; }  // exactly on an edge
        const Vec3 x = vec3_add(vec3_add(vec3_scale(a, 1 - u - v), vec3_scale(b, u)), vec3_scale(c, v));
        float bu, bv;
        triangle_barycentrics(x, a, b, c, &bu, &bv);
        EXPECT_NEAR(bu, u, 1e-5f);
        EXPECT_NEAR(bv, v, 1e-5f);
        RadiosityLocation loc = radiosity_locate(mesh.tree.data(), uint32_t(t), bu, bv);
        ASSERT_LT(loc.triangle, mesh.triangle_count());
        EXPECT_EQ(mesh.source[loc.triangle], t);
        // The weights rebuild the point from the refined triangle's corners.
        Vec3 rebuilt = vec3_splat(0.0f);
        for (int k = 0; k < 3; ++k) rebuilt = vec3_madd(rebuilt, v3(mesh.positions[mesh.indices[3 * loc.triangle + k]]), loc.w[k]);
        EXPECT_LT(vec3_length(vec3_sub(rebuilt, x)), 1e-5f) << "triangle " << t << " point " << i;
        EXPECT_NEAR(loc.w[0] + loc.w[1] + loc.w[2], 1.0f, 1e-6f);
      }
    }
  }
}

TEST(RadiosityRefinement, RefusesAMaxEdgeFarTooSmall) {
  Scene big = test::folded_sheet(100.0f, 100.0f, 90.0f);
  EXPECT_GT(estimate_refined_triangles(big, 0.01), double(kMaxRefinedTriangles));
  EXPECT_THROW(refine_mesh(big, 0.0), SettingError);
}

}  // namespace
}  // namespace pm

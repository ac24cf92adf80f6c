// Host tests of the radiosity elements (render/radiosity/radiosity_elements.h): vertices split
// where normals differ by more than the feature angle, by side and by material; normals of
// smooth surfaces averaged; one-rings and smoothing neighbours that stay on their side of
// feature edges; Morton order keeps every index consistent.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "render/radiosity/mesh_refinement.h"
#include "render/radiosity/radiosity_elements.h"
#include "support/analytic_scenes.h"
#include "support/radiosity_meshes.h"

namespace pm {
namespace {

double dot(const Float3& a, const Float3& b) { return double(a.x) * b.x + double(a.y) * b.y + double(a.z) * b.z; }

TEST(RadiosityElements, CubeCornersSplitIntoThreeElementsPerSide) {
  Scene cube = test::closed_cube(1.0f);
  RefinedMesh mesh = refine_mesh(cube, 10.0);
  RadiosityElements one = build_radiosity_elements(cube, mesh, 40.0f, false);
  RadiosityElements two = build_radiosity_elements(cube, mesh, 40.0f, true);
  EXPECT_EQ(one.count(), 24u);
  EXPECT_EQ(two.count(), 48u);
  EXPECT_EQ(one.vertices_with_elements, 8u);
  for (size_t e = 0; e < one.count(); ++e) {
    const Float3 n = one.normal(e), p = one.position(e);
    // Axis-aligned and pointing out of the cube (away from its centre along that axis).
    EXPECT_NEAR(std::fabs(n.x) + std::fabs(n.y) + std::fabs(n.z), 1.0, 1e-6);
    const Float3 from_centre{p.x - 0.5f, p.y - 0.5f, p.z - 0.5f};
    EXPECT_GT(dot(n, from_centre), 0.0);
  }
  // A feature angle above 90 degrees merges the three faces at each corner.
  RadiosityElements merged = build_radiosity_elements(cube, mesh, 100.0f, false);
  EXPECT_EQ(merged.count(), 8u);
}

TEST(RadiosityElements, SmoothSphereHasOneElementPerVertexWithRadialNormals) {
  Scene sphere = test::diffuse_sphere(2.0f, 0.5f, 2, {1, 1, 1});
  RefinedMesh mesh = refine_mesh(sphere, 10.0);
  RadiosityElements el = build_radiosity_elements(sphere, mesh, 40.0f, true);
  ASSERT_EQ(el.count(), 2 * mesh.positions.size());
  for (size_t e = 0; e < el.count(); ++e) {
    const Float3 p = el.position(e), n = el.normal(e);
    const double cos_radial = dot(n, p) / std::sqrt(dot(p, p));
    // Front elements face the centre (the sphere's triangles face inwards), back ones outwards.
    EXPECT_NEAR(cos_radial, el.back[e] ? 1.0 : -1.0, 2e-3);
  }
}

TEST(RadiosityElements, MaterialBoundariesSplitVertices) {
  Scene flat = test::folded_sheet(1.0f, 1.0f, 0.0f);
  flat.materials.push_back(test::grey_material(0.2f));
  flat.triangle_material = {0, 0, 1, 1};  // the two rectangles in different materials
  RefinedMesh mesh = refine_mesh(flat, 10.0);
  EXPECT_EQ(build_radiosity_elements(flat, mesh, 40.0f, false).count(), 8u);  // 6 vertices, 2 on the boundary twice
  flat.triangle_material = {0, 0, 0, 0};
  EXPECT_EQ(build_radiosity_elements(flat, mesh, 40.0f, false).count(), 6u);
}

TEST(RadiosityElements, RingsAndNeighboursAreConsistentAndStayOnTheirSide) {
  Scene fold = test::folded_sheet(1.0f, 1.0f, 90.0f);
  RefinedMesh mesh = refine_mesh(fold, 0.2);
  RadiosityElements el = build_radiosity_elements(fold, mesh, 40.0f, true);
  const size_t n = el.count();
  ASSERT_EQ(el.ranges.size(), n + 1);
  for (size_t e = 0; e < n; ++e) {
    // Every one-ring triangle has this element at the named corner, on the element's side.
    ASSERT_LT(el.ranges[e].x, el.ranges[e + 1].x) << "element " << e << " has no one-ring";
    for (uint32_t i = el.ranges[e].x; i < el.ranges[e + 1].x; ++i) {
      const uint32_t r = el.adjacency[i] >> 2, k = el.adjacency[i] & 3u;
      const uint4 side = el.triangles[2 * r + (el.back[e] ? 1 : 0)];
      const uint32_t corner[3] = {side.x, side.y, side.z};
      EXPECT_EQ(corner[k], e);
      EXPECT_EQ(mesh.indices[3 * r + k], el.vertex[e]);
    }
    // Neighbours: distinct, not itself, same side, normals within the feature angle.
    std::set<uint32_t> seen;
    for (uint32_t i = el.ranges[e].y; i < el.ranges[e + 1].y; ++i) {
      const uint32_t other = el.adjacency[i];
      ASSERT_LT(other, n);
      EXPECT_NE(other, e);
      EXPECT_TRUE(seen.insert(other).second);
      EXPECT_EQ(el.back[other], el.back[e]);
      EXPECT_GT(dot(el.normal(other), el.normal(e)), std::cos(40.0 * M_PI / 180.0));
    }
  }
  // Vertices on the fold line carry one element per rectangle and side.
  size_t fold_line = 0;
  for (size_t e = 0; e < n; ++e) fold_line += std::fabs(el.position(e).y) < 1e-6f && std::fabs(el.position(e).z) < 1e-6f;
  EXPECT_EQ(fold_line, 2 * 2 * 9u);  // 9 vertices on the 1 m edge, halved down to 0.125 m
}

}  // namespace
}  // namespace pm

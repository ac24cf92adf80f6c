// Mesh refinement for vertex link radiosity: elements are mesh vertices, so large triangles are
// subdivided until no edge is longer than max_edge ("large triangles get enough elements").
// Vertices with equal positions are welded first, then every round splits each edge that is too
// long at its midpoint; since the decision belongs to the edge, both triangles sharing it split
// it and the mesh stays conforming (no T-junctions). A triangle with one, two or three split
// edges becomes two, three (the quad cut along its shorter diagonal) or four triangles, keeping
// its winding. The rounds form a tree per original triangle (the refinement tree) whose nodes
// hold their corners in the original triangle's barycentric (u, v) plane: the device maps any
// point of a scene triangle to its refined triangle by descending it (radiosity_mesh.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "kernels/common/compat_host.h"
#include "kernels/common/types.h"
#include "render/scene.h"

namespace pm {

// More refined triangles than this are refused (host memory of the element build, 32-bit links).
constexpr size_t kMaxRefinedTriangles = size_t(1) << 24;

struct RefinedMesh {
  std::vector<Float3> positions;  // the welded input vertices, then the edge midpoints
  std::vector<uint32_t> indices;  // 3 per refined triangle, in the original triangle's winding
  std::vector<uint32_t> source;   // the original (scene) triangle of each refined triangle
  // 2 float4 per node: (u0, v0, u1, v1), (u2, v2, first child or refined triangle as uint bits,
  // child count); nodes 0 .. T-1 are the scene's triangles, children of a node are contiguous.
  std::vector<float4> tree;
  size_t welded_vertices = 0;  // vertices of the input after welding equal positions
  int depth = 0;               // deepest tree level (an unrefined triangle is level 0)

  size_t triangle_count() const { return indices.size() / 3; }
  size_t node_count() const { return tree.size() / 2; }
};

// Refined triangles the scene will have for max_edge, estimated from the longest edges (an upper
// estimate), so that a max_edge far too small is refused before any work.
double estimate_refined_triangles(const Scene& scene, double max_edge);

// Refines the scene. Throws SettingError ("max-edge") when the result would exceed
// kMaxRefinedTriangles.
RefinedMesh refine_mesh(const Scene& scene, double max_edge);

}  // namespace pm

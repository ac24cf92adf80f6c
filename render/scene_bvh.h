// The scene BVH (stage S0): a binned-SAH bounding volume hierarchy over the scene's triangles,
// built once per scene on the host and flattened into float4 arrays the device traversal reads.
// Owns the node/triangle layout contract described below; the traversal kernels depend on it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(__CUDACC__)
#include "kernels/cuda/compat.h"  // CUDA's own float4 when included from the CUDA host glue
#else
#include "kernels/common/compat_host.h"
#endif
#include "kernels/common/types.h"
#include "render/scene.h"

namespace pm {

// Deepest allowed inner-node level (root = level 1). A stack traversal defers at most one child
// per inner level (two pushed, one popped when it pushes both), so a path of D inner nodes needs
// at most D + 1 stack entries; D <= PM_TRAVERSAL_STACK - 2 keeps that within the stack.
constexpr int kSceneBvhMaxDepth = PM_TRAVERSAL_STACK - 2;
// Leaves never hold more than this many triangles, whatever the input.
constexpr int kSceneBvhMaxLeafSize = 8;

// Flattened BVH, ready to upload.
//
// Node i is nodes[4i .. 4i+3]; node 0 is the root. Each node stores the boxes of its two
// children (Aila & Laine's GPU layout, so one node fetch decides both children):
//   n0 = (L.min.x, L.max.x, L.min.y, L.max.y)
//   n1 = (R.min.x, R.max.x, R.min.y, R.max.y)
//   n2 = (L.min.z, L.max.z, R.min.z, R.max.z)
//   n3 = (left, right, left_count, right_count) as int bits
// For each child: count > 0 => leaf holding leaf-order triangles [index, index + count);
// count == 0 and index >= 0 => inner node `index`; index == -1 (count 0) => empty child, whose
// box is inverted (min = +INF, max = -INF) so that no slab test ever accepts it.
//
// Child boxes are padded outward by about 8 ulps of the coordinate's magnitude plus ~1e-6 of the
// scene's extent, so that a hit exactly on a box face survives the traversal's float rounding
// and a flat axis-aligned wall (zero thickness) still gets a box of tiny positive thickness.
// The traversal should nevertheless use a robust min/max slab test (Ize 2013).
//
// triangles holds 3 float4 per triangle in leaf order:
//   (v0.xyz, material index as int bits, | PM_TRIANGLE_MASKED when the material has an alpha
//   mask), (v1.xyz, original triangle index as int bits),
//   (v2.xyz, object index as int bits; 0 when the scene has no triangle_object).
struct SceneBvh {
  std::vector<float4> nodes;
  std::vector<float4> triangles;
  std::vector<uint32_t> original_index;  // leaf-order position -> index into Scene triangles

  // Statistics for reports.
  int depth = 0;          // inner-node levels on the longest path (root alone = 1)
  size_t leaf_count = 0;  // non-empty leaves
  float sah_cost = 0;     // SAH cost (traversal 1, intersection 1 per triangle), relative to root

  size_t node_count() const { return nodes.size() / 4; }
  size_t triangle_count() const { return original_index.size(); }
};

struct SceneBvhOptions {
  // Inner-level limit; the builder switches to median splits early enough to honour it. Values
  // too small for the triangle count are raised to the smallest feasible depth. Tests use
  // larger values to show that an input is pathological; the renderer keeps the default.
  int max_depth = kSceneBvhMaxDepth;
  int bin_count = 32;  // SAH bins per axis over the centroid bounds (clamped to [2, 256])
};

// Builds the BVH. Throws InputError when the mesh is inconsistent (index count not a multiple of
// three, vertex index out of range, material list not one per triangle). An empty scene yields
// a root with two empty children.
SceneBvh build_scene_bvh(const Scene& scene);
SceneBvh build_scene_bvh(const Scene& scene, const SceneBvhOptions& options);

}  // namespace pm

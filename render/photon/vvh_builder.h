// The voxel-volume-heuristic (VVH) photon map builder: a host-side, top-down alternative to the
// device LBVH (kernels/common/photon_map.h), kept as a comparison option (`--photon-bvh vvh`)
// for the paper's Table 1 (Fabianowski & Dingliana 2009, section 5.1, eq. 14; termination by a
// leaf size threshold as in section 5.3). Owns the split search, the depth bound and the output
// in the LBVH's node layout, so the same device traversal and gather run on either tree.
//
// Output layout (identical to photon_map.h): 4 float4 per inner node p, root = node 0,
//   nodes[4p+0] = (left.lo.xyz,  left.ref)     nodes[4p+2] = (right.lo.xyz, right.ref)
//   nodes[4p+1] = (left.hi.xyz,  left.count)   nodes[4p+3] = (right.hi.xyz, right.count)
// ref/count are uint bit patterns in .w; ref with PM_PHOTON_MAP_LEAF = leaf over positions
// [ref & 0x7FFFFFFF, + count) of `order`, else ref = inner node index. Child boxes are exact
// (min/max) unions of the hits' AABBs. n >= 2: the root is inner (for n <= T its two children are
// leaves); n == 1: no nodes; n == 0: nothing.
//
// Node numbering: an inner left child is numbered by the LAST position of its range, an inner
// right child by its FIRST position (root 0). This is the numbering a Karras radix tree has, and
// it is a bijection onto [0, n-2] for any binary tree over an ordered sequence, so `nodes` has
// 4 (n - 1) entries like the LBVH (slots of unused numbers hold empty boxes, count 0) and the
// query's stack-overflow fallback (which derives a child's interval from its number) stays
// exact. Independently of that, depth is kept <= kVvhMaxDepth so the 64-entry stack never fills.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(__CUDACC__)
#include "kernels/cuda/compat.h"  // CUDA's own float4 when included from the CUDA host glue
#else
#include "kernels/common/compat_host.h"
#endif

namespace pm {

// Deepest inner-node level (root = level 1). The query pushes at most one node per inner level
// below the root, so this stays well inside PM_TRAVERSAL_STACK (64).
constexpr int kVvhMaxDepth = 60;

// Flat boxes (e.g. footprints on an axis-aligned wall) have zero volume, which would make every
// split cost 0. While scoring the splits of a node, each child box extent is therefore padded by
// kVvhFlatEpsilon * (largest extent of that node's box) before the product, so a flat box costs
// ~ its area times a tiny thickness and the heuristic still prefers tighter splits; for boxes
// thicker than the pad the cost is the plain volume of eq. 14. Relative to the node, not the
// scene, so the choice at a node does not depend on the scale of the node.
constexpr double kVvhFlatEpsilon = 1e-6;

struct VvhPhotonMap {
  std::vector<float4> nodes;   // 4 * (n - 1) float4 for n >= 2, empty otherwise
  std::vector<uint32_t> order; // order[i] = input index of the hit at position i
  int depth = 0;               // inner-node levels (root alone = 1; 0 for n < 2)
  size_t leaves = 0;           // leaf children in the tree (1 for n == 1: the single hit)
};

// lo/hi: the n hits' footprint AABBs (xyz used, finite). leaf_threshold T: a child holding
// <= T hits becomes a leaf (T = 0 is treated as 1). At each inner node the 3N plane-sweep
// partitionings (hits sorted by AABB centroid per axis) are scored with C = V_L N_L + V_R N_R
// and the cheapest is taken; ties (within 1e-9 relative) go to the more balanced split. A
// candidate whose child could not be finished within kVvhMaxDepth by median splits is excluded
// (the median always stays allowed), so the bound only bites on degenerate inputs, where the
// deep part degrades towards median splits. O(N log N) presort, then O(N) per tree level. Throws std::invalid_argument if lo.size() != hi.size() or n >= 2^31.
VvhPhotonMap build_vvh_photon_map(const std::vector<float4>& lo, const std::vector<float4>& hi,
                                  uint32_t leaf_threshold);

// Expected query cost of any tree in the layout above (LBVH or VVH): the sum over all child slots
// reachable from the root of V(slot box) * count, i.e. eq. 14 summed over the whole tree, with
// V = product of (extent + flat_pad) per axis. n = number of hits (0 for n < 2).
double photon_map_expected_cost(const std::vector<float4>& nodes, size_t n, double flat_pad = 0.0);

}  // namespace pm

/* Stage S4, the photon map: a linear BVH over the photon hits' footprint AABBs (Fabianowski &
   Dingliana 2009, sections 5.2, 5.3, 6.2). Owns the bounds reduction, Morton codes of hit
   positions, the binary radix tree (Karras 2012), the bottom-up box / count pass with leaf fusion
   under the threshold T, the node layout and T_auto; its traversal (section 6.3) is
   photon_map_query.h's. The (code, index) sort between the Morton and tree steps is the device
   library's (CUB on CUDA, radix_sort.h on OpenCL).

   Pipeline, each step "one call per work item", n hits, n <= 2^29 (int index arithmetic):
     1. photon_map_bounds_tile     work item = tile of PM_PHOTON_MAP_BOUNDS_TILE hit slots: bounds,
                                   area and count of its valid hits; the host combines the tiles
                                   (photon_map_combine_partials).
     2. photon_map_morton_tile     work item = tile: the Morton codes of its valid hits, written
                                   compacted at the tile's offset (photon_map_tile_offsets).
     3. sort the n (code, slot) pairs ascending by code (any stable or unstable sort: ties are
        broken by sorted position below, which is exactly "augment the key with the index").
     4. photon_map_build_node      i < n - 1: Karras's range + split of inner node i; parent links;
                                   zeroes the visit counter of node i.
     5. photon_map_bottom_up       k < n: child boxes, counts and leaf fusion, from the leaf boxes
                                   in sorted order.
     6. the query per shading point or box of them (gather, S6): photon_map_query.h.

   Node layout (4 float4 per inner node p = 0 .. n-2, root = 0; both CHILD boxes live in the
   parent, as in section 6.3, so one traversal step reads one node):
     nodes[4p+0] = (left.lo.xyz,  left.ref)      nodes[4p+2] = (right.lo.xyz, right.ref)
     nodes[4p+1] = (left.hi.xyz,  left.count)    nodes[4p+3] = (right.hi.xyz, right.count)
   ref and count are uint bit patterns in .w. count = hits below the child. If ref has bit 31
   (PM_PHOTON_MAP_LEAF) set, the child is a leaf: sorted hit positions [ref & 0x7FFFFFFF,
   + count). Otherwise ref is the inner node to descend into. A child becomes a leaf when
   count <= T (T = 1: only single hits; section 5.3's "stop splitting when the number of hits
   reaches a threshold", built bottom-up as in section 6.2 by undoing splits below T).
   The array keeps all n - 1 nodes (no compaction): nodes inside a fused subtree are written but
   never reached. The root is always an inner node, so when n <= T the root's two children are
   the leaves. n == 1 has no node at all; the query scans hit 0 directly.
   The sorted positions index sorted_lo/sorted_hi and the gather data, all in sorted order (the
   footprint stage writes them so, photon_footprint.h). Section 6.3 marks a leaf's end with a
   flag on its last hit; here (first, count) sits in the parent's slot instead, since the counts
   are needed for fusion anyway and the hit arrays stay untouched. n == 0: the host skips the
   stage. */
#ifndef PM_PHOTON_MAP_H
#define PM_PHOTON_MAP_H

#include "morton.h"
#include "types.h"
#include "vec3.h"

/* PM_MEMORY_FENCE comes from the backend's compat.h (CUDA __threadfence(), OpenCL
   mem_fence(CLK_GLOBAL_MEM_FENCE), nothing on the single-threaded host). It orders step 5's
   child-slot writes before the visit counter, and the counter before the sibling's slot read. */
#ifndef PM_MEMORY_FENCE
#error "PM_MEMORY_FENCE must be defined by the backend's compat.h"
#endif

#define PM_PHOTON_MAP_BOUNDS_TILE 256
#define PM_PHOTON_MAP_LEAF 0x80000000u
#define PM_PHOTON_MAP_NO_PARENT 0xFFFFFFFFu

/* ---- 1. overall bounds of the hit positions (section 6.2: "their overall bounding volume") ---- */

PM_DEVICE uint photon_map_bounds_tile_count(uint count)
{
  return (count + PM_PHOTON_MAP_BOUNDS_TILE - 1) / PM_PHOTON_MAP_BOUNDS_TILE;
}

/* Where steps 1 and 2 find their hits: their PM_HIT_* flags and positions, in one of two layouts:
   the trace's hit slots (slot_words non-null: a word of flags and a record index per slot, the
   position at positions[stride * record], photon_trace.h), or positions in place (slot_words
   null: positions[i], the flags as uint bits in its w). A tile is one work item's loop, so its
   hits are read a batch at a time: every slot word of the batch, then the positions of its valid
   hits, so that the batch's loads are in flight together rather than one dependent pair after
   another. Hits [first, first + PM_PHOTON_MAP_HIT_BATCH) into flags[] and position[]; flags 0
   from `end` on. An empty slot's record is not read. */
#define PM_PHOTON_MAP_HIT_BATCH 8u

PM_DEVICE void photon_map_hit_batch(uint first, uint end, PM_GLOBAL const uint* slot_words,
                                    PM_GLOBAL const float4* positions, uint stride, uint* flags, float4* position)
{
  for (uint j = 0; j < PM_PHOTON_MAP_HIT_BATCH; ++j) {
    uint i = first + j;
    flags[j] = 0u;
    position[j] = PM_MAKE_FLOAT4(0.0f, 0.0f, 0.0f, 0.0f);
    if (i >= end) continue;
    if (slot_words) {
      flags[j] = PM_LOAD(&slot_words[i]);
    } else {
      position[j] = PM_LOAD(&positions[i]);
      flags[j] = PM_AS_UINT(position[j].w);
    }
  }
  if (!slot_words) return;
  for (uint j = 0; j < PM_PHOTON_MAP_HIT_BATCH; ++j)
    if ((flags[j] & PM_HIT_VALID) != 0u) position[j] = PM_LOAD(&positions[stride * (flags[j] >> PM_HIT_RECORD_SHIFT)]);
}

/* Work item = tile of slots [tile * TILE, min(count, (tile + 1) * TILE)): bounds of the valid
   hits' positions (photon_map_hit_batch), the sum of their footprint areas (area_in[i].w; none when
   area_in is null) and their count, into partials[2 tile] = (lo, area), [2 tile + 1] = (hi,
   count as uint bits). A tile without valid hits gives the empty box (+1e30, -1e30). */
PM_DEVICE void photon_map_bounds_tile(uint tile, uint count, PM_GLOBAL const uint* slot_words,
                                      PM_GLOBAL const float4* positions, uint stride,
                                      PM_GLOBAL const float4* area_in, PM_GLOBAL float4* partials)
{
  uint begin = tile * PM_PHOTON_MAP_BOUNDS_TILE;
  uint end = pm_min_u(begin + PM_PHOTON_MAP_BOUNDS_TILE, count);
  Vec3 lo = vec3_splat(1e30f), hi = vec3_splat(-1e30f);
  float area = 0.0f;
  uint valid = 0;
  for (uint first = begin; first < end; first += PM_PHOTON_MAP_HIT_BATCH) {
    uint flags[PM_PHOTON_MAP_HIT_BATCH];
    float4 c[PM_PHOTON_MAP_HIT_BATCH];
    photon_map_hit_batch(first, end, slot_words, positions, stride, flags, c);
    for (uint j = 0; j < PM_PHOTON_MAP_HIT_BATCH; ++j) {
      if ((flags[j] & PM_HIT_VALID) == 0u) continue;
      Vec3 x = vec3_from_float4(c[j]);
      lo = vec3_min(lo, x);
      hi = vec3_max(hi, x);
      if (area_in) area += PM_LOAD(&area_in[first + j]).w;
      ++valid;
    }
  }
  partials[2 * tile] = vec3_to_float4(lo, area);
  partials[2 * tile + 1] = vec3_to_float4(hi, PM_UINT_AS_FLOAT(valid));
}

#ifdef PM_HOST_BACKEND
/* The few tile partials combined on the host, after one small read-back: overall bounds, the
   area sum (in double: many small terms) and the valid count. Host only (no fp64 on the device). */
typedef struct PhotonMapBounds {
  float4 lo, hi;
  double area;
  uint count;
} PhotonMapBounds;

PM_DEVICE PhotonMapBounds photon_map_combine_partials(const float4* partials, uint tiles)
{
  PhotonMapBounds b;
  Vec3 lo = vec3_splat(1e30f), hi = vec3_splat(-1e30f);
  b.area = 0.0;
  b.count = 0u;
  for (uint t = 0; t < tiles; ++t) {
    lo = vec3_min(lo, vec3_from_float4(partials[2 * t]));
    hi = vec3_max(hi, vec3_from_float4(partials[2 * t + 1]));
    b.area += (double)partials[2 * t].w;
    b.count += PM_AS_UINT(partials[2 * t + 1].w);
  }
  b.lo = vec3_to_float4(lo, 0.0f);
  b.hi = vec3_to_float4(hi, 0.0f);
  return b;
}

/* Where each tile's valid hits start in the compacted key array (step 2): the exclusive prefix
   sum of the tiles' counts. */
PM_DEVICE void photon_map_tile_offsets(const float4* partials, uint tiles, uint* first_out)
{
  uint sum = 0u;
  for (uint t = 0; t < tiles; ++t) {
    first_out[t] = sum;
    sum += PM_AS_UINT(partials[2 * t + 1].w);
  }
}
#endif

/* ---- 2. Morton codes of the valid hits, compacted (sections 5.2, 6.2: 30-bit codes in the
   overall bounds) ---- */

#define PM_MORTON_SORT_BITS 30

PM_DEVICE uint photon_map_morton_key(float4 center, float4 bounds_lo, float4 bounds_hi)
{
  return morton_code(vec3_from_float4(center), vec3_from_float4(bounds_lo), vec3_from_float4(bounds_hi));
}

/* Work item = tile (as in step 1): the Morton key and slot of each valid hit of the tile, in slot
   order, from position first_out[tile] on (the exclusive prefix sum of the tiles' valid counts).
   Only valid hits reach the sort, in an order that does not depend on scheduling. */
PM_DEVICE void photon_map_morton_tile(uint tile, uint count, PM_GLOBAL const uint* slot_words,
                                      PM_GLOBAL const float4* positions, uint stride,
                                      PM_GLOBAL const uint* first_out, float4 bounds_lo, float4 bounds_hi,
                                      PM_GLOBAL uint* keys, PM_GLOBAL uint* slots)
{
  uint begin = tile * PM_PHOTON_MAP_BOUNDS_TILE;
  uint end = pm_min_u(begin + PM_PHOTON_MAP_BOUNDS_TILE, count);
  uint out = PM_LOAD(&first_out[tile]);
  for (uint first = begin; first < end; first += PM_PHOTON_MAP_HIT_BATCH) {
    uint flags[PM_PHOTON_MAP_HIT_BATCH];
    float4 c[PM_PHOTON_MAP_HIT_BATCH];
    photon_map_hit_batch(first, end, slot_words, positions, stride, flags, c);
    for (uint j = 0; j < PM_PHOTON_MAP_HIT_BATCH; ++j) {
      if ((flags[j] & PM_HIT_VALID) == 0u) continue;
      keys[out] = photon_map_morton_key(c[j], bounds_lo, bounds_hi);
      slots[out] = first + j;
      ++out;
    }
  }
}

/* ---- 4. binary radix tree over the sorted codes (Karras 2012, section 4) ---- */

/* Length of the common prefix of the keys at sorted positions i and j, -1 outside [0, n).
   Equal codes are told apart by the positions: key = (code, position) as 64 bits. */
PM_DEVICE int photon_map_delta(PM_GLOBAL const uint* codes, int n, int i, int j)
{
  if (j < 0 || j >= n) return -1;
  uint a = PM_LOAD(&codes[i]);
  uint b = PM_LOAD(&codes[j]);
  if (a != b) return pm_clz(a ^ b);
  return 32 + pm_clz((uint)i ^ (uint)j);
}

/* Work item = inner node i < n - 1. Finds the node's key range [min(i, j), max(i, j)] and split
   gamma; links the children to i: parent = (i << 1) | side, side 0 = left. Leaves (children
   whose range is one key) link through leaf_parent, inner nodes through node_parent. */
PM_DEVICE void photon_map_build_node(uint i, uint n, PM_GLOBAL const uint* codes, PM_GLOBAL uint* node_parent,
                                     PM_GLOBAL uint* leaf_parent, PM_GLOBAL uint* visits)
{
  int ii = (int)i, nn = (int)n;
  int d = photon_map_delta(codes, nn, ii, ii + 1) > photon_map_delta(codes, nn, ii, ii - 1) ? 1 : -1;
  /* Upper bound of the range length, then the exact other end j by binary search. */
  int delta_min = photon_map_delta(codes, nn, ii, ii - d);
  int l_max = 2;
  while (photon_map_delta(codes, nn, ii, ii + l_max * d) > delta_min) l_max <<= 1;
  int l = 0;
  for (int t = l_max >> 1; t >= 1; t >>= 1)
    if (photon_map_delta(codes, nn, ii, ii + (l + t) * d) > delta_min) l += t;
  int j = ii + l * d;
  /* Split: the last position (in direction d) sharing more than the node's prefix with i. */
  int delta_node = photon_map_delta(codes, nn, ii, j);
  int s = 0;
  int t = l;
  do {
    t = (t + 1) >> 1;
    if (photon_map_delta(codes, nn, ii, ii + (s + t) * d) > delta_node) s += t;
  } while (t > 1);
  int gamma = ii + s * d + pm_min_i(d, 0);

  uint left = i << 1, right = (i << 1) | 1u;
  if (pm_min_i(ii, j) == gamma) leaf_parent[gamma] = left;
  else node_parent[gamma] = left;
  if (pm_max_i(ii, j) == gamma + 1) leaf_parent[gamma + 1] = right;
  else node_parent[gamma + 1] = right;
  if (i == 0) node_parent[0] = PM_PHOTON_MAP_NO_PARENT;
  visits[i] = 0;
}

/* ---- 5. bottom-up boxes, counts and leaf fusion (section 6.2) ---- */

/* Work item = leaf k < n (sorted position), whose AABB sorted_lo/hi[k] holds (the footprint
   stage writes the boxes in sorted order). Walks up: at each parent it writes its subtree's slot
   (box, ref, count), and only the second work item to arrive at a node (atomic visit counter) goes
   on, with the union of both slots. A slot whose count <= threshold is written as a leaf interval,
   which undoes the splits below T. Every slot of every node is written exactly once whatever the
   arrival order, so the result does not depend on scheduling. Needs the visit counters zeroed
   (step 4 does that); for n == 1 there is nothing to do. */
PM_DEVICE void photon_map_bottom_up(uint k, uint n, uint leaf_threshold, PM_GLOBAL const float4* sorted_lo,
                                    PM_GLOBAL const float4* sorted_hi, PM_GLOBAL const uint* node_parent,
                                    PM_GLOBAL const uint* leaf_parent, PM_GLOBAL uint* visits, PM_GLOBAL float4* nodes)
{
  Vec3 lo = vec3_from_float4(PM_LOAD(&sorted_lo[k]));
  Vec3 hi = vec3_from_float4(PM_LOAD(&sorted_hi[k]));
  if (n < 2) return;

  uint threshold = leaf_threshold > 1u ? leaf_threshold : 1u;
  uint child = k;     /* current subtree: its node index (inner) or k (leaf) */
  uint first = k;     /* its first sorted position */
  uint count = 1u;    /* its hit count */
  uint link = PM_LOAD(&leaf_parent[k]);
  while (link != PM_PHOTON_MAP_NO_PARENT) {
    uint p = link >> 1;
    uint side = link & 1u;
    uint ref = count <= threshold ? (first | PM_PHOTON_MAP_LEAF) : child;
    nodes[4 * p + 2 * side] = vec3_to_float4(lo, PM_UINT_AS_FLOAT(ref));
    nodes[4 * p + 2 * side + 1] = vec3_to_float4(hi, PM_UINT_AS_FLOAT(count));
    /* Release: our slot must be visible before the counter says it is there. */
    PM_MEMORY_FENCE();
    if (pm_atomic_add_u32(&visits[p], 1u) == 0u) return; /* first arrival: the sibling finishes p */
    /* Acquire: read the sibling's slot only after its writer's counter increment, and never
       from a stale cache line: the slot was written in this launch, perhaps by another
       multiprocessor, so neither PM_LOAD nor a plain load (either may hit a stale L1 line). */
    PM_MEMORY_FENCE();
    uint other = 2 * (1u - side);
    float4 sib_lo = PM_LOAD_SHARED_FLOAT4(&nodes[4 * p + other]);
    float4 sib_hi = PM_LOAD_SHARED_FLOAT4(&nodes[4 * p + other + 1]);
    uint sib_count = PM_AS_UINT(sib_hi.w);
    lo = vec3_min(lo, vec3_from_float4(sib_lo));
    hi = vec3_max(hi, vec3_from_float4(sib_hi));
    if (side == 1u) first -= sib_count; /* the left sibling's interval ends just before ours */
    count += sib_count;
    child = p;
    link = PM_LOAD(&node_parent[p]);
  }
}

/* ---- T_auto (section 5.3) ---- */

/* max(1, round(c * total footprint area / total scene surface area)); 1 for a NaN ratio or a
   scene area that is not positive, capped at 2^30 (also for an overflowing ratio). c is
   calibrated elsewhere. */
PM_DEVICE uint photon_map_auto_leaf_size(float total_footprint_area, float total_scene_area, float c)
{
  float t = c * (total_footprint_area / total_scene_area);
  if (!(total_scene_area > 0.0f) || !(t >= 1.0f)) return 1u; /* also NaN */
  if (t >= 1073741824.0f) return 1073741824u;                /* also +inf */
  return (uint)pm_floorf(t + 0.5f);
}

/* T_auto held within [least, most]: on devices whose lanes run in lockstep (GPUs) the best T
   follows how the map is walked more than the footprints' overlap (docs/algorithm.md, S4, T_auto).
   - Where the gather's pixel tiles walk the map together (gather_tiles.h), every lane scans the
     hits of the leaves meeting its tile's box at once: the best fixed T measured 16 to 32 on all
     four benchmark scenes at the paper's and the production profile, whatever the overlap, where
     T_auto read 8 (Sponza) to 214 (the Cornell box), where the gather was 19 % slower than at 24.
   - Final gathering reads its map at its rays' hits, each lane at a point of its own, with the
     map at an overlap of 3 (final_gather.h), where T_auto reads 1 and each hit costs a node
     visit: the best T measured 4 to 8, a pass 4 to 8 % faster at 8 than at 1. */
#define PM_TILE_WALK_LEAF_MIN 16u
#define PM_TILE_WALK_LEAF_MAX 32u
#define PM_RAY_HIT_WALK_LEAF_MIN 8u

PM_DEVICE uint photon_map_leaf_size_within(uint auto_leaf_size, uint least, uint most)
{
  return auto_leaf_size < least ? least : auto_leaf_size > most ? most : auto_leaf_size;
}

#endif

/* Stage S4's query (Fabianowski & Dingliana 2009, section 6.3): the iterator over the photon
   map's hits whose footprint AABB contains a shading point, or meets a box of shading points
   (the gather's pixel tiles, gather_tiles.h). The map's layout and build are photon_map.h's. */
#ifndef PM_PHOTON_MAP_QUERY_H
#define PM_PHOTON_MAP_QUERY_H

#include "photon_map.h"

/* ---- 6. query: every hit whose footprint AABB contains x (section 6.3), or meets a box ---- */

#define PM_PHOTON_MAP_NO_NODE 0xFFFFFFFFu

typedef struct PhotonMapQuery {
  Vec3 lo, hi;         /* the query box; a point query's is the point (lo == hi == x) */
  uint cur, end;       /* sorted positions still to scan: [cur, end) */
  uint check;          /* nonzero: test each scanned hit's own AABB (fused leaf or overflow) */
  uint node;           /* inner node to visit next without a pop, or PM_PHOTON_MAP_NO_NODE */
  uint sp, stack_limit;
  uint nodes_visited;  /* statistics: inner nodes read */
  uint overflows;      /* statistics: subtrees scanned linearly because the stack was full */
  uint stack[PM_TRAVERSAL_STACK];
} PhotonMapQuery;

/* Inclusive test, so points on a face count; the stored boxes are exact unions (min/max), so a
   parent box never misses a point its hits contain. NaN x is in no box (without fast-math). */
PM_DEVICE int photon_map_box_contains(float4 lo, float4 hi, Vec3 x)
{
  return lo.x <= x.x && x.x <= hi.x && lo.y <= x.y && x.y <= hi.y && lo.z <= x.z && x.z <= hi.z;
}

/* Whether the box [lo, hi] meets the query box [q_lo, q_hi], faces included: for a point query
   (q_lo == q_hi == x) the same comparisons as photon_map_box_contains. */
PM_DEVICE int photon_map_box_meets(float4 lo, float4 hi, Vec3 q_lo, Vec3 q_hi)
{
  return lo.x <= q_hi.x && q_lo.x <= hi.x && lo.y <= q_hi.y && q_lo.y <= hi.y && lo.z <= q_hi.z && q_lo.z <= hi.z;
}

/* stack_limit: PM_TRAVERSAL_STACK for rendering; smaller values (down to 0) force the overflow
   path in tests. Only a node with two inner children containing x pushes one of them, so the
   stack never holds more entries than the tree has levels; a radix tree over (30-bit code, 32-bit
   position) keys has at most 62 inner levels, so 64 entries do not overflow. The fallback keeps
   the result exact anyway: a child that cannot be pushed is scanned as its interval of hits. */
/* A query for every hit whose AABB meets the box [lo, hi]. The traversal's order does not depend
   on the query (at each node the leaf children's hits first, in sorted order, then the inner
   child with more hits, then the other), so the hits whose boxes contain a point x inside [lo,
   hi] come in the same order as a point query at x returns them: a box query filtered by each
   hit's own box at x finds what x's point query finds, in its order (tests/unit/photon_map_test.cpp).
   The stack never fills (see below), which that order needs. */
PM_DEVICE void photon_map_query_begin_box(PhotonMapQuery* q, Vec3 lo, Vec3 hi, uint n, uint stack_limit)
{
  q->lo = lo;
  q->hi = hi;
  q->cur = 0;
  q->end = n >= 2 ? 0u : n; /* no tree for 0 or 1 hits: scan them */
  q->check = 1;
  q->node = n >= 2 ? 0u : PM_PHOTON_MAP_NO_NODE; /* the root */
  q->sp = 0;
  q->stack_limit = pm_min_u(stack_limit, (uint)PM_TRAVERSAL_STACK);
  q->nodes_visited = 0;
  q->overflows = 0;
}

PM_DEVICE void photon_map_query_begin(PhotonMapQuery* q, Vec3 x, uint n, uint stack_limit)
{
  photon_map_query_begin_box(q, x, x, n, stack_limit);
}

/* The traversal's next step: visits inner nodes until one has leaf children meeting the query's
   box, and leaves their hits' sorted positions in [q->cur, q->end) (q->check: whether each hit's
   own AABB must still be tested against the box: a fused leaf, or a subtree scanned because the
   stack was full). Returns 0 when the tree is done. A caller may scan the interval itself
   (gather_within, which tests each hit at its shading point) or through photon_map_query_next. */
PM_DEVICE int photon_map_query_advance(PhotonMapQuery* q, PM_GLOBAL const float4* nodes)
{
  for (;;) {
    uint node = q->node;
    if (node == PM_PHOTON_MAP_NO_NODE) {
      if (q->sp == 0) return 0;
      node = q->stack[--q->sp];
    }
    q->node = PM_PHOTON_MAP_NO_NODE;
    q->nodes_visited++;
    /* Leaf children meeting the query's box are scanned. The two children's intervals are adjacent (left
       ends where right starts), so whatever has to be scanned is one interval [begin, end). */
    uint begin = 0xFFFFFFFFu, end = 0u, check = 0u;
    uint left_ref = PM_PHOTON_MAP_NO_NODE, right_ref = PM_PHOTON_MAP_NO_NODE;
    uint left_count = 0u, right_count = 0u;
    for (uint side = 0; side < 2u; ++side) {
      float4 lo = PM_LOAD(&nodes[4 * node + 2 * side]);
      float4 hi = PM_LOAD(&nodes[4 * node + 2 * side + 1]);
      if (!photon_map_box_meets(lo, hi, q->lo, q->hi)) continue;
      uint ref = PM_AS_UINT(lo.w);
      uint count = PM_AS_UINT(hi.w);
      if (ref & PM_PHOTON_MAP_LEAF) {
        uint first = ref & ~PM_PHOTON_MAP_LEAF;
        begin = pm_min_u(begin, first);
        end = end > first + count ? end : first + count;
        if (count > 1u) check = 1u; /* a single hit's box was just tested exactly */
      } else if (side == 0u) {
        left_ref = ref;
        left_count = count;
      } else {
        right_ref = ref;
        right_count = count;
      }
    }
    /* Inner children: descend into one directly; when both meet the box, defer the one with fewer
       hits (cheaper to scan should the stack be full). An absent child has count 0, so with one
       inner child that one is always "near". */
    uint defer_left = left_count < right_count;
    uint far = defer_left ? left_ref : right_ref;
    q->node = defer_left ? right_ref : left_ref;
    if (q->node != PM_PHOTON_MAP_NO_NODE && far != PM_PHOTON_MAP_NO_NODE) {
      if (q->sp < q->stack_limit) {
        q->stack[q->sp++] = far;
      } else {
        /* Overflow: Karras's inner node index is the right end of a left child's range and the
           left end of a right child's range. Both children are inner, so no leaf interval is
           pending at this node. */
        uint count = defer_left ? left_count : right_count;
        begin = defer_left ? far + 1u - count : far;
        end = begin + count;
        check = 1u;
        q->overflows++;
      }
    }
    if (begin < end) {
      q->cur = begin;
      q->end = end;
      q->check = check;
      return 1;
    }
  }
}

/* Next sorted position whose hit AABB meets the query's box (for a point query: contains the
   point), or -1 when done. Each such hit is returned exactly once; the caller evaluates the
   ellipsoid itself (section 6.3: accumulate the hits whose footprints overlap x). Read-only
   inputs: nodes and sorted_lo/hi from step 5. */
PM_DEVICE int photon_map_query_next(PhotonMapQuery* q, PM_GLOBAL const float4* nodes,
                                    PM_GLOBAL const float4* sorted_lo, PM_GLOBAL const float4* sorted_hi)
{
  for (;;) {
    while (q->cur < q->end) {
      uint k = q->cur++;
      if (!q->check || photon_map_box_meets(PM_LOAD(&sorted_lo[k]), PM_LOAD(&sorted_hi[k]), q->lo, q->hi))
        return (int)k;
    }
    if (!photon_map_query_advance(q, nodes)) return -1;
  }
}

#endif

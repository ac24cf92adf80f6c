/* The k-nearest-neighbour baseline (Jensen's photon map density estimate, paper section 3.1) on
   the same photons and the same LBVH: the tree is built over point boxes (position +- rmax), and
   this traversal shrinks each child box back by rmax to the box of its photon positions, so it
   prunes with the current k-th distance as the search radius shrinks. The k candidates live in a
   private max-heap (the cost the paper attributes to k-NN gathering). */
#ifndef PM_KNN_GATHER_H
#define PM_KNN_GATHER_H

#include "brdf.h"
#include "footprint.h"
#include "gather_reach.h"
#include "kernel_globals.h"
#include "photon_map.h"

#define PM_KNN_MAX_K 256

/* Squared distance from x to the box [lo + pad, hi - pad]. */
PM_DEVICE float knn_box_distance2(float4 lo, float4 hi, float pad, Vec3 x)
{
  float dx = pm_fmaxf(pm_fmaxf(lo.x + pad - x.x, 0.0f), x.x - (hi.x - pad));
  float dy = pm_fmaxf(pm_fmaxf(lo.y + pad - x.y, 0.0f), x.y - (hi.y - pad));
  float dz = pm_fmaxf(pm_fmaxf(lo.z + pad - x.z, 0.0f), x.z - (hi.z - pad));
  return dx * dx + dy * dy + dz * dz;
}

typedef struct KnnHeap {
  uint size, k;
  float dist2[PM_KNN_MAX_K]; /* max-heap on distance */
  uint index[PM_KNN_MAX_K];
} KnnHeap;

PM_DEVICE float knn_radius2(const KnnHeap* h, float rmax2) { return h->size < h->k ? rmax2 : h->dist2[0]; }

PM_DEVICE void knn_offer(KnnHeap* h, float d2, uint index)
{
  uint i;
  if (h->size < h->k) {
    i = h->size++;
    while (i > 0 && h->dist2[(i - 1) / 2] < d2) { /* sift up */
      h->dist2[i] = h->dist2[(i - 1) / 2];
      h->index[i] = h->index[(i - 1) / 2];
      i = (i - 1) / 2;
    }
  } else {
    if (d2 >= h->dist2[0]) return;
    i = 0; /* replace the farthest, sift down */
    for (;;) {
      uint c = 2 * i + 1;
      if (c >= h->size) break;
      if (c + 1 < h->size && h->dist2[c + 1] > h->dist2[c]) ++c;
      if (h->dist2[c] <= d2) break;
      h->dist2[i] = h->dist2[c];
      h->index[i] = h->index[c];
      i = c;
    }
  }
  h->dist2[i] = d2;
  h->index[i] = index;
}

/* Offers the photons [first, first + count) whose reach (their clipped sphere of r_max,
   photon_footprint.h) contains x on a surface facing like theirs (gather_reach.h): photons across
   a wall or around an edge are not neighbours. */
PM_DEVICE void knn_consider_range(const KernelGlobals* kg, KnnHeap* h, uint first, uint count, Vec3 x, Vec3 n,
                                  float rmax2)
{
  for (uint k = first; k < first + count; ++k) {
    float4 c = PM_LOAD(&kg->map_center[k]);
    Vec3 d = vec3_sub(x, vec3_from_float4(c));
    float d2 = vec3_dot(d, d), reach2;
    if (d2 < knn_radius2(h, rmax2) && footprint_reaches(kg, k, c, x, n, &reach2)) knn_offer(h, d2, k);
  }
}

/* Fills the heap with the k nearest photons within rmax of x that reach x (normal n). */
PM_DEVICE void knn_search(const KernelGlobals* kg, const LaunchParams* p, Vec3 x, Vec3 n, KnnHeap* h)
{
  float rmax2 = p->rmax * p->rmax;
  h->size = 0;
  h->k = pm_min_u(p->knn_k, (uint)PM_KNN_MAX_K);
  if (p->hit_count < 2) {
    knn_consider_range(kg, h, 0, p->hit_count, x, n, rmax2);
    return;
  }
  uint stack[PM_TRAVERSAL_STACK];
  float stack_d2[PM_TRAVERSAL_STACK];
  uint sp = 0;
  uint node = 0;
  for (;;) {
    uint next[2];
    float next_d2[2];
    uint n_next = 0;
    for (uint side = 0; side < 2u; ++side) {
      float4 lo = PM_LOAD(&kg->map_nodes[4 * node + 2 * side]);
      float4 hi = PM_LOAD(&kg->map_nodes[4 * node + 2 * side + 1]);
      float d2 = knn_box_distance2(lo, hi, p->rmax, x);
      if (d2 >= knn_radius2(h, rmax2)) continue;
      uint ref = PM_AS_UINT(lo.w);
      if (ref & PM_PHOTON_MAP_LEAF) knn_consider_range(kg, h, ref & ~PM_PHOTON_MAP_LEAF, PM_AS_UINT(hi.w), x, n, rmax2);
      else { next[n_next] = ref; next_d2[n_next] = d2; ++n_next; }
    }
    if (n_next == 2) {
      uint near_first = next_d2[0] <= next_d2[1];
      node = near_first ? next[0] : next[1];
      /* 62 inner levels at most (photon_map.h), so one push per level always fits. */
      stack[sp] = near_first ? next[1] : next[0];
      stack_d2[sp] = near_first ? next_d2[1] : next_d2[0];
      ++sp;
    } else if (n_next == 1) {
      node = next[0];
    } else {
      /* Pop, skipping subtrees the shrunken radius has excluded since they were pushed. */
      int found = 0;
      while (sp > 0 && !found) {
        --sp;
        if (stack_d2[sp] < knn_radius2(h, rmax2)) {
          node = stack[sp];
          found = 1;
        }
      }
      if (!found) break;
    }
  }
}

/* Radiance towards wo at x from the k nearest photons: sum f_r Phi K / (pi r^2), r the k-th
   distance (rmax when fewer than k photons lie within rmax). Same split into indirect/caustic.
   Near edges and walls the whole disc's area dilutes the photons: -26 to -56 % in the benchmark
   scenes (docs/accuracy.md). */
PM_DEVICE void knn_gather_at(const KernelGlobals* kg, const LaunchParams* p, const Material* m, Vec3 x, Vec3 n,
                             Vec3 wo, Vec3* indirect, Vec3* caustic, uint* accepted)
{
  KnnHeap h;
  knn_search(kg, p, x, n, &h);
  float r2 = knn_radius2(&h, p->rmax * p->rmax);
  if (!(r2 > 0.0f)) return;
  float inv_area = 1.0f / (PM_PI * r2);
  for (uint i = 0; i < h.size; ++i) {
    uint k = h.index[i];
    Vec3 wi = vec3_from_float4(PM_LOAD(&kg->map_incident[k]));
    if (vec3_dot(wi, n) <= 0.0f) continue;
    float w = p->kernel_shape == PM_KERNEL_EPANECHNIKOV ? kernel_epanechnikov(h.dist2[i] / r2) : 1.0f;
    Vec3 contribution = vec3_scale(vec3_mul(brdf_eval(m, n, wi, wo), vec3_from_float4(PM_LOAD(&kg->map_power[k]))),
                                   w * inv_area);
    if (PM_AS_UINT(PM_LOAD(&kg->map_center[k]).w) & PM_HIT_CAUSTIC) *caustic = vec3_add(*caustic, contribution);
    else *indirect = vec3_add(*indirect, contribution);
    ++*accepted;
  }
}

#endif

/* The k-nearest-neighbour baseline (Jensen's photon map density estimate, paper section 3.1) on
   the same photons and the same LBVH: the tree is built over point boxes (position +- rmax), and
   this traversal shrinks each child box back by rmax to the box of its photon positions, so it
   prunes with the current k-th distance as the search radius shrinks. The k candidates live in a
   private max-heap (the cost the paper attributes to k-NN gathering).

   Jensen's estimate divides the flux of the k nearest photons by the area pi r^2 of the disc they
   were found in. That is right only where the disc lies wholly on the shading point's surface:
   near an edge, a column, a wall, part of the disc hangs in the air or lies behind the wall, no
   photon can land there, and the estimate is too dark (-26 to -56 % in the benchmark scenes,
   docs/accuracy.md). So here one region serves as both the set of photons counted and the area
   divided by: the search region of x is the footprint ellipsoid of a disc of radius r in x's
   tangent plane with the pd footprints' normal half-axis (the photons are ranked by their
   distance in that ellipsoid's metric), clipped at the walls around x (footprint_clip.h), and its
   area is the part of the clipped disc over a surface the gather accepts, measured with the
   footprint probes (footprint_coverage.h). A photon counts when it lies in the region on a
   surface facing like x's. The probes and the clip are a scene traversal per shading point: the
   knn gather has its kernel of its own, so the footprint gather does not carry them. */
#ifndef PM_KNN_GATHER_H
#define PM_KNN_GATHER_H

#include "brdf.h"
#include "footprint.h"
#include "footprint_clip.h"
#include "footprint_coverage.h"
#include "gather_reach.h"
#include "kernel_globals.h"
#include "photon_map.h"
#include "ray.h"
#include "rng.h"

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

/* The metric of the search region (an ellipsoid with in-plane radius 1 and normal half-axis
   `thickness` about x, normal n): rho^2 = |d|^2 + (1 / thickness^2 - 1) (d . n)^2, which is at
   least |d|^2 min(1, 1 / thickness^2): the traversal prunes with Euclidean box distances scaled
   by that factor (1 for the default thickness 0.5; --footprint-thickness allows up to 4). */
typedef struct KnnRegion {
  Vec3 x, n;
  float normal_stretch; /* 1 / thickness^2 - 1 */
  float box_scale;      /* min(1, 1 / thickness^2) */
} KnnRegion;

PM_DEVICE float knn_region_distance2(const KnnRegion* q, Vec3 photon)
{
  Vec3 d = vec3_sub(photon, q->x);
  float h = vec3_dot(d, q->n);
  return vec3_dot(d, d) + q->normal_stretch * h * h;
}

/* Offers the photons [first, first + count) that lie on a surface facing like x's. */
PM_DEVICE void knn_consider_range(const KernelGlobals* kg, KnnHeap* h, const KnnRegion* q, uint first, uint count,
                                  float rmax2)
{
  for (uint k = first; k < first + count; ++k) {
    float d2 = knn_region_distance2(q, vec3_from_float4(PM_LOAD(&kg->map_center[k])));
    if (d2 < knn_radius2(h, rmax2) && photon_faces_like(PM_LOAD(&kg->map_row_n[k]), q->n)) knn_offer(h, d2, k);
  }
}

/* Fills the heap with the k photons nearest to x in the region's metric, within rmax. */
PM_DEVICE void knn_search(const KernelGlobals* kg, const LaunchParams* p, const KnnRegion* q, KnnHeap* h)
{
  float rmax2 = p->rmax * p->rmax;
  Vec3 x = q->x;
  h->size = 0;
  h->k = pm_min_u(p->knn_k, (uint)PM_KNN_MAX_K);
  if (p->hit_count < 2) {
    knn_consider_range(kg, h, q, 0, p->hit_count, rmax2);
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
      float4 lo = PM_LOAD(&PM_MAP_NODES(kg)[4 * node + 2 * side]);
      float4 hi = PM_LOAD(&PM_MAP_NODES(kg)[4 * node + 2 * side + 1]);
      float d2 = knn_box_distance2(lo, hi, p->rmax, x) * q->box_scale;
      if (d2 >= knn_radius2(h, rmax2)) continue;
      uint ref = PM_AS_UINT(lo.w);
      if (ref & PM_PHOTON_MAP_LEAF) knn_consider_range(kg, h, q, ref & ~PM_PHOTON_MAP_LEAF, PM_AS_UINT(hi.w), rmax2);
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

/* The normal half-axis of knn's region over its radius: the pd footprints' (footprint.h). */
PM_DEVICE float knn_region_thickness(const LaunchParams* p)
{
  return p->footprint_thickness > 0.0f ? p->footprint_thickness : PM_FOOTPRINT_NORMAL_RATIO;
}

/* knn's region of radius r about x (normal n) in *f and *cut (clipped at the walls around x, which
   may shrink it), and its area on x's surface: the clipped disc's area times the share the
   probes find covered, counted as surface area (footprint_probe_covered). turn: the probe
   pattern's angle. */
PM_DEVICE float knn_region_area(const KernelGlobals* kg, const LaunchParams* p, Vec3 x, Vec3 n, float r, float turn,
                                Footprint* f, FootprintCut* cut)
{
  Vec3 t, b;
  vec3_onb(n, &t, &b);
  f->axis_u = vec3_scale(t, r);
  f->axis_v = vec3_scale(b, r);
  f->axis_n = vec3_scale(n, knn_region_thickness(p) * r);
  float offset = ray_offset_distance(x, 0.0f, p->ray_epsilon);
  *cut = footprint_uncut();
  if (p->footprint_clip) *cut = footprint_clip(kg, f, x, n, offset, p->kernel_shape);
  float coverage = p->footprint_coverage ? footprint_covered_share(kg, f, cut, x, n, offset, turn, p->kernel_shape,
                                                                 PM_COVERAGE_SURFACE_AREA, n)
                                         : 1.0f;
  return footprint_area(*f) * cut->kept * coverage;
}

/* The probe pattern's turn for knn's region at a pixel's shading point of mirror depth `depth`. */
PM_DEVICE float knn_region_turn(const LaunchParams* p, uint pixel, uint depth)
{
  return PM_TWO_PI * rng_to_unit(rng_bits4(p->seed, p->frame, pixel, depth, PM_STREAM_FOOTPRINT_PROBE, p->pass_index).b0);
}

/* Radiance towards wo at x (normal n) from the k nearest photons: sum f_r Phi K / A, A the area
   of the region they were found in that lies on x's surface (knn_region_area), r the k-th
   distance (rmax when fewer than k photons lie within rmax). turn: the probe pattern's angle
   (knn_region_turn). Same split into indirect/caustic. */
PM_DEVICE void knn_gather_at(const KernelGlobals* kg, const LaunchParams* p, const Material* m, Vec3 x, Vec3 n,
                             Vec3 wo, float turn, Vec3* indirect, Vec3* caustic, uint* accepted)
{
  float thickness = knn_region_thickness(p);
  KnnRegion q;
  q.x = x;
  q.n = n;
  q.normal_stretch = 1.0f / (thickness * thickness) - 1.0f;
  q.box_scale = pm_fminf(1.0f, 1.0f / (thickness * thickness));
  KnnHeap h;
  knn_search(kg, p, &q, &h);
  float r = pm_sqrtf(knn_radius2(&h, p->rmax * p->rmax));
  if (!(r > 0.0f)) return;
  Footprint f;
  FootprintCut cut;
  float area = knn_region_area(kg, p, x, n, r, turn, &f, &cut);
  if (!(area > 0.0f)) return;
  /* The region's coordinates: its axes are orthogonal, so the inverse basis is a_i / |a_i|^2. */
  Vec3 row_u = vec3_scale(f.axis_u, 1.0f / vec3_dot(f.axis_u, f.axis_u));
  Vec3 row_v = vec3_scale(f.axis_v, 1.0f / vec3_dot(f.axis_v, f.axis_v));
  Vec3 row_n = vec3_scale(f.axis_n, 1.0f / vec3_dot(f.axis_n, f.axis_n));
  /* A full heap's farthest photon (its root) marks the radius: of k photons found within r, k - 1
     are spread over the region, and E[(k - 1) / (pi r^2)] is the density where E[k / (pi r^2)]
     reads it k / (k - 1) too bright (pi rho r^2 follows a Gamma(k) distribution for photons of
     density rho). */
  for (uint i = h.size == h.k ? 1u : 0u; i < h.size; ++i) {
    uint k = h.index[i];
    float4 c = PM_LOAD(&kg->map_center[k]);
    Vec3 d = vec3_sub(vec3_from_float4(c), x);
    float lu = vec3_dot(row_u, d), lv = vec3_dot(row_v, d), ln = vec3_dot(row_n, d);
    float r2 = lu * lu + lv * lv + ln * ln;
    if (r2 > 1.0f || !footprint_cut_keeps(&cut, lu, lv)) continue;
    Vec3 wi = vec3_from_float4(PM_LOAD(&kg->map_incident[k]));
    if (vec3_dot(wi, n) <= 0.0f) continue;
    float w = gather_kernel_weight(p->kernel_shape, r2) / area;
    Vec3 contribution = vec3_scale(vec3_mul(brdf_eval(m, n, wi, wo), vec3_from_float4(PM_LOAD(&kg->map_power[k]))), w);
    if (PM_AS_UINT(c.w) & PM_HIT_CAUSTIC) *caustic = vec3_add(*caustic, contribution);
    else *indirect = vec3_add(*indirect, contribution);
    ++*accepted;
  }
}

#endif

/* Stage S6 (sections 3.2 and 6.3, eq. 1): at every shading point of the camera pass, sum over
   the photon hits whose footprint ellipsoid contains the point: kernel value times BRDF for the
   photon's incident direction times flux / footprint area. Indirect and caustic photons go to
   their own layers. Each pass adds its estimate into the film sums (film.h), which the resolve
   divides by the pass count. */
#ifndef PM_GATHER_H
#define PM_GATHER_H

#include "brdf.h"
#include "camera_pass.h"
#include "film.h"
#include "footprint.h"
#include "gather_reach.h"
#include "gather_tiles.h"
#include "kernel_globals.h"
#include "pixel_order.h"
#include "knn_gather.h"
#include "photon_map_query.h"
#include "photon_trace.h"

/* Photon k's light towards wo at x (its footprint holding x), added to the indirect or the caustic
   sum (eq. 1); with `facet_weighting` (a constant where the kernels inline it) weighed by its tilt
   gain there (gather_reach.h). */
PM_DEVICE void gather_add_hit(const KernelGlobals* kg, const LaunchParams* p, const Material* m, Vec3 x, Vec3 n,
                              Vec3 wo, uint k, Vec3* indirect, Vec3* caustic, uint* accepted, int facet_weighting)
{
  float4 c = PM_LOAD(&kg->map_center[k]);
  float r2, at_u, at_v;
  if (!footprint_reaches_at(kg, k, c, x, n, &r2, &at_u, &at_v)) return;
  Vec3 wi = vec3_from_float4(PM_LOAD(&kg->map_incident[k]));
  if (vec3_dot(wi, n) <= 0.0f) return; /* arrived on the other side of this surface */
  Vec3 f = brdf_eval(m, n, wi, wo);
  float weight = footprint_gather_weight(kg, k, c, r2, at_u, at_v, p->kernel_shape);
  if (facet_weighting) weight *= gather_tilt_gain(PM_LOAD(&kg->map_row_n[k]), wi, n);
  Vec3 contribution = vec3_scale(vec3_mul(f, vec3_from_float4(PM_LOAD(&kg->map_power[k]))), weight);
  if (PM_AS_UINT(c.w) & PM_HIT_CAUSTIC) *caustic = vec3_add(*caustic, contribution);
  else *indirect = vec3_add(*indirect, contribution);
  ++*accepted;
}

/* How many hits of a leaf interval have their boxes tested at x before any of them is evaluated,
   so that their loads are in flight together (docs/benchmarks.md, "A leaf's hits tested at the
   shading point"). At most 32. */
#ifndef PM_GATHER_SCAN_STEP
#define PM_GATHER_SCAN_STEP 2
#endif

/* Radiance towards wo at x from the photon map, split into indirect and caustic parts. The map is
   walked with the box [lo, hi] around x: x itself, or the box of x's pixel tile (gather_tiles.h),
   whose lanes walk the same nodes together. Either way each hit of a leaf interval counts only
   where its own box holds x, so that either walk sums the same photons in the same order. The
   hits are tested at x alone, not first against the walk's box: inside a tile's box, a hit that
   holds x meets the box. On Conference's 1080p frame three in four hits of the tiles' leaves
   missed the box, and each hit that met it was tested twice. */
PM_DEVICE void gather_within(const KernelGlobals* kg, const LaunchParams* p, const Material* m, Vec3 x, Vec3 n,
                             Vec3 wo, Vec3 lo, Vec3 hi, Vec3* indirect, Vec3* caustic, uint* accepted,
                             int facet_weighting)
{
  PhotonMapQuery q;
  photon_map_query_begin_box(&q, lo, hi, p->hit_count, PM_TRAVERSAL_STACK);
  do {
    for (uint k = q.cur; k < q.end; k += PM_GATHER_SCAN_STEP) {
      uint held = 0u; /* bit j: hit k + j holds x */
      for (uint j = 0; j < PM_GATHER_SCAN_STEP; ++j)
        if (k + j < q.end && photon_map_box_contains(PM_LOAD(&kg->map_lo[k + j]), PM_LOAD(&kg->map_hi[k + j]), x))
          held |= 1u << j;
      for (; held != 0u; held &= held - 1u) /* in order, lowest bit first */
        gather_add_hit(kg, p, m, x, n, wo, k + (uint)(31 - pm_clz(held & (0u - held))), indirect, caustic, accepted,
                       facet_weighting);
    }
  } while (photon_map_query_advance(&q, PM_MAP_NODES(kg)));
}

/* The same, the map walked at x alone. */
PM_DEVICE void gather_at(const KernelGlobals* kg, const LaunchParams* p, const Material* m, Vec3 x, Vec3 n, Vec3 wo,
                         Vec3* indirect, Vec3* caustic, uint* accepted, int facet_weighting)
{
  gather_within(kg, p, m, x, n, wo, x, x, indirect, caustic, accepted, facet_weighting);
}

/* How gather_pixel reads the map: the footprint gather, the same with facet weighting, or the knn
   gather. Each kernel inlines gather_pixel with its own constant, so the footprint gather carries
   neither the knn gather's traversals nor the facet weighting's loads and registers (without
   launch bounds, 72 registers on sm_90 against 79 with facet weighting, which made Sponza's
   gather 10 % slower on an H100). */
#define PM_GATHER_FOOTPRINTS 0
#define PM_GATHER_FACETS 1
#define PM_GATHER_KNN 2

/* The film's indirect and caustic radiance at one pixel, summed over its shading points (the
   mirror chain), read from the map as `mode` says. */
PM_DEVICE void gather_pixel(const KernelGlobals* kg, const LaunchParams* p, uint item, int mode)
{
  uint pixel;
  if (!pixel_of_work_item(item, p->width, p->height, &pixel)) return;
  Vec3 indirect = vec3_splat(0.0f), caustic = vec3_splat(0.0f);
  uint accepted = 0, points = 0, tiled = 0;
  EyePath eye = eye_path_begin(pixel);
  ShadingPoint sp;
  for (uint depth = 0; eye_path_next(kg, p, &eye, &sp); ++depth) {
    const Material* m = &sp.material;
    if (channel_mean(material_diffuse(m)) + channel_mean(material_glossy(m)) <= 0.0f) continue;
    Vec3 point_indirect = vec3_splat(0.0f), point_caustic = vec3_splat(0.0f);
    Vec3 tile_lo, tile_hi; /* a first point walks the map with its tile's box where that is compact */
    if (mode == PM_GATHER_KNN) {
      knn_gather_at(kg, p, m, sp.position, sp.normal, sp.outgoing, knn_region_turn(p, pixel, depth), &point_indirect,
                    &point_caustic, &accepted);
    } else if (depth == 0u && gather_tile_box(kg, p, item, &tile_lo, &tile_hi)) {
      gather_within(kg, p, m, sp.position, sp.normal, sp.outgoing, tile_lo, tile_hi, &point_indirect,
                    &point_caustic, &accepted, mode == PM_GATHER_FACETS);
      ++tiled;
    } else {
      gather_at(kg, p, m, sp.position, sp.normal, sp.outgoing, &point_indirect, &point_caustic, &accepted,
                mode == PM_GATHER_FACETS);
    }
    indirect = vec3_add(indirect, vec3_mul(sp.weight, point_indirect));
    caustic = vec3_add(caustic, vec3_mul(sp.weight, point_caustic));
    ++points;
  }
  film_add(kg, p, pixel, indirect, caustic);
  if (p->collect_stats) {
    pm_atomic_add_u32(&kg->gather_stats[0], accepted);
    pm_atomic_add_u32(&kg->gather_stats[1], points);
    pm_atomic_add_u32(&kg->gather_stats[2], tiled);
  }
}

/* Work item = pixel in tile order (pixel_order.h): the footprint gather (pd, radius). */
PM_DEVICE void kernel_gather(const KernelGlobals* kg, const LaunchParams* p, uint item)
{
  gather_pixel(kg, p, item, PM_GATHER_FOOTPRINTS);
}

/* Work item = pixel in tile order: the footprint gather with facet weighting (--facet-weighting). */
PM_DEVICE void kernel_facet_gather(const KernelGlobals* kg, const LaunchParams* p, uint item)
{
  gather_pixel(kg, p, item, PM_GATHER_FACETS);
}

/* Work item = pixel in tile order: the knn gather. */
PM_DEVICE void kernel_knn_gather(const KernelGlobals* kg, const LaunchParams* p, uint item)
{
  gather_pixel(kg, p, item, PM_GATHER_KNN);
}

#endif

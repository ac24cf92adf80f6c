/* The part of a footprint that lies on a surface (stage S3): a photon's flux must be spread over
   the area its footprint actually covers, or the light of every footprint that hangs over an edge
   is lost. Eq. 1 divides each photon's flux by its footprint's area; the clip (footprint_clip.h)
   already takes out what lies behind walls. What remains is the surface simply ending inside the
   ellipse: a ledge, the rim of a table, a column or a rail thinner than the footprint, a window,
   the edge of a small triangle fan. The gather can find no shading point there, so a flux divided
   by the whole ellipse loses the share that hangs in the air: in scenes of real detail (arches,
   columns, cornices) that is 10-20 % of the indirect light, a bias that no photon count removes
   while the footprints keep their size.

   The covered share is measured with probes: PM_FOOTPRINT_EDGE_PROBES points spread evenly over
   the unit disc (Vogel's spiral: each point in the middle of an equal-area cell, the pattern
   turned by an angle drawn per hit so that its error does not line up between footprints), each
   weighted by the kernel at its radius. A footprint traces PM_FOOTPRINT_PROBES of them first (the
   first pattern, below); only one that they find partly covered traces the others. A probe that
   the cuts exclude does not count at all (the clip's kept fraction accounts for it exactly). A
   kept probe is covered when a ray along -n through the ellipsoid's thickness there finds a
   surface the gather would accept (footprint_probe_covered). The footprint's area is multiplied
   by the covered share of the kept kernel mass, so each photon's flux integrates to itself over
   the shading points it reaches.

   A footprint whose probes all miss still covers its own hit: it counts as half a probe's cell,
   so the flux never divides by zero. Cost: PM_FOOTPRINT_PROBES short rays per footprint, and
   PM_FOOTPRINT_EDGE_PROBES in all at an edge: O(photons), not O(gathers). */
#ifndef PM_FOOTPRINT_COVERAGE_H
#define PM_FOOTPRINT_COVERAGE_H

#include "footprint.h"
#include "footprint_clip.h"
#include "gather_reach.h"
#include "kernel_globals.h"
#include "rng.h"
#include "scene_traverse.h"

/* Probes per footprint (types.h): the first pattern's PM_FOOTPRINT_PROBES (16) tell whether the
   surface ends inside the footprint; where it does, all PM_FOOTPRINT_EDGE_PROBES (64) measure
   the covered share, whose quantisation is then about 1.6 % of a footprint. */
/* The golden angle, pi (3 - sqrt(5)). */
#define PM_GOLDEN_ANGLE 2.39996323f
/* Random stream of the probe pattern's turn per hit. */
#define PM_STREAM_FOOTPRINT_PROBE 0x50524f42u /* "PROB" */

/* Probe j of `count` in the unit disc, turned by `turn` radians: radius sqrt((j + 1/2) / count)
   places each probe in the middle of an equal-area ring cell (Vogel's spiral). */
PM_DEVICE void footprint_probe_point(uint j, uint count, float turn, float* x, float* y)
{
  float r = pm_sqrtf(((float)j + 0.5f) / (float)count);
  float s, c;
  pm_sincosf(turn + PM_GOLDEN_ANGLE * (float)j, &s, &c);
  *x = r * c;
  *y = r * s;
}

/* Whether disc point (x, y) passes the cuts of `cut` (footprint_clip.h: m_k . q <= t_k). */
PM_DEVICE int footprint_cut_keeps(const FootprintCut* cut, float x, float y)
{
  for (int k = 0; k < PM_FOOTPRINT_CUTS; ++k)
    if (!(cut->mu[k] * x + cut->mv[k] * y <= cut->t[k])) return 0;
  return 1;
}

/* Whether a surface the gather would accept for this footprint lies under disc point (x, y): a
   ray along -n through the ellipsoid's thickness there, from its top to its bottom (plus the
   hit's ray offset on both sides, so the photon's own plane is always inside), meets from open
   space a surface whose normal lies within the gather's angle of n. Steeper surfaces on the way
   (a column inside a thick footprint) are passed, up to PM_FOOTPRINT_PROBE_HITS crossings; after
   an odd number of crossings the ray is inside a solid, whose far side (a slab's underside) faces
   away from the photon. Returns the probe's weight: 0 where nothing is covered; where something
   is, 1 whatever its tilt and however many layers lie below (a footprint spreads its photon over
   its own surface; counting the tilted or layered area of neighbouring surfaces as well, which
   send their own photons back less than they take, darkens the flat ground measurably: Sponza,
   one bounce, -3.4 % instead of +1.4 %, docs/accuracy.md), or with `surface_area` the surface
   area over the probe's cell, 1 / |cos| of the surface's tilt from n (the knn region counts the
   photons that landed on that area, knn_gather.h), or with `lit_area` that area only where the
   photon's incident direction wi lies above the surface (the only surfaces the gather gives the
   photon to) and none elsewhere: the area the photon's light is spread over when the gather
   weighs it on a tilted facet by what its beam delivers there (gather_tilt_gain, gather_reach.h). */
#define PM_FOOTPRINT_PROBE_HITS 4
#define PM_COVERAGE_CELLS 0u        /* a covered probe counts its cell once */
#define PM_COVERAGE_SURFACE_AREA 1u /* the surface area over its cell */
#define PM_COVERAGE_LIT_AREA 2u     /* the surface area over its cell where wi lies above the surface */
PM_DEVICE float footprint_probe_covered(const KernelGlobals* kg, int root, const Footprint* f, Vec3 center, Vec3 n,
                                        float offset, float x, float y, uint area_mode, Vec3 wi)
{
  float reach = vec3_length(f->axis_n) * pm_sqrtf(pm_fmaxf(1.0f - x * x - y * y, 0.0f)) + offset;
  Vec3 at = vec3_add(center, vec3_add(vec3_scale(f->axis_u, x), vec3_scale(f->axis_v, y)));
  Ray ray = ray_make(vec3_madd(at, n, reach), vec3_neg(n));
  float t_min = 0.0f;
  float gap = pm_fmaxf(1.0e-3f * reach, offset);
  for (int k = 0; k < PM_FOOTPRINT_PROBE_HITS; ++k) {
    /* Inlined: a probe kernel does little but trace (scene_trace_from says why others call it). */
    SceneHit hit = scene_traverse(kg, root, &ray, t_min, 2.0f * reach, 0);
    if (hit.triangle < 0) return 0.0f;
    /* Triangles are two-sided: either side may face the gather's shading point. */
    Vec3 surface_normal = scene_triangle_normal(kg->triangles, hit.triangle);
    float facing = vec3_dot(surface_normal, n);
    if ((k & 1) == 0 && facing * facing >= PM_GATHER_MIN_NORMAL_COS2) {
      if (area_mode == PM_COVERAGE_CELLS) return 1.0f;
      /* The side of the surface that faces the footprint's own normal. */
      if (area_mode == PM_COVERAGE_LIT_AREA && !(vec3_dot(wi, surface_normal) * facing > 0.0f)) return 0.0f;
      return 1.0f / pm_fabsf(facing);
    }
    /* Past this surface: a crossing that hits two triangles (their shared edge, a duplicated
       face) is one crossing, or the parity would flip. */
    t_min = hit.t + gap;
  }
  return 0.0f;
}

/* Bounds of every probe ray of the footprint (footprint_probe_covered: over the disc, from
   reach above to reach below it along n, reach <= |a_n| + offset), widened so that a ray inside
   them cannot enter a box outside them by rounding: the box of the probes' traversal
   (scene_node_holding). */
PM_DEVICE void footprint_probe_bounds(const Footprint* f, Vec3 center, Vec3 n, float offset, Vec3* lo, Vec3* hi)
{
  Vec3 u = f->axis_u, v = f->axis_v;
  float reach = vec3_length(f->axis_n) + offset;
  Vec3 ext = vec3(pm_sqrtf(u.x * u.x + v.x * v.x) + pm_fabsf(n.x) * reach,
                  pm_sqrtf(u.y * u.y + v.y * v.y) + pm_fabsf(n.y) * reach,
                  pm_sqrtf(u.z * u.z + v.z * v.z) + pm_fabsf(n.z) * reach);
  float scale = pm_fmaxf(pm_fmaxf(pm_fabsf(center.x), pm_fabsf(center.y)), pm_fmaxf(pm_fabsf(center.z), 0.0f));
  float margin = 2.0f * offset + 1.0e-5f * (scale + pm_fmaxf(pm_fmaxf(ext.x, ext.y), ext.z));
  ext = vec3_add(ext, vec3_splat(margin));
  *lo = vec3_sub(center, ext);
  *hi = vec3_add(center, ext);
}

/* The first pattern is 16 of the 64 probes, so that a footprint at an edge traces the other 48
   and not 64 more: probes 5, 8, 11, 12, 14, 15, 30, 31, 37, 41, 42, 46, 47, 53, 56 and 57, chosen
   (bench/first_probe_subset.py) for what a pattern of 16 must do, tell an edge: of random
   straight rims, convex and concave corners and holes in a footprint about a covered centre, the
   kernel mass left uncovered where all 16 probes are covered is at most what a 16-point spiral of
   its own leaves (0.83 to 0.96 of it by kind, constant and Epanechnikov kernels;
   tests/unit/footprint_first_pattern_test.cpp). Probe j of the first pattern is byte j % 4 of
   word j / 4; the mask has bit q set for each (bit q % 32 of word q / 32). */
#define PM_FIRST_PROBES_0 0x0c0b0805u /* 5, 8, 11, 12 */
#define PM_FIRST_PROBES_1 0x1f1e0f0eu /* 14, 15, 30, 31 */
#define PM_FIRST_PROBES_2 0x2e2a2925u /* 37, 41, 42, 46 */
#define PM_FIRST_PROBES_3 0x3938352fu /* 47, 53, 56, 57 */
#define PM_FIRST_PROBE_MASK_LO 0xc000d920u
#define PM_FIRST_PROBE_MASK_HI 0x0320c620u

/* Probe j (< PM_FOOTPRINT_PROBES) of the first pattern, as a probe of the whole pattern. */
PM_DEVICE uint footprint_first_probe(uint j)
{
  uint word = j < 8u ? (j < 4u ? PM_FIRST_PROBES_0 : PM_FIRST_PROBES_1)
                     : (j < 12u ? PM_FIRST_PROBES_2 : PM_FIRST_PROBES_3);
  return (word >> (8u * (j & 3u))) & 0xffu;
}

/* Whether bit q of a mask of the whole pattern's probes, (lo, hi), is set. */
PM_DEVICE uint footprint_probe_bit(uint lo, uint hi, uint q) { return ((q < 32u ? lo : hi) >> (q & 31u)) & 1u; }

/* Whether probe q of the whole pattern belongs to the first. */
PM_DEVICE uint footprint_probe_in_first(uint q)
{
  return footprint_probe_bit(PM_FIRST_PROBE_MASK_LO, PM_FIRST_PROBE_MASK_HI, q);
}

/* Whether the cuts keep probe q of the whole pattern turned by `turn`; if so its disc point (x, y)
   and its kernel weight w. */
PM_DEVICE int footprint_probe_kept(const FootprintCut* cut, uint q, float turn, uint shape, float* x, float* y,
                                   float* w)
{
  footprint_probe_point(q, PM_FOOTPRINT_EDGE_PROBES, turn, x, y);
  if (!footprint_cut_keeps(cut, *x, *y)) return 0;
  *w = shape == PM_KERNEL_EPANECHNIKOV ? kernel_epanechnikov(*x * *x + *y * *y) : 1.0f;
  return 1;
}

/* Adds to *kept, *covered and *kept_probes the kept and covered kernel weights of the first
   pattern's probes (`rest` 0), or of the others of the whole pattern (`rest` 1; see
   footprint_covered_share). */
PM_DEVICE void footprint_probe_pattern(const KernelGlobals* kg, const Footprint* f, const FootprintCut* cut, Vec3 center,
                                       Vec3 n, float offset, float turn, uint shape, uint area_mode, Vec3 wi,
                                       uint rest, float* kept, float* covered, uint* kept_probes)
{
  uint count = rest ? PM_FOOTPRINT_EDGE_PROBES : PM_FOOTPRINT_PROBES;
  for (uint i = 0; i < count; ++i) {
    uint q = rest ? i : footprint_first_probe(i);
    if (rest && footprint_probe_in_first(q)) continue;
    float x, y, w;
    if (!footprint_probe_kept(cut, q, turn, shape, &x, &y, &w)) continue;
    *kept += w;
    ++*kept_probes;
    *covered += w * footprint_probe_covered(kg, 0, f, center, n, offset, x, y, area_mode, wi);
  }
}

/* Whether the first pattern's sums call for the second: partly covered, or (area modes) tilted. */
PM_DEVICE int footprint_pattern_at_edge(float kept, float covered) { return covered > 0.0f && covered != kept; }

/* The covered share from a pattern's sums. A footprint whose probes all miss (a sliver, a thin
   rail) still covers its own hit, which lies on the surface: it counts as half a probe's cell. */
PM_DEVICE float footprint_share_of(float kept, float covered, uint kept_probes)
{
  if (!(kept > 0.0f)) return 1.0f; /* no probe inside the cuts: the clip's kept fraction is all we know */
  return covered > 0.0f ? covered / kept : 0.5f / (float)kept_probes;
}

/* Share of the kernel mass kept by `cut` that lies over accepted surface, in (0, 1] (with an area
   mode, footprint_probe_covered: that surface's area over the kept disc's, up to 2).
   turn: the pattern's angle for this hit. A footprint that its first pattern finds partly covered
   (or, with an area mode, tilted) is measured with all PM_FOOTPRINT_EDGE_PROBES, the first
   pattern's and the others: the flux is divided by the share, and 1 / share is convex, so its
   noise is a bias (+1.0 % in Sponza's first bounce with 16 probes throughout, at the smallest
   footprints measured; docs/accuracy.md). Footprints wholly on a surface, most of them, cost the
   first pattern only. One work item measures the whole pattern here (the
   knn gather's region about a shading point); the photon map's footprints spread theirs over a
   work item per probe (footprint_probes.h). */
PM_DEVICE float footprint_covered_share(const KernelGlobals* kg, const Footprint* f, const FootprintCut* cut,
                                        Vec3 center, Vec3 n, float offset, float turn, uint shape, uint area_mode,
                                        Vec3 wi)
{
  float kept = 0.0f, covered = 0.0f;
  uint kept_probes = 0u;
  footprint_probe_pattern(kg, f, cut, center, n, offset, turn, shape, area_mode, wi, 0u, &kept, &covered,
                          &kept_probes);
  if (footprint_pattern_at_edge(kept, covered))
    footprint_probe_pattern(kg, f, cut, center, n, offset, turn, shape, area_mode, wi, 1u, &kept, &covered,
                            &kept_probes);
  return footprint_share_of(kept, covered, kept_probes);
}

#endif

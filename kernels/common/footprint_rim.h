/* A footprint that hangs over a straight rim (stage S3 and the gather, S6): the surface ends in
   a line across the disc, a ledge's or a doorway's convex edge, and the part beyond it is in the
   air. Dividing the flux by the covered share (footprint_coverage.h) keeps each photon's flux on
   its surface but not the density along the rim: a shading point at the rim gathers only
   footprints that lose half their disc or more, one a radius inland also gathers the boosted ones,
   so a uniform density reads 0.69 at the rim and 1.12 a radius in (docs/accuracy.md, "A clean
   convex edge: the arch"). Cutting at the rim and normalising about the shading point, as for a
   wall, needs the rim of every footprint within two radii of it, not only of those that cross it
   (a band of 0.93-0.96 remains; "Edges normalised at the shading point").

   The boundary kernel of density estimation by reflection: the part of the kernel beyond the rim
   is folded back across the rim line, a photon at q counting K(q) + K(q') at a shading point q
   whose mirror image across the line is q'. A photon's flux then lands on the surface whole
   (what hangs over is folded onto it), and a uniform density reads uniform up to the rim (exactly
   so for the exact line): the photons within a radius of a shading point and the mirror images of
   those beyond the rim tile the disc about it. A footprint that does not cross the rim folds
   nothing, so only the footprints that cross it need to know its line (those that cross it by a
   sliver that their first 16 probes miss do not fold: 0.95 at the rim on a ledge of uniform
   photons, tests/unit/footprint_probes_test.cpp).

   The line comes from the whole pattern of coverage probes (64, footprint_probes.h), which every
   footprint at an edge traces: of the lines that separate its covered probes from the uncovered
   ones, the one with the widest gap between them, placed halfway across that gap. It is
   accepted only where such a line exists and every covered probe lies on a surface of the
   footprint's own plane; a strip between two parallel rims folds at both (footprint_probed_strip
   below); a corner, a hole or a tilted face keeps the covered share, as do footprints that two
   walls cut (the rim takes the second cut slot; one wall's cut stays in the
   first, normalised about the shading point as before). The gather's side:
   footprint_fold_weight and footprint_gather_weight (gather_reach.h). */
#ifndef PM_FOOTPRINT_RIM_H
#define PM_FOOTPRINT_RIM_H

#include "footprint_clip.h"
#include "footprint_coverage.h"
#include "footprint_probes.h"

/* A covered probe's value over a surface in the footprint's own plane is 1 (PM_COVERAGE_CELLS),
   or 1 / cos of a tilt within rounding (PM_COVERAGE_LIT_AREA): the pattern's covered sum at most
   this times its covered probes' kernel weights. */
#define PM_RIM_FLAT_PROBES 1.001f
/* The search for the widest gap: turns of PM_RIM_COARSE_STEP within PM_RIM_COARSE_STEPS steps
   either side of the direction between the covered and uncovered probes' centroids (64 probes
   put it within a few degrees of the rim's normal), then of PM_RIM_FINE_STEP about the best
   (radians: 6 and 2 degrees). */
#define PM_RIM_COARSE_STEPS 2
#define PM_RIM_COARSE_STEP 0.1047198f
#define PM_RIM_FINE_STEPS 2
#define PM_RIM_FINE_STEP 0.0349066f

/* The whole pattern's probe points (turned by `turn`) as the edge fit reads them. On GPUs
   (PM_RIM_POINTS_RECOMPUTED, compat.h) the fit computes each point again where it needs it
   (footprint_probe_point, as the probes were traced): kept in arrays, the 64 points lived in
   local memory, 1.2 KB of stack a lane, and the launch took a third longer (docs/benchmarks.md,
   "The edge fit without its arrays"). On CPUs (PoCL) the arrays stay in cache and computing the
   points again made the footprint stage 28-51 % slower, so there they are kept. */
typedef struct {
  float turn;
#if !PM_RIM_POINTS_RECOMPUTED
  float x[PM_FOOTPRINT_EDGE_PROBES], y[PM_FOOTPRINT_EDGE_PROBES];
#endif
} RimPoints;

/* Keeps point q at (x, y) where the points are kept. */
PM_DEVICE void rim_point_keep(RimPoints* points, uint q, float x, float y)
{
#if PM_RIM_POINTS_RECOMPUTED
  (void)points;
  (void)q;
  (void)x;
  (void)y;
#else
  points->x[q] = x;
  points->y[q] = y;
#endif
}

/* Point q of the pattern. */
PM_DEVICE void rim_point(const RimPoints* points, uint q, float* x, float* y)
{
#if PM_RIM_POINTS_RECOMPUTED
  footprint_probe_point(q, PM_FOOTPRINT_EDGE_PROBES, points->turn, x, y);
#else
  *x = points->x[q];
  *y = points->y[q];
#endif
}

/* Where probe q lies along the unit normal (mx, my). */
PM_DEVICE float footprint_rim_along(const RimPoints* points, uint q, float mx, float my)
{
  float x, y;
  rim_point(points, q, &x, &y);
  return mx * x + my * y;
}

/* The gap along the unit normal (mx, my) between the farthest covered probe and the nearest
   uncovered one of the kept probes (bits `kept`) of the pattern at `points`, covered bits
   `covered`: positive where a line of that normal separates them (the uncovered beyond); their
   projections in *covered_far and *open_near. */
PM_DEVICE float footprint_rim_gap(const RimPoints* points, uint kept_lo, uint kept_hi, uint covered_lo,
                                  uint covered_hi, float mx, float my, float* covered_far, float* open_near)
{
  *covered_far = -2.0f;
  *open_near = 2.0f;
  for (uint q = 0; q < PM_FOOTPRINT_EDGE_PROBES; ++q) {
    if (!footprint_probe_bit(kept_lo, kept_hi, q)) continue;
    float along = footprint_rim_along(points, q, mx, my);
    if (footprint_probe_bit(covered_lo, covered_hi, q)) *covered_far = pm_fmaxf(*covered_far, along);
    else *open_near = pm_fminf(*open_near, along);
  }
  return *open_near - *covered_far;
}

/* The best turn about `centre` in `steps` steps of `step` either side: the widest gap. */
PM_DEVICE float footprint_rim_widest(const RimPoints* points, uint kept_lo, uint kept_hi, uint covered_lo,
                                     uint covered_hi, float centre, int steps, float step, float* widest)
{
  float best = centre;
  for (int i = -steps; i <= steps; ++i) {
    float a = centre + step * (float)i, s, c, far, near;
    pm_sincosf(a, &s, &c);
    float gap = footprint_rim_gap(points, kept_lo, kept_hi, covered_lo, covered_hi, c, s, &far, &near);
    if (gap > *widest) {
      *widest = gap;
      best = a;
    }
  }
  return best;
}

/* A strip: the surface between two parallel rims, both across the disc (a lintel's face, an
   arch's soffit, a moulding, a beam a footprint wide). Folding at both rims is reflecting across
   two parallel lines, whose images of a point repeat with a period of twice the strip's width: the
   shading point's images along the rims' normal m are 2 t - s + 2 j w and s + 2 j w (j != 0) for s
   = m . q, the near rim at t and the strip w wide. The gather sums the kernel over those within
   the unit disc (footprint_fold_weight, gather_reach.h), and a uniform density on the strip reads
   uniform across it, as the single rim's reflection does up to one rim. Narrower than this (of the
   radius), a strip's images would be too many for the gather and its probes too few to place it:
   it keeps the covered share. */
#define PM_STRIP_MIN_WIDTH 0.2f
/* The search for the strip's normal: turns of PM_STRIP_STEP within PM_STRIP_STEPS steps either side
   of the covered probes' minor axis (a strip's covered probes spread along it), then of
   PM_STRIP_FINE_STEP about the best (3 and 1 degrees). */
#define PM_STRIP_STEPS 4
#define PM_STRIP_STEP 0.0523599f
#define PM_STRIP_FINE_STEPS 2
#define PM_STRIP_FINE_STEP 0.0174533f

/* The band along the unit normal (mx, my) that the covered probes of the kept ones span, band[0]
   to band[1], and the nearest uncovered probe beyond either end, band[2] below and band[3] above
   (-2 and 2 where none is). Returns the narrower of the two gaps: negative where an uncovered
   probe lies within the band, or none beyond one of its ends (a single rim, or none). */
PM_DEVICE float footprint_strip_gap(const RimPoints* points, uint kept_lo, uint kept_hi, uint covered_lo,
                                    uint covered_hi, float mx, float my, float* band)
{
  band[0] = 2.0f;
  band[1] = -2.0f;
  band[2] = -2.0f;
  band[3] = 2.0f;
  for (uint q = 0; q < PM_FOOTPRINT_EDGE_PROBES; ++q) {
    if (!footprint_probe_bit(kept_lo, kept_hi, q) || !footprint_probe_bit(covered_lo, covered_hi, q)) continue;
    float along = footprint_rim_along(points, q, mx, my);
    band[0] = pm_fminf(band[0], along);
    band[1] = pm_fmaxf(band[1], along);
  }
  for (uint q = 0; q < PM_FOOTPRINT_EDGE_PROBES; ++q) {
    if (!footprint_probe_bit(kept_lo, kept_hi, q) || footprint_probe_bit(covered_lo, covered_hi, q)) continue;
    float along = footprint_rim_along(points, q, mx, my);
    if (along > band[1]) band[3] = pm_fminf(band[3], along);
    else if (along < band[0]) band[2] = pm_fmaxf(band[2], along);
    else return -1.0f;
  }
  if (!(band[2] > -2.0f) || !(band[3] < 2.0f)) return -1.0f;
  return pm_fminf(band[3] - band[1], band[0] - band[2]);
}

/* The best turn about `centre` in `steps` steps of `step` either side: the widest of the strip's
   narrower gaps. */
PM_DEVICE float footprint_strip_widest(const RimPoints* points, uint kept_lo, uint kept_hi, uint covered_lo,
                                       uint covered_hi, float centre, int steps, float step, float* widest)
{
  float best = centre, band[4];
  for (int i = -steps; i <= steps; ++i) {
    float a = centre + step * (float)i, s, c;
    pm_sincosf(a, &s, &c);
    float gap = footprint_strip_gap(points, kept_lo, kept_hi, covered_lo, covered_hi, c, s, band);
    if (gap > *widest) {
      *widest = gap;
      best = a;
    }
  }
  return best;
}

/* The strip that explains the kept probes (a wall's cut, a soffit's end at a jamb, stays in the
   first slot, normalised about the shading point): its rims' unit normal (mu, mv), the near rim's
   distance t and its width w, each rim halfway across its gap (footprint_stashed_rim says why).
   Returns whether one does. */
PM_DEVICE int footprint_probed_strip(const RimPoints* points, uint kept_lo, uint kept_hi, uint covered_lo,
                                     uint covered_hi, float* mu, float* mv, float* t, float* w)
{
  /* The covered probes' minor axis: a strip's covered probes spread along the strip. */
  float n = 0.0f, sx = 0.0f, sy = 0.0f, sxx = 0.0f, syy = 0.0f, sxy = 0.0f;
  for (uint q = 0; q < PM_FOOTPRINT_EDGE_PROBES; ++q) {
    if (!footprint_probe_bit(kept_lo, kept_hi, q) || !footprint_probe_bit(covered_lo, covered_hi, q)) continue;
    float x, y;
    rim_point(points, q, &x, &y);
    n += 1.0f;
    sx += x;
    sy += y;
    sxx += x * x;
    syy += y * y;
    sxy += x * y;
  }
  if (!(n > 2.0f)) return 0;
  float cxx = sxx / n - (sx / n) * (sx / n), cyy = syy / n - (sy / n) * (sy / n), cxy = sxy / n - (sx / n) * (sy / n);
  float angle = 0.5f * pm_atan2f(2.0f * cxy, cxx - cyy) + 1.5707963f;
  float widest = 0.0f, band[4];
  angle = footprint_strip_widest(points, kept_lo, kept_hi, covered_lo, covered_hi, angle, PM_STRIP_STEPS, PM_STRIP_STEP,
                                 &widest);
  angle = footprint_strip_widest(points, kept_lo, kept_hi, covered_lo, covered_hi, angle, PM_STRIP_FINE_STEPS,
                                 PM_STRIP_FINE_STEP, &widest);
  if (!(widest > 0.0f)) return 0;
  pm_sincosf(angle, mv, mu);
  footprint_strip_gap(points, kept_lo, kept_hi, covered_lo, covered_hi, *mu, *mv, band);
  /* The photon's own hit lies on the strip: the covered band reaches the centre either way. */
  float near_hi = pm_fmaxf(band[1], 0.0f), far_hi = pm_fminf(band[3], 1.0f);
  float near_lo = pm_fminf(band[0], 0.0f), far_lo = pm_fmaxf(band[2], -1.0f);
  if (!(far_hi > near_hi) || !(near_lo > far_lo)) return 0;
  *t = 0.5f * (near_hi + far_hi);
  *w = *t - 0.5f * (near_lo + far_lo);
  return *w >= PM_STRIP_MIN_WIDTH;
}

/* The rim, or the strip's two, of the footprint stashed at k (launch 5, after the second pattern),
   whose covered share is `share`: the rims' unit normal (mu, mv) in disc coordinates, the near
   rim's distance t and the strip's width w (0 for a single rim). Returns whether a straight rim
   or a strip explains the probes (see the top of this file and footprint_probed_strip) and the
   cut's second slot is free for it. */
PM_DEVICE int footprint_stashed_rim(const KernelGlobals* kg, const LaunchParams* p, uint k, float share, float* mu,
                                    float* mv, float* t, float* width)
{
  if (!footprint_stashed_at_edge(kg, k)) return 0; /* no second pattern */
  FootprintCut cut = footprint_stashed_cut(kg, k);
  if (cut.t[1] < 1.0f || !(share > 0.0f) || !(share < 1.0f)) return 0;
  PM_GLOBAL const uint* mask = PM_FOOTPRINT_EDGE_MASK(kg, p, k);
  uint covered_lo = mask[0], covered_hi = mask[1], kept_lo = 0u, kept_hi = 0u;
  RimPoints points;
  points.turn = kg->map_lo[k].w;
  /* The kept probes' bits, and every covered probe flat: the lanes' covered sums (each probe's
     weight times its value, which is at least 1 where covered) no more than the covered probes'
     weights. */
  float flat = 0.0f, measured = 0.0f;
  for (uint q = 0; q < PM_FOOTPRINT_EDGE_PROBES; ++q) {
    float x, y, w;
    int kept = footprint_probe_kept(&cut, q, points.turn, p->kernel_shape, &x, &y, &w);
    rim_point_keep(&points, q, x, y);
    if (!kept) continue;
    if (q < 32u) kept_lo |= 1u << q;
    else kept_hi |= 1u << (q - 32u);
    if (footprint_probe_bit(covered_lo, covered_hi, q)) flat += w;
  }
  PM_GLOBAL const float* values = PM_FOOTPRINT_PROBE_VALUES(kg, k);
  for (uint lane = 0; lane < PM_FOOTPRINT_PROBES; ++lane) measured += values[lane];
  if (measured > PM_RIM_FLAT_PROBES * flat) return 0;
  /* The widest gap, from the centroids' direction. */
  float cx = 0.0f, cy = 0.0f, ux = 0.0f, uy = 0.0f, covered = 0.0f, open = 0.0f;
  for (uint j = 0; j < PM_FOOTPRINT_EDGE_PROBES; ++j) {
    if (!footprint_probe_bit(kept_lo, kept_hi, j)) continue;
    uint bit = footprint_probe_bit(covered_lo, covered_hi, j);
    float x, y;
    rim_point(&points, j, &x, &y);
    cx += bit ? x : 0.0f;
    cy += bit ? y : 0.0f;
    ux += bit ? 0.0f : x;
    uy += bit ? 0.0f : y;
    covered += (float)bit;
    open += (float)(1u - bit);
  }
  if (!(covered > 0.0f) || !(open > 0.0f)) return 0;
  *width = 0.0f;
  float widest = 0.0f;
  float angle = pm_atan2f(uy / open - cy / covered, ux / open - cx / covered);
  angle = footprint_rim_widest(&points, kept_lo, kept_hi, covered_lo, covered_hi, angle, PM_RIM_COARSE_STEPS,
                               PM_RIM_COARSE_STEP, &widest);
  angle = footprint_rim_widest(&points, kept_lo, kept_hi, covered_lo, covered_hi, angle, PM_RIM_FINE_STEPS,
                               PM_RIM_FINE_STEP, &widest);
  if (!(widest > 0.0f))
    return footprint_probed_strip(&points, kept_lo, kept_hi, covered_lo, covered_hi, mu, mv, t, width);
  /* Halfway across the gap, and no nearer the centre than through it: the photon's own hit lies
     on the surface. Halfway, not where a straight cut keeps the measured covered share: that
     share reads a few hundredths of the radius beyond the rim (a strip's two rims, placed by it,
     read 0.94 of a uniform density on a strip 0.8 radii wide, halfway 1.00; a single rim 0.948
     at the rim and 1.004 a quarter of a radius in, halfway 0.952 and 0.999). */
  float far, near;
  pm_sincosf(angle, mv, mu);
  footprint_rim_gap(&points, kept_lo, kept_hi, covered_lo, covered_hi, *mu, *mv, &far, &near);
  far = pm_fmaxf(far, 0.0f);
  if (!(near > far)) return 0;
  *t = 0.5f * (far + pm_fminf(near, 1.0f));
  return 1;
}

/* What the edge fit (launch 5 of footprint_probes.h) leaves of a footprint at an edge, in the
   probes' values at k, which it is the last to read: the covered share, whether the footprint
   folds, and its rim (mu, mv, t, the strip's width). */
#define PM_EDGE_FIT_SHARE 0
#define PM_EDGE_FIT_FOLDED 1
#define PM_EDGE_FIT_RIM 2

/* Work item = entry e of the list of footprints at edges (items past its end do nothing: the
   launch is sized for every hit): its covered share and its rim. Done here, not in the store
   (launch 6) that runs over every hit, so that a warp's lanes all fit rims: in the store the
   fit's 64 probe positions left every lane with 2.4 KB of spills and most lanes waiting on the few
   at edges (docs/benchmarks.md, "The edge fit in a launch of its own"). */
PM_DEVICE void kernel_photon_footprint_rim(const KernelGlobals* kg, const LaunchParams* p, uint e)
{
  if (e >= kg->hit_record_count[0]) return;
  uint k = PM_FOOTPRINT_EDGE_LIST(kg, p)[e];
  float share = footprint_stashed_share(kg, p, k);
  float mu = 0.0f, mv = 0.0f, t = 0.0f, width = 0.0f;
  int folded = footprint_stashed_rim(kg, p, k, share, &mu, &mv, &t, &width);
  PM_GLOBAL float* fit = PM_FOOTPRINT_PROBE_VALUES(kg, k);
  fit[PM_EDGE_FIT_SHARE] = share;
  fit[PM_EDGE_FIT_FOLDED] = folded ? 1.0f : 0.0f;
  fit[PM_EDGE_FIT_RIM + 0] = mu;
  fit[PM_EDGE_FIT_RIM + 1] = mv;
  fit[PM_EDGE_FIT_RIM + 2] = t;
  fit[PM_EDGE_FIT_RIM + 3] = width;
}

/* The covered share of the footprint at k after the edge fit, and whether it folds at the rim it
   returns in (mu, mv, t, width): at an edge, the fit's; else the first pattern's share, no fold. */
PM_DEVICE int footprint_fitted_edge(const KernelGlobals* kg, uint k, float* share, float* mu, float* mv, float* t,
                                    float* width)
{
  *mu = *mv = *t = *width = 0.0f;
  if (!footprint_stashed_at_edge(kg, k)) {
    float4 first = kg->map_hi[k];
    *share = footprint_share_of(first.x, first.y, PM_AS_UINT(first.z));
    return 0;
  }
  PM_GLOBAL const float* fit = PM_FOOTPRINT_PROBE_VALUES(kg, k);
  *share = fit[PM_EDGE_FIT_SHARE];
  if (!(fit[PM_EDGE_FIT_FOLDED] > 0.0f)) return 0;
  *mu = fit[PM_EDGE_FIT_RIM + 0];
  *mv = fit[PM_EDGE_FIT_RIM + 1];
  *t = fit[PM_EDGE_FIT_RIM + 2];
  *width = fit[PM_EDGE_FIT_RIM + 3];
  return 1;
}

#endif

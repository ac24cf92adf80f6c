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

   The line comes from the second pattern of coverage probes (64, footprint_probes.h), which every
   footprint at an edge traces: of the lines that separate its covered probes from the uncovered
   ones, the one with the widest gap between them, and within that gap the distance from the
   centre of the straight cut that keeps the measured covered share of the kernel's mass. It is
   accepted only where such a line exists and every covered probe lies on a surface of the
   footprint's own plane; a corner, a strip, a hole or a tilted face keeps the covered share, as do
   footprints that two walls cut (the rim takes the second cut slot; one wall's cut stays in the
   first, normalised about the shading point as before). The gather's side:
   footprint_rim_mirror_r2 and footprint_gather_weight (gather_reach.h). */
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

/* Whether bit q of the 64-bit mask (lo, hi) is set. */
PM_DEVICE uint footprint_rim_bit(uint lo, uint hi, uint q) { return ((q < 32u ? lo : hi) >> (q & 31u)) & 1u; }

/* The gap along the unit normal (mx, my) between the farthest covered probe and the nearest
   uncovered one of the kept probes (bits `kept`) at (x, y), covered bits `covered`: positive where
   a line of that normal separates them (the uncovered beyond); their projections in *covered_far
   and *open_near. */
PM_DEVICE float footprint_rim_gap(const float* x, const float* y, uint kept_lo, uint kept_hi, uint covered_lo,
                                  uint covered_hi, float mx, float my, float* covered_far, float* open_near)
{
  *covered_far = -2.0f;
  *open_near = 2.0f;
  for (uint q = 0; q < PM_FOOTPRINT_EDGE_PROBES; ++q) {
    if (!footprint_rim_bit(kept_lo, kept_hi, q)) continue;
    float along = mx * x[q] + my * y[q];
    if (footprint_rim_bit(covered_lo, covered_hi, q)) *covered_far = pm_fmaxf(*covered_far, along);
    else *open_near = pm_fminf(*open_near, along);
  }
  return *open_near - *covered_far;
}

/* The best turn about `centre` in `steps` steps of `step` either side: the widest gap. */
PM_DEVICE float footprint_rim_widest(const float* x, const float* y, uint kept_lo, uint kept_hi, uint covered_lo,
                                     uint covered_hi, float centre, int steps, float step, float* widest)
{
  float best = centre;
  for (int i = -steps; i <= steps; ++i) {
    float a = centre + step * (float)i, s, c, far, near;
    pm_sincosf(a, &s, &c);
    float gap = footprint_rim_gap(x, y, kept_lo, kept_hi, covered_lo, covered_hi, c, s, &far, &near);
    if (gap > *widest) {
      *widest = gap;
      best = a;
    }
  }
  return best;
}

/* The kernel mass that the rim m . q <= t keeps of what the cut's first slot keeps (a wall, or
   nothing: footprint_clip.h), a fraction that grows with t. */
PM_DEVICE float footprint_rim_kept(const FootprintCut* cut, float mu, float mv, float t, uint shape)
{
  if (!(cut->t[0] < 1.0f)) return footprint_kept_one_cut(t, shape);
  float m_u[2], m_v[2], d[2];
  m_u[0] = cut->mu[0];
  m_v[0] = cut->mv[0];
  d[0] = cut->t[0];
  m_u[1] = mu;
  m_v[1] = mv;
  d[1] = t;
  return footprint_kept_fraction(m_u, m_v, d, 2, shape) / pm_fmaxf(cut->kept, 1.0e-6f);
}

/* Bisection steps for the rim's distance within the probes' gap (a few tenths of the radius wide:
   1/1024 of it at most). */
#define PM_RIM_OFFSET_STEPS 10

/* The distance t from the centre of the rim m . q <= t that keeps `share` of the kernel mass the
   cut keeps (footprint_rim_kept, which grows with t), by bisection within [lo, hi], the gap that
   the probes leave between the covered ones and the uncovered ones along m (the share's answer
   clamped to it). */
PM_DEVICE float footprint_rim_offset(const FootprintCut* cut, float mu, float mv, float share, float lo, float hi,
                                     uint shape)
{
  for (int step = 0; step < PM_RIM_OFFSET_STEPS; ++step) {
    float mid = 0.5f * (lo + hi);
    if (footprint_rim_kept(cut, mu, mv, mid, shape) < share) lo = mid;
    else hi = mid;
  }
  return 0.5f * (lo + hi);
}

/* The rim of the footprint stashed at k (launch 5, after the second pattern), whose covered share
   is `share`: its unit normal (mu, mv) in disc coordinates and distance t. Returns whether a
   straight rim explains the probes (see the top of this file) and the cut's second slot is free
   for it. */
PM_DEVICE int footprint_stashed_rim(const KernelGlobals* kg, const LaunchParams* p, uint k, float share, float* mu,
                                    float* mv, float* t)
{
  if (!footprint_stashed_at_edge(kg, k)) return 0; /* no second pattern */
  FootprintCut cut = footprint_stashed_cut(kg, k);
  if (cut.t[1] < 1.0f || !(share > 0.0f) || !(share < 1.0f)) return 0;
  PM_GLOBAL const uint* mask = PM_FOOTPRINT_EDGE_MASK(kg, p, k);
  uint covered_lo = mask[0], covered_hi = mask[1], kept_lo = 0u, kept_hi = 0u;
  float turn = kg->map_lo[k].w;
  float x[PM_FOOTPRINT_EDGE_PROBES], y[PM_FOOTPRINT_EDGE_PROBES], w[PM_FOOTPRINT_EDGE_PROBES];
  for (uint q = 0; q < PM_FOOTPRINT_EDGE_PROBES; ++q) {
    w[q] = 0.0f;
    if (footprint_probe_kept(&cut, q, PM_FOOTPRINT_EDGE_PROBES, turn, p->kernel_shape, &x[q], &y[q], &w[q])) {
      if (q < 32u) kept_lo |= 1u << q;
      else kept_hi |= 1u << (q - 32u);
    }
  }
  /* Every covered probe flat: the lanes' covered sums (each probe's weight times its value, which
     is at least 1 where covered) no more than the covered probes' weights. */
  PM_GLOBAL const float* values = PM_FOOTPRINT_PROBE_VALUES(kg, k);
  float flat = 0.0f, measured = 0.0f;
  for (uint q = 0; q < PM_FOOTPRINT_EDGE_PROBES; ++q)
    if (footprint_rim_bit(covered_lo, covered_hi, q)) flat += w[q];
  for (uint lane = 0; lane < PM_FOOTPRINT_PROBES; ++lane) measured += values[lane];
  if (measured > PM_RIM_FLAT_PROBES * flat) return 0;
  /* The widest gap, from the centroids' direction. */
  float cx = 0.0f, cy = 0.0f, ux = 0.0f, uy = 0.0f, covered = 0.0f, open = 0.0f;
  for (uint j = 0; j < PM_FOOTPRINT_EDGE_PROBES; ++j) {
    if (!footprint_rim_bit(kept_lo, kept_hi, j)) continue;
    uint bit = footprint_rim_bit(covered_lo, covered_hi, j);
    cx += bit ? x[j] : 0.0f;
    cy += bit ? y[j] : 0.0f;
    ux += bit ? 0.0f : x[j];
    uy += bit ? 0.0f : y[j];
    covered += (float)bit;
    open += (float)(1u - bit);
  }
  if (!(covered > 0.0f) || !(open > 0.0f)) return 0;
  float widest = 0.0f;
  float angle = pm_atan2f(uy / open - cy / covered, ux / open - cx / covered);
  angle = footprint_rim_widest(x, y, kept_lo, kept_hi, covered_lo, covered_hi, angle, PM_RIM_COARSE_STEPS,
                               PM_RIM_COARSE_STEP, &widest);
  angle = footprint_rim_widest(x, y, kept_lo, kept_hi, covered_lo, covered_hi, angle, PM_RIM_FINE_STEPS,
                               PM_RIM_FINE_STEP, &widest);
  if (!(widest > 0.0f)) return 0;
  /* Within the gap, and no nearer the centre than through it: the photon's own hit lies on the
     surface (a hit on the rim itself reads a share of a half within the probes' noise). */
  float far, near;
  pm_sincosf(angle, mv, mu);
  footprint_rim_gap(x, y, kept_lo, kept_hi, covered_lo, covered_hi, *mu, *mv, &far, &near);
  far = pm_fmaxf(far, 0.0f);
  if (!(near > far)) return 0;
  *t = footprint_rim_offset(&cut, *mu, *mv, share, far, pm_fminf(near, 1.0f), p->kernel_shape);
  return 1;
}

#endif

/* The photon map's coverage probes, one work item per probe (stage S3, footprint_coverage.h says
   what a probe measures). Traced in a loop per footprint, the probes left a warp's lanes on 32
   different footprints, each with its own rays, cut and edge: the footprint stage ran at 7.6 of
   32 active threads per warp instruction and was most of the production frame (docs/benchmarks.md).
   Here the PM_FOOTPRINT_PROBES lanes of a footprint trace its probes together: parallel rays a
   footprint apart, which visit the same nodes and triangles.

   The stage's launches over the sorted hits (render/photon/photon_mapping.cpp runs them):
   1. photon_footprint (photon_footprint.h): the footprint and its cuts, stashed at k;
   2. photon_footprint_probe: probe j of hit k's first pattern, its covered value kept;
   3. photon_footprint_pattern: the first pattern's sums, and whether the footprint is at an edge:
      those that are join a list (in any order: each writes only its own values);
   4. photon_footprint_edge_probe: the second pattern of the listed footprints, the 48 probes of
      the whole pattern that the first did not trace, so that a warp's lanes all work on
      footprints at edges: taken in the order of their angles, lane j tracing those of rank j,
      j + 16, j + 32 (round r a third of the disc, whose probes mostly lie on one side of the
      edge) and keeping their weighted sum with the first pattern's probe j;
   5. photon_footprint_rim (footprint_rim.h): over the list, the share from those sums and the
      rim the footprint folds at, left in its probes' values;
   6. photon_footprint_store (photon_footprint.h): the gather data.
   On devices whose work items do not run in lockstep (CPUs: PoCL) one work item per footprint
   runs launches 2 to 4 for it (photon_footprint_coverage), the same functions in the same order:
   there the probes' own launches only added work items (PoCL, Sponza: the footprint stage 20-40 %
   slower).

   What launch 1 stashes at k, in the gather arrays that launch 6 then overwrites:
     map_row_u, map_row_v, map_row_n: (a_u, mu_0), (a_v, mv_0), (a_n, t_0), the scaled semiaxes
       (their w are the first cut's, as stored for the gather);
     map_cut: (mu_1, mv_1, t_1, the kept fraction);  map_center: as stored for the gather;
     map_lo: (the unit normal, the pattern's turn);
     map_power: (the flux, the scene BVH node under which the probes' triangles lie);
     map_incident: as stored for the gather;  map_hi: launch 3's sums.
   The probes' values, PM_FOOTPRINT_PROBES floats per hit at 16 k, after them the list of
   footprints at edges, and after that two words per hit, the second pattern's covered probes as
   bits (for the rim's line, footprint_rim.h), live in the hit records, which launch 1 has read
   for the last time (80 bytes a record, at least one record per valid hit: 19 of the 20 words);
   the list's length is counted in hit_record_count[0], which the host has read and set to 0. */
#ifndef PM_FOOTPRINT_PROBES_H
#define PM_FOOTPRINT_PROBES_H

#include "footprint_coverage.h"
#include "kernel_globals.h"
#include "ray.h"

/* Rounds of PM_FOOTPRINT_PROBES lanes that trace the second pattern: the whole pattern less the
   first. */
#define PM_FOOTPRINT_EDGE_ROUNDS ((PM_FOOTPRINT_EDGE_PROBES - PM_FOOTPRINT_PROBES) / PM_FOOTPRINT_PROBES)
/* The probes' values of hit k. */
#define PM_FOOTPRINT_PROBE_VALUES(kg, k) ((PM_GLOBAL float*)(kg)->hit_records + PM_FOOTPRINT_PROBES * (k))

/* The list of footprints at edges, after the probes' values of hit_count hits. */
#define PM_FOOTPRINT_EDGE_LIST(kg, p) ((PM_GLOBAL uint*)(kg)->hit_records + PM_FOOTPRINT_PROBES * (p)->hit_count)

/* The bits of hit k's probes of the whole pattern that found a surface (bit q % 32 of word q / 32),
   after the list. */
#define PM_FOOTPRINT_EDGE_MASK(kg, p, k) \
  ((PM_GLOBAL uint*)(kg)->hit_records + (PM_FOOTPRINT_PROBES + 1u) * (p)->hit_count + 2u * (k))

/* The probe after probe q of the whole pattern in the order of their angles about the centre
   (golden angle * q, turned alike for every probe). By the three-distance theorem the angles of
   q golden-angle steps leave between neighbours the gaps of 55, 34 and 21 steps (Fibonacci
   numbers, 21 + 34 = 55): the next angle is that of q + 55, else q - 34, else q + 21, the first
   that lies in the pattern (tests/unit/footprint_probes_test.cpp checks the order). Only for
   PM_FOOTPRINT_EDGE_PROBES = 64. */
PM_DEVICE uint footprint_edge_probe_next(uint q)
{
  return q + 55u < PM_FOOTPRINT_EDGE_PROBES ? q + 55u : (q >= 34u ? q - 34u : q + 21u);
}

/* The second pattern's probe after probe q in the order of their angles: the next that the first
   pattern did not trace. Probe 0, the first by angle, is not in the first pattern. */
PM_DEVICE uint footprint_second_probe_next(uint q)
{
  do q = footprint_edge_probe_next(q);
  while (footprint_probe_in_first(q));
  return q;
}

/* The footprint stashed at k by photon_footprint. */
PM_DEVICE Footprint footprint_stashed(const KernelGlobals* kg, uint k)
{
  Footprint f;
  f.axis_u = vec3_from_float4(kg->map_row_u[k]);
  f.axis_v = vec3_from_float4(kg->map_row_v[k]);
  f.axis_n = vec3_from_float4(kg->map_row_n[k]);
  return f;
}

/* The cuts stashed at k (their kept fraction included). */
PM_DEVICE FootprintCut footprint_stashed_cut(const KernelGlobals* kg, uint k)
{
  FootprintCut cut = footprint_uncut();
  float4 second = kg->map_cut[k];
  cut.mu[0] = kg->map_row_u[k].w;
  cut.mv[0] = kg->map_row_v[k].w;
  cut.t[0] = kg->map_row_n[k].w;
  cut.mu[1] = second.x;
  cut.mv[1] = second.y;
  cut.t[1] = second.z;
  cut.kept = second.w;
  return cut;
}

/* Covered value of probe q of the whole pattern of the footprint stashed at k
   (footprint_probe_covered), and in w its kernel weight; both 0 where the cuts drop it. */
PM_DEVICE float footprint_stashed_probe(const KernelGlobals* kg, const LaunchParams* p, const Footprint* f,
                                        const FootprintCut* cut, uint k, uint q, float* w)
{
  float4 normal_turn = kg->map_lo[k];
  float x, y;
  *w = 0.0f;
  if (!footprint_probe_kept(cut, q, normal_turn.w, p->kernel_shape, &x, &y, w)) return 0.0f;
  Vec3 center = vec3_from_float4(kg->map_center[k]);
  return footprint_probe_covered(kg, (int)PM_AS_UINT(kg->map_power[k].w), f, center, vec3_from_float4(normal_turn),
                                 ray_offset_distance(center, 0.0f, p->ray_epsilon), x, y,
                                 p->facet_weighting ? PM_COVERAGE_LIT_AREA : PM_COVERAGE_CELLS,
                                 vec3_from_float4(kg->map_incident[k]));
}

/* Work item = PM_FOOTPRINT_PROBES * (k - batch_first) + j: probe j of hit k's first pattern. Its
   covered value alone is kept (launch 3 weighs it, in the order of footprint_probe_pattern). */
PM_DEVICE void kernel_photon_footprint_probe(const KernelGlobals* kg, const LaunchParams* p, uint index)
{
  uint k = p->batch_first + index / PM_FOOTPRINT_PROBES, j = index % PM_FOOTPRINT_PROBES;
  Footprint f = footprint_stashed(kg, k);
  FootprintCut cut = footprint_stashed_cut(kg, k);
  float w;
  PM_FOOTPRINT_PROBE_VALUES(kg, k)[j] = footprint_stashed_probe(kg, p, &f, &cut, k, footprint_first_probe(j), &w);
}

/* The first pattern's kept and covered weights of the footprint at k, summed in
   footprint_probe_pattern's order from its probes' values, in map_hi[k] = (kept, covered, kept
   probes, at an edge). Returns whether the footprint is at an edge. */
PM_DEVICE uint footprint_first_pattern_sums(const KernelGlobals* kg, const LaunchParams* p, uint k)
{
  FootprintCut cut = footprint_stashed_cut(kg, k);
  float turn = kg->map_lo[k].w;
  PM_GLOBAL const float* values = PM_FOOTPRINT_PROBE_VALUES(kg, k);
  float kept = 0.0f, covered = 0.0f;
  uint kept_probes = 0u;
  for (uint j = 0; j < PM_FOOTPRINT_PROBES; ++j) {
    float x, y, w;
    if (!footprint_probe_kept(&cut, footprint_first_probe(j), turn, p->kernel_shape, &x, &y, &w)) continue;
    kept += w;
    ++kept_probes;
    covered += w * values[j];
  }
  uint at_edge = (uint)footprint_pattern_at_edge(kept, covered);
  kg->map_hi[k] = PM_MAKE_FLOAT4(kept, covered, PM_UINT_AS_FLOAT(kept_probes), PM_UINT_AS_FLOAT(at_edge));
  if (at_edge) {
    PM_GLOBAL uint* mask = PM_FOOTPRINT_EDGE_MASK(kg, p, k);
    mask[0] = 0u;
    mask[1] = 0u;
  }
  return at_edge;
}

/* Work item = hit k: the first pattern's sums (footprint_first_pattern_sums); a footprint at an
   edge joins the list. */
PM_DEVICE void kernel_photon_footprint_pattern(const KernelGlobals* kg, const LaunchParams* p, uint k)
{
  if (footprint_first_pattern_sums(kg, p, k))
    PM_FOOTPRINT_EDGE_LIST(kg, p)[pm_atomic_add_u32(&kg->hit_record_count[0], 1u)] = k;
}

/* Sets bit q of the mask of the footprint at k: probe q of the whole pattern found a surface. */
PM_DEVICE void footprint_mark_covered(const KernelGlobals* kg, const LaunchParams* p, uint k, uint q)
{
  pm_atomic_or_u32(PM_FOOTPRINT_EDGE_MASK(kg, p, k) + (q >> 5), 1u << (q & 31u));
}

/* Lane j's weighted covered sum for the footprint at k: the first pattern's probe j, whose value
   launch 2 left in the lane's slot, and the second pattern's probes of rank j + PM_FOOTPRINT_PROBES
   r, r < PM_FOOTPRINT_EDGE_ROUNDS, in the order of their angles. The probes that find a surface
   set their bits in the footprint's mask. */
PM_DEVICE float footprint_edge_lane_sum(const KernelGlobals* kg, const LaunchParams* p, uint k, uint j)
{
  Footprint f = footprint_stashed(kg, k);
  FootprintCut cut = footprint_stashed_cut(kg, k);
  uint first = footprint_first_probe(j);
  float x, y, w;
  float covered = 0.0f, value = PM_FOOTPRINT_PROBE_VALUES(kg, k)[j];
  if (footprint_probe_kept(&cut, first, kg->map_lo[k].w, p->kernel_shape, &x, &y, &w)) covered = w * value;
  if (value > 0.0f) footprint_mark_covered(kg, p, k, first);
  uint q = 0u;
  for (uint step = 0; step < j; ++step) q = footprint_second_probe_next(q);
  for (uint r = 0; r < PM_FOOTPRINT_EDGE_ROUNDS; ++r) {
    float c = footprint_stashed_probe(kg, p, &f, &cut, k, q, &w);
    covered += w * c; /* a dropped probe adds 0 */
    if (c > 0.0f) footprint_mark_covered(kg, p, k, q);
    for (uint step = 0; step < PM_FOOTPRINT_PROBES; ++step) q = footprint_second_probe_next(q);
  }
  return covered;
}

/* Work item = PM_FOOTPRINT_PROBES * (e - batch_first) + j for entry e of the list of footprints at
   edges (items past its end do nothing: the launch is sized for every hit): lane j's sum of the
   second pattern (footprint_edge_lane_sum). */
PM_DEVICE void kernel_photon_footprint_edge_probe(const KernelGlobals* kg, const LaunchParams* p, uint index)
{
  uint e = p->batch_first + index / PM_FOOTPRINT_PROBES, j = index % PM_FOOTPRINT_PROBES;
  if (e >= kg->hit_record_count[0]) return;
  uint k = PM_FOOTPRINT_EDGE_LIST(kg, p)[e];
  PM_FOOTPRINT_PROBE_VALUES(kg, k)[j] = footprint_edge_lane_sum(kg, p, k, j);
}

/* Work item = hit k, on devices whose work items do not run in lockstep: launches 2 to 4 for the
   footprint at k in one work item, one probe or lane after another, leaving what they leave (a
   footprint at an edge joins the list once its second pattern is summed). */
PM_DEVICE void kernel_photon_footprint_coverage(const KernelGlobals* kg, const LaunchParams* p, uint k)
{
  Footprint f = footprint_stashed(kg, k);
  FootprintCut cut = footprint_stashed_cut(kg, k);
  PM_GLOBAL float* values = PM_FOOTPRINT_PROBE_VALUES(kg, k);
  for (uint j = 0; j < PM_FOOTPRINT_PROBES; ++j) {
    float w;
    values[j] = footprint_stashed_probe(kg, p, &f, &cut, k, footprint_first_probe(j), &w);
  }
  if (!footprint_first_pattern_sums(kg, p, k)) return;
  for (uint j = 0; j < PM_FOOTPRINT_PROBES; ++j) values[j] = footprint_edge_lane_sum(kg, p, k, j);
  PM_FOOTPRINT_EDGE_LIST(kg, p)[pm_atomic_add_u32(&kg->hit_record_count[0], 1u)] = k;
}

/* Whether launch 3 found the footprint at k partly covered (and launch 4 traced its second
   pattern). */
PM_DEVICE int footprint_stashed_at_edge(const KernelGlobals* kg, uint k) { return PM_AS_UINT(kg->map_hi[k].w) != 0u; }

/* The covered share of the footprint at k from launches 3 and 4 (footprint_covered_share's
   answer; at an edge the whole pattern's weights are summed per lane, then over the lanes). */
PM_DEVICE float footprint_stashed_share(const KernelGlobals* kg, const LaunchParams* p, uint k)
{
  float4 first = kg->map_hi[k];
  float kept = first.x, covered = first.y;
  uint kept_probes = PM_AS_UINT(first.z);
  if (footprint_stashed_at_edge(kg, k)) {
    FootprintCut cut = footprint_stashed_cut(kg, k);
    float turn = kg->map_lo[k].w;
    PM_GLOBAL const float* values = PM_FOOTPRINT_PROBE_VALUES(kg, k);
    kept = 0.0f;
    covered = 0.0f;
    kept_probes = 0u;
    for (uint q = 0; q < PM_FOOTPRINT_EDGE_PROBES; ++q) {
      float x, y, w;
      if (!footprint_probe_kept(&cut, q, turn, p->kernel_shape, &x, &y, &w)) continue;
      kept += w;
      ++kept_probes;
    }
    for (uint j = 0; j < PM_FOOTPRINT_PROBES; ++j) covered += values[j];
  }
  return footprint_share_of(kept, covered, kept_probes);
}

#endif

/* Stage S3 (end of section 4.3): turns each recorded hit into its footprint ellipsoid, clipped
   at the geometry around the hit (footprint_clip.h), and stores what the photon map and the
   gather need: the ellipsoid's AABB, the rows of its inverse basis (so the gather's containment
   test is three dot products), and flux / area. The radius estimator uses the same path with a
   sphere of the fixed radius, knn a disc of r_max (its normal only). It runs after the sort,
   over the valid hits only, in sorted order; a tile reduction then gives the total footprint
   area for T_auto (photon_map_stage.h). */
#ifndef PM_PHOTON_FOOTPRINT_H
#define PM_PHOTON_FOOTPRINT_H

#include "footprint.h"
#include "footprint_clip.h"
#include "footprint_coverage.h"
#include "footprint_probes.h"
#include "footprint_rim.h"
#include "kernel_globals.h"
#include "photon_map.h"
#include "photon_trace.h"

/* Footprint of one hit under the estimator in use, before clipping: the photon-differential
   ellipsoid (pd), a sphere of the fixed radius (radius, the multi-pass paper's gather), or, for
   knn, a disc of the search radius r_max, of which the knn gather reads only the normal (its
   region is its own, knn_gather.h). (The radius
   estimator keeps its sphere: a flat disc cut by a curved surface loses the ring near its rim,
   -10 % in the closed diffuse sphere of tests/opencl/analytic_sphere_test.cpp.) */
PM_DEVICE Footprint hit_footprint(const KernelGlobals* kg, const LaunchParams* p, uint flags, uint record)
{
  Vec3 n = vec3_from_float4(photon_hit_part(kg, record, PM_RECORD_NORMAL));
  if (p->estimator != PM_ESTIMATOR_PD) {
    int radius = p->estimator == PM_ESTIMATOR_RADIUS;
    float r = radius ? p->gather_radius : p->rmax;
    Footprint f;
    Vec3 t, b;
    vec3_onb(n, &t, &b);
    f.axis_u = vec3_scale(t, r);
    f.axis_v = vec3_scale(b, r);
    f.axis_n = vec3_scale(n, radius ? r : PM_FOOTPRINT_NORMAL_RATIO * r);
    return f;
  }
  int caustic = (flags & PM_HIT_CAUSTIC) != 0u;
  float delta = photon_hit_part(kg, record, PM_RECORD_INCIDENT).w;
  Footprint f = footprint_from_differentials(vec3_from_float4(photon_hit_part(kg, record, PM_RECORD_DP_U)),
                                             vec3_from_float4(photon_hit_part(kg, record, PM_RECORD_DP_V)),
                                             n, delta, p->smoothing, p->rmax, caustic);
  if (p->footprint_thickness > 0.0f) footprint_set_thickness(&f, p->footprint_thickness);
  return f;
}

/* Work item = sorted position k < hit_count: the footprint of hit sorted_slots[k] (scaled for a
   shrinking pass), clipped at the geometry around it (footprint_clip.h), stashed at k for the
   coverage probes and photon_footprint_store (the layout: footprint_probes.h). */
PM_DEVICE void kernel_photon_footprint(const KernelGlobals* kg, const LaunchParams* p, uint k)
{
  uint slot = kg->sorted_slots[k];
  uint slot_word = kg->hit_slots[slot];
  uint hit_flags = slot_word & PM_HIT_SLOT_FLAGS, record = photon_hit_record(slot_word);
  Vec3 center = vec3_from_float4(photon_hit_part(kg, record, PM_RECORD_POSITION));
  Vec3 normal = vec3_normalize(vec3_from_float4(photon_hit_part(kg, record, PM_RECORD_NORMAL)));
  Footprint f = hit_footprint(kg, p, hit_flags, record);
  /* Progressive shrink (docs/progressive.md): every footprint of this pass scaled alike (knn's
     reach is r_max, which the host already shrank). */
  if (p->estimator != PM_ESTIMATOR_KNN) {
    f.axis_u = vec3_scale(f.axis_u, p->footprint_scale);
    f.axis_v = vec3_scale(f.axis_v, p->footprint_scale);
    f.axis_n = vec3_scale(f.axis_n, p->footprint_scale);
  }
  FootprintCut cut = footprint_uncut();
  /* knn's region is clipped about each shading point instead (knn_gather.h). */
  if (p->footprint_clip && p->estimator != PM_ESTIMATOR_KNN)
    cut = footprint_clip(kg, &f, center, normal,
                         ray_offset_distance(center, 0.0f, p->ray_epsilon), p->kernel_shape);
  /* The probe pattern's turn: drawn per photon and record, the same on every backend and for any
     slot layout. */
  uint per_photon = p->hit_slots_per_photon > 0u ? p->hit_slots_per_photon : 1u;
  uint frame = p->photon_sequence == PM_PHOTON_SEQUENCE_HALTON ? 0u : p->photon_frame; /* the same every frame */
  float turn = PM_TWO_PI * rng_to_unit(rng_bits4(p->seed, frame, p->photon_offset + slot / per_photon,
                                                 slot % per_photon, PM_STREAM_FOOTPRINT_PROBE,
                                                 p->photon_offset_hi).b0);
  /* The probes' traversal starts below the nodes that hold nothing near the footprint. */
  int probe_root = 0;
  if (p->footprint_coverage && p->estimator != PM_ESTIMATOR_KNN) {
    Vec3 lo, hi;
    footprint_probe_bounds(&f, center, normal, ray_offset_distance(center, 0.0f, p->ray_epsilon), &lo, &hi);
    probe_root = scene_node_holding(kg, lo, hi);
  }
  uint flags = hit_flags | (cut.t[1] < 1.0f ? PM_HIT_SECOND_CUT : 0u);
  kg->map_row_u[k] = vec3_to_float4(f.axis_u, cut.mu[0]);
  kg->map_row_v[k] = vec3_to_float4(f.axis_v, cut.mv[0]);
  kg->map_row_n[k] = vec3_to_float4(f.axis_n, cut.t[0]);
  kg->map_cut[k] = PM_MAKE_FLOAT4(cut.mu[1], cut.mv[1], cut.t[1], cut.kept);
  kg->map_center[k] = vec3_to_float4(center, PM_UINT_AS_FLOAT(flags));
  kg->map_lo[k] = vec3_to_float4(normal, turn);
  kg->map_power[k] = vec3_to_float4(photon_hit_flux(kg, record), PM_UINT_AS_FLOAT((uint)probe_root));
  kg->map_incident[k] = photon_hit_part(kg, record, PM_RECORD_INCIDENT);
}

/* Work item = sorted position k < hit_count: the gather data of the footprint stashed at k,
   written at k, so the photon map's leaves and the gather read contiguous memory: its bounds,
   the rows of the inverse of its basis, whose w hold the first cut (mu, mv, t): the gather
   accepts x where mu (row_u . (x - hit)) + mv (row_v . (x - hit)) <= t, a second cut in map_cut
   (flagged PM_HIT_SECOND_CUT), and flux / (area * covered share); the gather divides by the
   kernel mass the cuts keep about each shading point. For knn the bounds are the point box hit
   +- r_max the knn traversal expects, and the power is the flux (the knn gather divides by its
   own area). */
PM_DEVICE void kernel_photon_footprint_store(const KernelGlobals* kg, const LaunchParams* p, uint k)
{
  Footprint f = footprint_stashed(kg, k);
  Vec3 center = vec3_from_float4(kg->map_center[k]);
  float kept = kg->map_cut[k].w;
  int probed = p->footprint_coverage && p->estimator != PM_ESTIMATOR_KNN;
  /* A footprint over a straight rim, or over a strip's two, folds there (footprint_rim.h, which
     the edge fit has found): its flux is spread over the whole ellipse, the overhang folded back
     onto the surface by the gather. */
  float coverage = 1.0f, rim_mu = 0.0f, rim_mv = 0.0f, rim_t = 0.0f, strip_width = 0.0f;
  int folded = probed && footprint_fitted_edge(kg, k, &coverage, &rim_mu, &rim_mv, &rim_t, &strip_width);
  Vec3 lo, hi;
  footprint_bounds(f, center, &lo, &hi);
  /* The footprint's area on the surface (T_auto, the histogram); the flux is divided by the
     ellipse's area times its coverage only (folded, by the whole ellipse's): the gather divides by
     the kept mass about each shading point (footprint_kept_about, gather_reach.h). */
  float area = footprint_area(f) * kept * coverage;
  float spread = footprint_area(f) * (folded ? 1.0f : coverage);

  /* Inverse of the basis (a_u, a_v, a_n): its rows are the reciprocal basis vectors. */
  Vec3 c_vn = vec3_cross(f.axis_v, f.axis_n), c_nu = vec3_cross(f.axis_n, f.axis_u), c_uv = vec3_cross(f.axis_u, f.axis_v);
  float det = vec3_dot(f.axis_u, c_vn);
  float inv_det = det != 0.0f && pm_isfinite(det) ? 1.0f / det : 0.0f; /* singular: contains nothing */
  Vec3 flux = vec3_from_float4(kg->map_power[k]);
  Vec3 power = area > 0.0f && spread > 0.0f ? vec3_scale(flux, 1.0f / spread) : vec3_splat(0.0f);
  if (inv_det == 0.0f || !pm_isfinite(power.x + power.y + power.z)) {
    power = vec3_splat(0.0f);
    area = 0.0f;
  }
  if (p->estimator == PM_ESTIMATOR_KNN) {
    lo = vec3_sub(center, vec3_splat(p->rmax));
    hi = vec3_add(center, vec3_splat(p->rmax));
    power = flux;
    area = 0.0f; /* no footprint area: T_auto stays at 1 for the knn map, as before clipping */
  }
  kg->map_lo[k] = vec3_to_float4(lo, area);
  kg->map_hi[k] = vec3_to_float4(hi, 0.0f);
  kg->map_row_u[k] = vec3_to_float4(vec3_scale(c_vn, inv_det), kg->map_row_u[k].w);
  kg->map_row_v[k] = vec3_to_float4(vec3_scale(c_nu, inv_det), kg->map_row_v[k].w);
  kg->map_row_n[k] = vec3_to_float4(vec3_scale(c_uv, inv_det), kg->map_row_n[k].w);
  if (folded) {
    /* The rim in the second slot, which the edge fit found free, and a strip's width
       (footprint_rim.h). */
    kg->map_cut[k] = PM_MAKE_FLOAT4(rim_mu, rim_mv, rim_t, strip_width);
    kg->map_center[k].w = PM_UINT_AS_FLOAT(PM_AS_UINT(kg->map_center[k].w) | PM_HIT_RIM);
  } else {
    kg->map_cut[k].w = 0.0f;
  }
  kg->map_power[k] = vec3_to_float4(power, 0.0f);
}

#endif

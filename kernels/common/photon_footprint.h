/* Stage S3 (end of section 4.3): turns each recorded hit into its footprint ellipsoid, and
   stores what the photon map and the gather need: the ellipsoid's AABB, the rows of its inverse
   basis (so the gather's containment test is three dot products), and flux / area. The radius
   estimator uses the same path with a sphere of the fixed radius. A tile reduction
   (photon_map_stage.h) then gives the hits' bounds, count and total footprint area. */
#ifndef PM_PHOTON_FOOTPRINT_H
#define PM_PHOTON_FOOTPRINT_H

#include "footprint.h"
#include "kernel_globals.h"
#include "photon_map.h"
#include "photon_trace.h"

PM_DEVICE int hit_is_valid(float4 normal) { return (PM_AS_UINT(normal.w) & PM_HIT_VALID) != 0u; }

/* Footprint of one hit under the estimator in use. */
PM_DEVICE Footprint hit_footprint(const KernelGlobals* kg, const LaunchParams* p, uint slot)
{
  float4 n4 = kg->hit_normal[slot];
  Vec3 n = vec3_from_float4(n4);
  if (p->estimator == PM_ESTIMATOR_RADIUS) {
    Footprint f;
    Vec3 t, b;
    vec3_onb(n, &t, &b);
    f.axis_u = vec3_scale(t, p->gather_radius);
    f.axis_v = vec3_scale(b, p->gather_radius);
    f.axis_n = vec3_scale(n, p->gather_radius);
    return f;
  }
  int caustic = (PM_AS_UINT(n4.w) & PM_HIT_CAUSTIC) != 0u;
  float delta = kg->hit_incident[slot].w;
  return footprint_from_differentials(vec3_from_float4(kg->hit_dp_u[slot]), vec3_from_float4(kg->hit_dp_v[slot]), n,
                                      delta, p->smoothing, p->rmax, caustic);
}

PM_DEVICE void kernel_photon_footprint(const KernelGlobals* kg, const LaunchParams* p, uint slot)
{
  float4 n4 = kg->hit_normal[slot];
  if (!hit_is_valid(n4)) {
    kg->footprint_lo[slot] = PM_MAKE_FLOAT4(1e30f, 1e30f, 1e30f, 0.0f);
    kg->footprint_hi[slot] = PM_MAKE_FLOAT4(-1e30f, -1e30f, -1e30f, 0.0f);
    kg->footprint_center[slot] = n4; /* w carries the (empty) flags */
    return;
  }
  Vec3 center = vec3_from_float4(kg->hit_position[slot]);
  if (p->estimator == PM_ESTIMATOR_KNN) {
    /* Point boxes grown by the search radius; the k-NN gather divides by its own area. */
    kg->footprint_lo[slot] = vec3_to_float4(vec3_sub(center, vec3_splat(p->rmax)), 0.0f);
    kg->footprint_hi[slot] = vec3_to_float4(vec3_add(center, vec3_splat(p->rmax)), 0.0f);
    kg->footprint_center[slot] = vec3_to_float4(center, n4.w);
    kg->footprint_power[slot] = kg->hit_flux[slot];
    return;
  }
  Footprint f = hit_footprint(kg, p, slot);
  /* Progressive shrink (docs/progressive.md): every footprint of this pass scaled alike. */
  f.axis_u = vec3_scale(f.axis_u, p->footprint_scale);
  f.axis_v = vec3_scale(f.axis_v, p->footprint_scale);
  f.axis_n = vec3_scale(f.axis_n, p->footprint_scale);
  Vec3 lo, hi;
  footprint_bounds(f, center, &lo, &hi);
  float area = footprint_area(f);

  /* Inverse of the basis (a_u, a_v, a_n): its rows are the reciprocal basis vectors. */
  Vec3 c_vn = vec3_cross(f.axis_v, f.axis_n), c_nu = vec3_cross(f.axis_n, f.axis_u), c_uv = vec3_cross(f.axis_u, f.axis_v);
  float det = vec3_dot(f.axis_u, c_vn);
  float inv_det = det != 0.0f && pm_isfinite(det) ? 1.0f / det : 0.0f; /* singular: contains nothing */
  Vec3 power = area > 0.0f ? vec3_scale(vec3_from_float4(kg->hit_flux[slot]), 1.0f / area) : vec3_splat(0.0f);
  if (inv_det == 0.0f || !pm_isfinite(power.x + power.y + power.z)) {
    power = vec3_splat(0.0f);
    area = 0.0f;
  }
  kg->footprint_lo[slot] = vec3_to_float4(lo, area);
  kg->footprint_hi[slot] = vec3_to_float4(hi, 0.0f);
  kg->footprint_center[slot] = vec3_to_float4(center, n4.w);
  kg->footprint_row_u[slot] = vec3_to_float4(vec3_scale(c_vn, inv_det), 0.0f);
  kg->footprint_row_v[slot] = vec3_to_float4(vec3_scale(c_nu, inv_det), 0.0f);
  kg->footprint_row_n[slot] = vec3_to_float4(vec3_scale(c_uv, inv_det), 0.0f);
  kg->footprint_power[slot] = vec3_to_float4(power, 0.0f);
}

#endif

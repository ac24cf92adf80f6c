/* The gather's test of whether a photon's footprint reaches a shading point (gather.h), with the
   normal test and kernel weight that the knn gather (knn_gather.h) shares. */
#ifndef PM_GATHER_REACH_H
#define PM_GATHER_REACH_H

#include "footprint_clip.h"
#include "kernel_globals.h"
#include "vec3.h"

/* Largest angle between a photon's surface normal and a shading point's for the photon to count
   there: 60 degrees (cos^2 = 1/4). Creases sharper than that, such as the 90-degree edges of a
   box, separate surfaces; the facets of tessellated curved surfaces are far closer. */
#define PM_GATHER_MIN_NORMAL_COS2 0.25f

/* Whether a photon whose normal axis row (map_row_n: n_hit / |a_n|) is row_n faces the way a
   shading point's normal n does, within PM_GATHER_MIN_NORMAL_COS2. */
PM_DEVICE int photon_faces_like(float4 row_n, Vec3 n)
{
  Vec3 axis_n = vec3_from_float4(row_n);
  float facing = vec3_dot(axis_n, n);
  return facing > 0.0f && facing * facing >= PM_GATHER_MIN_NORMAL_COS2 * vec3_dot(axis_n, axis_n);
}

/* Largest gain of gather_tilt_gain: a photon that grazed its own surface would otherwise count
   without bound on a facet that faces its beam. */
#define PM_GATHER_MAX_TILT_GAIN 4.0f

/* What a photon of incident direction wi (towards its light) that landed on a surface whose
   normal axis row is row_n delivers on a facet of normal n, over what it delivered on its own
   surface: the irradiance of a beam goes as the cosine of its incidence, cos(wi, n) / cos(wi,
   n_hit), capped at PM_GATHER_MAX_TILT_GAIN. Counting the photon in full on every facet within
   the gather's 60 degrees (gain 1) puts the light of a tessellated curved surface's facets where
   the beam strikes them obliquely: +6.5 % on the 30-60 degree bends of Sibenik's ribs and arches
   (docs/accuracy.md, "Bias at bends"). */
PM_DEVICE float gather_tilt_gain(float4 row_n, Vec3 wi, Vec3 n)
{
  float own = vec3_dot(wi, vec3_normalize(vec3_from_float4(row_n)));
  float there = vec3_dot(wi, n);
  if (!(own > 0.0f) || !(there > 0.0f)) return 0.0f;
  return pm_fminf(there / own, PM_GATHER_MAX_TILT_GAIN);
}

/* The gather's kernel weight at squared ellipsoid radius r2 (eq. 1's K). */
PM_DEVICE float gather_kernel_weight(uint shape, float r2)
{
  return shape == PM_KERNEL_EPANECHNIKOV ? kernel_epanechnikov(r2) : kernel_constant(r2);
}

/* Whether photon k's footprint reaches the shading point x with normal n: x lies in the
   ellipsoid, on the hit's side of its cuts (footprint_clip.h; the rows' w hold the first,
   mu lu + mv lv <= t in the ellipsoid's coordinates of x - hit, map_cut a second one where the
   flags say so), and x's surface faces the way the
   photon's did: the normal axis row_n = n_hit / |a_n| must lie within 60 degrees of n
   (PM_GATHER_MIN_NORMAL_COS2). The footprint's thickness lets a photon reach the neighbouring
   facets of a tessellated curved surface, and around a convex edge onto the other side of the
   adjoining face (a camera inside a closed box would see the light of the photons on its outside
   along its edges); the normal test keeps the first and stops the second. Writes the squared
   ellipsoid radius to *r2 and the disc coordinates of x to *at_u, *at_v. */
PM_DEVICE int footprint_reaches_at(const KernelGlobals* kg, uint k, float4 c, Vec3 x, Vec3 n, float* r2, float* at_u,
                                   float* at_v)
{
  Vec3 d = vec3_sub(x, vec3_from_float4(c));
  float4 row_u = PM_LOAD(&kg->map_row_u[k]), row_v = PM_LOAD(&kg->map_row_v[k]), row_n = PM_LOAD(&kg->map_row_n[k]);
  float lu = vec3_dot(vec3_from_float4(row_u), d);
  float lv = vec3_dot(vec3_from_float4(row_v), d);
  float ln = vec3_dot(vec3_from_float4(row_n), d);
  *r2 = lu * lu + lv * lv + ln * ln;
  *at_u = lu;
  *at_v = lv;
  if (!(*r2 <= 1.0f) || !(row_u.w * lu + row_v.w * lv <= row_n.w)) return 0;
  if (PM_AS_UINT(c.w) & PM_HIT_SECOND_CUT) {
    float4 cut = PM_LOAD(&kg->map_cut[k]);
    if (!(cut.x * lu + cut.y * lv <= cut.z)) return 0;
  }
  return photon_faces_like(row_n, n);
}

/* Least kept kernel mass about a shading point (a point at the tip of a narrow wedge between two
   walls): the gather's weight stays at most 16 times the open floor's. */
#define PM_GATHER_MIN_KEPT 0.0625f

/* The kernel mass of photon k's footprint, moved to centre on the shading point at disc
   coordinates (at_u, at_v), that its cuts keep (footprint_clip.h). The gather divides by it: near
   a wall, photons come from one side only, so a shading point at distance d from the wall sees
   the photon density times the kept mass of a footprint centred on it; dividing by that mass
   keeps a uniform density within 5 % at every distance from the wall, exact at its foot and from
   one radius on (dividing each photon by its own kept mass instead reads 69 % at the wall's foot
   and 112 % a radius away; tests/unit/footprint_clip_test.cpp). Not exact in between: a wall
   beyond a footprint's own radius is not among its cuts. */
PM_DEVICE float footprint_kept_about(const KernelGlobals* kg, uint k, float4 c, float at_u, float at_v, uint shape)
{
  float4 row_u = PM_LOAD(&kg->map_row_u[k]), row_v = PM_LOAD(&kg->map_row_v[k]), row_n = PM_LOAD(&kg->map_row_n[k]);
  float mu[PM_FOOTPRINT_CUTS], mv[PM_FOOTPRINT_CUTS], t[PM_FOOTPRINT_CUTS];
  mu[0] = row_u.w;
  mv[0] = row_v.w;
  t[0] = pm_fmaxf(row_n.w - (mu[0] * at_u + mv[0] * at_v), 0.0f);
  mu[1] = 0.0f;
  mv[1] = 0.0f;
  t[1] = 1.0f;
  if (PM_AS_UINT(c.w) & PM_HIT_SECOND_CUT) {
    float4 cut = PM_LOAD(&kg->map_cut[k]);
    mu[1] = cut.x;
    mv[1] = cut.y;
    t[1] = pm_fmaxf(cut.z - (cut.x * at_u + cut.y * at_v), 0.0f);
  }
  if (!(t[0] < 1.0f) && !(t[1] < 1.0f)) return 1.0f;
  float kept = !(t[1] < 1.0f) ? footprint_kept_one_cut(t[0], shape)
               : !(t[0] < 1.0f) ? footprint_kept_one_cut(t[1], shape)
                                : footprint_kept_fraction(mu, mv, t, PM_FOOTPRINT_CUTS, shape);
  return pm_fmaxf(kept, PM_GATHER_MIN_KEPT);
}

/* Most images of a shading point that a strip's fold sums, per family (a strip of
   PM_STRIP_MIN_WIDTH of the radius has at most 6 of each within the unit disc). */
#define PM_FOLD_MAX_IMAGES 8

/* The kernel at the images of the shading point at disc coordinates (at_u, at_v) and squared
   radius r2 across the rim m . q = t (rim = (mu, mv, t, w), map_cut; footprint_rim.h): its mirror
   image q' = q - 2 s m with s = m . q - t, so |q'|^2 = |q|^2 - 4 s t (the normal coordinate
   unchanged); for a strip w wide (w > 0) the images across both rims, 2 t - s + 2 j w and s + 2 j w
   (j != 0) along m for s = m . q, those within the unit disc. The gather weighs a folded footprint
   by K(r2) plus this (footprint_gather_weight). */
PM_DEVICE float footprint_fold_weight(uint shape, float4 rim, float at_u, float at_v, float r2)
{
  float s = rim.x * at_u + rim.y * at_v;
  if (!(rim.w > 0.0f)) return gather_kernel_weight(shape, r2 - 4.0f * (s - rim.z) * rim.z);
  float across2 = r2 - s * s, period = 2.0f * rim.w, weight = 0.0f;
  /* The mirror family a + j period from its first image at or beyond -1, then the translated one. */
  float a = 2.0f * rim.z - s;
  float image = a - period * pm_floorf((a + 1.0f) / period);
  for (int j = 0; j < PM_FOLD_MAX_IMAGES && image <= 1.0f; ++j, image += period)
    weight += gather_kernel_weight(shape, across2 + image * image);
  image = s - period * pm_floorf((s + 1.0f) / period);
  for (int j = 0; j < PM_FOLD_MAX_IMAGES && image <= 1.0f; ++j, image += period)
    if (pm_fabsf(image - s) > 0.5f * period) weight += gather_kernel_weight(shape, across2 + image * image);
  return weight;
}

/* The gather's weight of photon k's footprint at a shading point where footprint_reaches_at
   found it (squared radius r2, disc coordinates at_u, at_v): the kernel there (plus, for a
   footprint folded at its rim, at the point's mirror image across the rim: footprint_rim.h),
   divided by the kernel mass its cuts keep about the point. */
PM_DEVICE float footprint_gather_weight(const KernelGlobals* kg, uint k, float4 c, float r2, float at_u, float at_v,
                                        uint shape)
{
  float weight = gather_kernel_weight(shape, r2);
  if (PM_AS_UINT(c.w) & PM_HIT_RIM) weight += footprint_fold_weight(shape, PM_LOAD(&kg->map_cut[k]), at_u, at_v, r2);
  return weight / footprint_kept_about(kg, k, c, at_u, at_v, shape);
}

#endif

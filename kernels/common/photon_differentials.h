/* Photon differentials as pure functions (stages S1 emission and S2 differential updates).
   Fabianowski & Dingliana 2009, "Interactive Global Photon Mapping", sections 4-4.3, with the
   transfer and mirror equations of Igehy 1999, "Tracing Ray Differentials".

   A photon carries two positional differentials dp_u, dp_v and two directional differentials
   dd_u, dd_v, u standing for the emission parameter cos(theta) and v for phi. They are kept
   pre-scaled as in eq. 8, so one global spacing Delta = photon_spacing(n) (eq. 9) turns them into
   footprint semiaxes Delta * dp_u, Delta * dp_v at any hit (the footprint itself: footprint.h).

   The includer provides a compat header (PM_DEVICE, pm_* math) and vec3.h. */
#ifndef PM_PHOTON_DIFFERENTIALS_H
#define PM_PHOTON_DIFFERENTIALS_H

#include "brdf.h"
#include "types.h"
#include "vec3.h"

/* Smallest |cos| between a ray and the plane normal used by the transfer's projection: at
   grazing incidence the projected differential grows like 1/cos, so it is bounded by 1e4 times
   the unprojected one (and the footprint is clamped to r_max later, footprint.h). */
#define PM_PD_MIN_COS 1.0e-4f
/* Smallest survival probability used to rescale differentials (avoids 1/sqrt(0)). */
#define PM_PD_MIN_PROB 1.0e-6f

typedef struct PhotonRay {
  Vec3 origin, direction; /* direction is unit length */
  Vec3 dp_u, dp_v;        /* positional differentials (u: cos theta, v: phi), eq. 8 scaling */
  Vec3 dd_u, dd_v;        /* directional differentials */
} PhotonRay;

/* Global spacing between neighbouring photons in the (pre-scaled) parameter plane,
   Delta = 2 sqrt(pi / n) (eq. 9); n is the number of photons the light emitted. n = 0 is
   treated as 1 so the result stays finite. */
PM_DEVICE float photon_spacing(uint n)
{
  float count = n > 0u ? (float)n : 1.0f;
  return 2.0f * pm_sqrtf(PM_PI / count);
}

/* Direction of eq. 2 and its pre-scaled derivatives of eq. 8, in the frame (x, y, z):
   d     = (cos phi sin theta, sin phi sin theta, cos theta)                     (eq. 2)
   dd_u  = sin(theta) * dd/dcos(theta) = (-cos phi cos theta, -sin phi cos theta, sin theta)
   dd_v  = dd/dphi / sin(theta)        = (-sin phi, cos phi, 0)                  (eq. 8)
   Both are unit length, orthogonal to d and to each other, and finite at the poles where the
   unscaled derivatives of eq. 3 (cot theta) are not. sin theta >= 0 is passed in by the caller,
   who can compute it without the cancellation of sqrt(1 - cos^2) near the poles. */
PM_DEVICE void photon_sphere_direction(float cos_theta, float sin_theta, float phi, Vec3* d, Vec3* dd_u,
                                       Vec3* dd_v)
{
  float c = cos_theta, s = sin_theta;
  float sin_phi, cos_phi;
  pm_sincosf(phi, &sin_phi, &cos_phi);
  *d = vec3(cos_phi * s, sin_phi * s, c);
  *dd_u = vec3(-cos_phi * c, -sin_phi * c, s);
  *dd_v = vec3(-sin_phi, cos_phi, 0.0f);
}

/* S1: emission from an isotropic point light at light_pos (section 4.1). u1, u2 uniform in
   [0, 1): cos theta = 1 - 2 u1 (uniform in ]-1, 1]), sin theta = 2 sqrt(u1 (1 - u1)) (exact near
   the poles), phi = 2 pi u2. Positional differentials start at zero, directional ones follow
   eq. 8 (so Delta of eq. 9 applies to every photon). */
PM_DEVICE void photon_emit_point(Vec3 light_pos, float u1, float u2, PhotonRay* out)
{
  float sin_theta = 2.0f * pm_sqrtf(pm_fmaxf(0.0f, u1 * (1.0f - u1)));
  out->origin = light_pos;
  photon_sphere_direction(1.0f - 2.0f * u1, sin_theta, PM_TWO_PI * u2, &out->direction, &out->dd_u,
                          &out->dd_v);
  out->dp_u = vec3_splat(0.0f);
  out->dp_v = vec3_splat(0.0f);
}

/* Positional differential after travelling a distance t and hitting the plane with normal n
   (Igehy's transfer equation): dp' = dp + t dd, then the derivative of t moves the point back
   onto the plane along d:  dt = -dot(dp', n) / dot(d, n),  dp'' = dp' + dt d. */
PM_DEVICE Vec3 photon_transfer_differential(Vec3 dp, Vec3 dd, Vec3 d, float t, Vec3 n)
{
  float d_dot_n = vec3_dot(d, n);
  /* Grazing guard: keep |dot(d, n)| >= PM_PD_MIN_COS (sign kept; +0 counts as positive). */
  if (!(pm_fabsf(d_dot_n) >= PM_PD_MIN_COS)) d_dot_n = pm_copysignf(PM_PD_MIN_COS, d_dot_n);
  Vec3 moved = vec3_madd(dp, dd, t);
  return vec3_madd(moved, d, -vec3_dot(moved, n) / d_dot_n);
}

/* S2: move the photon to its hit at distance t on a plane with normal n (either orientation).
   The origin becomes the hit point; directional differentials do not change in transfer. */
PM_DEVICE void photon_transfer(PhotonRay* ray, float t, Vec3 n)
{
  Vec3 d = ray->direction;
  ray->dp_u = photon_transfer_differential(ray->dp_u, ray->dd_u, d, t, n);
  ray->dp_v = photon_transfer_differential(ray->dp_v, ray->dd_v, d, t, n);
  ray->origin = vec3_madd(ray->origin, d, t);
}

/* S2: perfect specular reflection at the current origin (Igehy):
   d' = d - 2 dot(d, n) n,   dd' = dd - 2 [dot(d, n) dn + (dd.n + d.dn) n].
   We use geometric (per-triangle) normals, so dn = 0 on the flat triangle and the formula
   reduces to reflecting the directional differentials: dd' = dd - 2 dot(dd, n) n.
   Positional differentials are unchanged (the reflection happens at the hit point). */
PM_DEVICE void photon_reflect_specular(PhotonRay* ray, Vec3 n)
{
  ray->direction = vec3_reflect(ray->direction, n);
  ray->dd_u = vec3_reflect(ray->dd_u, n);
  ray->dd_v = vec3_reflect(ray->dd_v, n);
}

/* Russian roulette with survival probability p and uniform u in [0, 1): returns 1 when the photon
   survives (u < p) and sets *flux_scale to 1/p, else returns 0 and sets it to 0, so the expected
   flux is unchanged. p >= 1 always survives with scale 1; p <= 0 never survives. */
PM_DEVICE int russian_roulette(float p, float u, float* flux_scale)
{
  float q = pm_fminf(p, 1.0f);
  int survive = u < q;
  *flux_scale = survive ? 1.0f / q : 0.0f;
  return survive;
}

/* Section 4.2: after surviving with probability p, scale all differentials by 1/sqrt(p) so the
   footprint area (quadratic in the differentials) grows by 1/p [HHK*07]. Directional
   differentials are scaled too so the footprint keeps growing consistently along the path. */
PM_DEVICE void photon_roulette_rescale(PhotonRay* ray, float p)
{
  float k = 1.0f / pm_sqrtf(pm_fminf(1.0f, pm_fmaxf(p, PM_PD_MIN_PROB)));
  ray->dp_u = vec3_scale(ray->dp_u, k);
  ray->dp_v = vec3_scale(ray->dp_v, k);
  ray->dd_u = vec3_scale(ray->dd_u, k);
  ray->dd_v = vec3_scale(ray->dd_v, k);
}

/* Footprint area of eq. 10: A = pi |Delta dp_u x Delta dp_v| = pi Delta^2 |dp_u x dp_v|. */
PM_DEVICE float photon_footprint_area(Vec3 dp_u, Vec3 dp_v, float delta)
{
  return PM_PI * delta * delta * vec3_length(vec3_cross(dp_u, dp_v));
}

/* S2: diffuse reflection as absorption and re-emission (section 4.3, eq. 10-13).
   In: ray at the hit point p (origin), incoming direction, positional differentials already
   transferred onto the surface (photon_transfer); n the geometric normal, either orientation:
   it is flipped to face the side the photon came from. u1, u2 uniform in [0, 1).

   Direction: cosine-weighted about the normal, cos theta' = sqrt(1 - u1), sin theta' = sqrt(u1)
   (the same distribution as cos theta' = sqrt(u1), but cos theta' is never exactly 0, so the
   photon never leaves tangent to the surface; pdf cos theta' / pi),
   phi' = 2 pi u2, put into the eq. 2 form in the local frame (t, b, n) and rotated to world.
   New directional differentials: eq. 8 in that local frame, rotated to world (the paper keeps the
   single global Delta for the re-emission parameters, section 4.3, so eq. 8 applies unchanged).

   Virtual offset: the new origin would be p' = p - v d' with zero positional differentials; after
   travelling v back to p they are v dd'_u, v dd'_v (eq. 11), giving the area
   A' = pi |Delta v dd'_u x Delta v dd'_v| = pi Delta^2 v^2 |dd'_u x dd'_v| (eq. 12, the same Delta as
   the old differentials, eq. 9). Equating with A = pi Delta^2 |dp_u x dp_v| (eq. 10), the Deltas
   cancel and v = sqrt(|dp_u x dp_v| / |dd'_u x dd'_v|) (eq. 13); with eq. 8, |dd'_u x dd'_v| = 1.

   Representation: the ray keeps starting at p (robust tracing, no re-hit of the virtual segment)
   and carries dp = v dd' (eq. 11), which is exactly the state of the virtual ray when it passes p;
   a later transfer by t then gives (v + t) dd' projected, as from p'. Returns v. */
/* Re-emission about the local frame (t, b, axis): direction (cos_theta, sin_theta, phi) in the
   eq. 2 form, eq.-8 directional differentials rotated to world, and the area-preserving virtual
   offset of eq. 13 applied as dp = v dd' (see photon_diffuse_reemit). Returns v. */
PM_DEVICE float photon_reemit_in_frame(PhotonRay* ray, Vec3 t, Vec3 b, Vec3 axis, float cos_theta, float sin_theta,
                                       float phi)
{
  Vec3 dl, dul, dvl;
  photon_sphere_direction(cos_theta, sin_theta, phi, &dl, &dul, &dvl);
  Vec3 d = vec3_frame_to_world(t, b, axis, dl);
  Vec3 du = vec3_frame_to_world(t, b, axis, dul);
  Vec3 dv = vec3_frame_to_world(t, b, axis, dvl);

  float area_in = vec3_length(vec3_cross(ray->dp_u, ray->dp_v));
  float area_dir = vec3_length(vec3_cross(du, dv)); /* 1 up to rounding (eq. 8) */
  float v = area_dir > 0.0f ? pm_sqrtf(area_in / area_dir) : 0.0f;
  if (!pm_isfinite(v)) v = 0.0f;

  ray->direction = d;
  ray->dd_u = du;
  ray->dd_v = dv;
  ray->dp_u = vec3_scale(du, v);
  ray->dp_v = vec3_scale(dv, v);
  return v;
}

PM_DEVICE float photon_diffuse_reemit(PhotonRay* ray, Vec3 n, float u1, float u2)
{
  Vec3 nf = vec3_dot(ray->direction, n) > 0.0f ? vec3_neg(n) : n;
  Vec3 t, b;
  vec3_onb(nf, &t, &b);
  LobeSample s = brdf_sample_diffuse(u1, u2);
  return photon_reemit_in_frame(ray, t, b, nf, s.cos_theta, s.sin_theta, s.phi);
}

#endif

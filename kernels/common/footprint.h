/* Photon footprints (stage S3, end of section 4.3 of Fabianowski & Dingliana 2009): the skewed
   footprint ellipsoid of a photon hit built from its positional differentials, its area, its
   axis-aligned bounds, the point-in-ellipsoid test, and the density-estimation kernels of
   section 3 (eq. 1, Figure 4).

   The ellipsoid is {center + x a_u + y a_v + z a_n : x^2 + y^2 + z^2 <= 1}, a_u and a_v the
   (skewed) in-plane semiaxes, a_n along the surface normal (Figure 1).

   The includer provides a compat header (PM_DEVICE, pm_* math) and vec3.h. */
#ifndef PM_FOOTPRINT_H
#define PM_FOOTPRINT_H

#include "types.h"
#include "vec3.h"

/* Smoothing factor of photons whose path was specular only (sharp caustics, section 7). */
#ifndef PM_CAUSTIC_SMOOTHING
#define PM_CAUSTIC_SMOOTHING 5.0f
#endif
/* Half-length of the normal axis as a fraction of the smaller in-plane semiaxis; see
   footprint_from_differentials. */
#ifndef PM_FOOTPRINT_NORMAL_RATIO
#define PM_FOOTPRINT_NORMAL_RATIO 0.5f
#endif
/* Radius of the circular fallback footprint, as a fraction of r_max, when no differential gives
   a usable length (both zero or not finite). */
#ifndef PM_FOOTPRINT_FALLBACK_FRACTION
#define PM_FOOTPRINT_FALLBACK_FRACTION 0.5f
#endif
/* In-plane semiaxes count as parallel when |a_u x a_v| <= this * |a_u| |a_v| (sine of angle). */
#define PM_FOOTPRINT_MIN_SINE 1.0e-4f
/* contains(): the basis counts as singular when |det| <= this * |a_u| |a_v| |a_n|. */
#define PM_FOOTPRINT_MIN_DET 1.0e-6f
/* r^2 reported for points that cannot be located in a singular basis. */
#define PM_FOOTPRINT_FAR 1.0e30f

typedef struct Footprint {
  Vec3 axis_u, axis_v, axis_n; /* semiaxes: in-plane (skewed) and along the normal */
} Footprint;

/* Length of one in-plane semiaxis from the length L = |dp_x| of its positional differential.
   Caustic photons: Delta * L * s_caustic (no compression).
   Diffusely reflected photons: the paper rescales "each footprint semiaxis by |dp_x|^(-3/4) with
   dp_x the positional differential that was used to generate it". We apply the exponent to the
   differential itself, in scene units, as written:  a_x = s Delta dp_x |dp_x|^(-3/4), so
   |a_x| = s Delta L^(1/4). Reading it as (Delta L)^(-3/4) instead would give s Delta^(1/4) L^(1/4),
   radii of ~25 with the paper's s = 40 and n = 256k, far beyond its Table 3 (radii ~0.6 at
   r_max = 0.7), whereas our reading gives 40 * 0.0070 * L^(1/4) ~ 0.5 for L ~ 25 m.
   Consequence: the rule is NOT scale-invariant. Scaling the scene by k scales footprints of
   diffuse photons by k^(1/4), not k; a fixed s (a per-scene setting in the paper) suits one scene
   size. The automatic smoothing (render/footprint_scale.h) chooses s per batch so that radii scale
   with the scene. L^(1/4) is computed as sqrt(sqrt(L)), exact and NaN-free for L >= 0. */
PM_DEVICE float footprint_semiaxis_length(float dp_length, float delta, float smoothing, int is_caustic)
{
  if (is_caustic) return PM_CAUSTIC_SMOOTHING * delta * dp_length;
  return smoothing * delta * pm_sqrtf(pm_sqrtf(dp_length));
}

/* One in-plane semiaxis along dp, length from footprint_semiaxis_length clamped to rmax.
   Zero when dp is zero or not finite (handled by the caller's fallback). */
PM_DEVICE Vec3 footprint_semiaxis(Vec3 dp, float delta, float smoothing, float rmax, int is_caustic)
{
  float len = vec3_length(dp);
  if (!(len > 0.0f) || !pm_isfinite(len)) return vec3_splat(0.0f);
  float r = pm_fminf(footprint_semiaxis_length(len, delta, smoothing, is_caustic), rmax);
  if (!(r > 0.0f) || !pm_isfinite(r)) return vec3_splat(0.0f);
  return vec3_scale(dp, r / len);
}

/* S3: footprint ellipsoid of a hit from its positional differentials (already transferred onto
   the surface), the surface normal, the global spacing delta (eq. 9), the smoothing factor s,
   the maximal radius rmax and whether the path was specular only.
   - In-plane semiaxes a_x = s Delta dp_x |dp_x|^(-3/4) for diffusely reflected photons, or
     s_caustic Delta dp_x for caustic photons (is_caustic != 0, s = PM_CAUSTIC_SMOOTHING = 5, the
     smoothing argument is ignored), each length clamped to rmax, direction kept (skew kept).
   - Degenerate differentials (zero, not finite, or parallel) fall back to a circle in the plane
     of the normal whose radius is the longer usable semiaxis, or rmax * PM_FOOTPRINT_FALLBACK_FRACTION
     if none is usable. The result is always finite.
   - Normal axis: half-length h = PM_FOOTPRINT_NORMAL_RATIO * min(|a_u|, |a_v|). h decides which
     points off the hit plane receive the photon: points on the same plane are unaffected; a small h
     keeps photons from leaking through thin walls and around creases onto the adjoining surface
     (where their incident direction does not belong), while a nonzero h still reaches query points
     on neighbouring triangles of a tessellated curved surface and absorbs hit-position rounding.
     Tying h to the in-plane size (rather than a fraction of rmax) keeps the ellipsoid's shape the
     same at every scale and keeps sharp caustic footprints thin; since |a_x| <= rmax, h <= rmax/2.
     Why half: a curved surface leaves a thin ellipsoid before the footprint's rim while the flux
     is normalised by the whole ellipse, a loss on every convex or concave surface. On the closed
     sphere (docs/progressive.md, one pass, s = 8) a ratio of 0.25 loses 1.87 % of the indirect
     light, 0.5 loses 0.44 % and 1.0 0.05 %; 0.5 keeps the light-leak tests' thin walls dark.
     Note: for very small footprints far from the origin, h can fall below float rounding of
     positions; callers should query with points on the hit's plane there. */
PM_DEVICE Footprint footprint_from_differentials(Vec3 dp_u, Vec3 dp_v, Vec3 normal, float delta,
                                                 float smoothing, float rmax, int is_caustic)
{
  Footprint f;
  Vec3 a_u = footprint_semiaxis(dp_u, delta, smoothing, rmax, is_caustic);
  Vec3 a_v = footprint_semiaxis(dp_v, delta, smoothing, rmax, is_caustic);
  float lu = vec3_length(a_u), lv = vec3_length(a_v);

  Vec3 n = vec3_normalize(normal);
  if (!(vec3_dot(n, n) > 0.5f) || !pm_isfinite(n.x + n.y + n.z)) {
    n = vec3_normalize(vec3_cross(a_u, a_v));
    if (!(vec3_dot(n, n) > 0.5f) || !pm_isfinite(n.x + n.y + n.z)) n = vec3(0.0f, 0.0f, 1.0f);
  }

  float cross_len = vec3_length(vec3_cross(a_u, a_v));
  if (!(cross_len > PM_FOOTPRINT_MIN_SINE * lu * lv) || !(lu > 0.0f) || !(lv > 0.0f)) {
    float r = pm_fmaxf(lu, lv);
    if (!(r > 0.0f)) r = rmax * PM_FOOTPRINT_FALLBACK_FRACTION;
    if (!(r > 0.0f) || !pm_isfinite(r)) r = 0.0f;
    Vec3 t, b;
    vec3_onb(n, &t, &b);
    a_u = vec3_scale(t, r);
    a_v = vec3_scale(b, r);
    lu = r;
    lv = r;
  }
  f.axis_u = a_u;
  f.axis_v = a_v;
  f.axis_n = vec3_scale(n, PM_FOOTPRINT_NORMAL_RATIO * pm_fminf(lu, lv));
  return f;
}

/* Sets f's normal half-axis to `ratio` times its shorter in-plane semiaxis, along its normal
   (--footprint-thickness; footprint_from_differentials uses PM_FOOTPRINT_NORMAL_RATIO). */
PM_DEVICE void footprint_set_thickness(Footprint* f, float ratio)
{
  float h = ratio * pm_fminf(vec3_length(f->axis_u), vec3_length(f->axis_v));
  f->axis_n = vec3_scale(vec3_normalize(f->axis_n), h);
}

/* Area of the skewed elliptical footprint, A = pi |a_u x a_v| (eq. 10). */
PM_DEVICE float footprint_area(Footprint f)
{
  return PM_PI * vec3_length(vec3_cross(f.axis_u, f.axis_v));
}

/* Axis-aligned bounds of the ellipsoid: along world axis i, the largest value of
   e_i . (x a_u + y a_v + z a_n) over the unit ball is the length of (a_u,i, a_v,i, a_n,i). */
PM_DEVICE void footprint_bounds(Footprint f, Vec3 center, Vec3* lo, Vec3* hi)
{
  Vec3 u = f.axis_u, v = f.axis_v, w = f.axis_n;
  Vec3 ext = vec3(pm_sqrtf(u.x * u.x + v.x * v.x + w.x * w.x),
                  pm_sqrtf(u.y * u.y + v.y * v.y + w.y * w.y),
                  pm_sqrtf(u.z * u.z + v.z * v.z + w.z * w.z));
  *lo = vec3_sub(center, ext);
  *hi = vec3_add(center, ext);
}

/* Whether x lies in the ellipsoid. Solves r = x - center = X a_u + Y a_v + Z a_n by Cramer's rule
   with cross products (the rows of the inverse are (a_v x a_n, a_n x a_u, a_u x a_v) / det,
   det = a_u . (a_v x a_n)). Writes r2 = X^2 + Y^2 + Z^2 to *r2_out (if not null); contains iff
   r2 <= 1. A singular basis contains nothing (r2 = PM_FOOTPRINT_FAR). */
PM_DEVICE int footprint_contains(Footprint f, Vec3 center, Vec3 x, float* r2_out)
{
  Vec3 c_vn = vec3_cross(f.axis_v, f.axis_n);
  Vec3 c_nu = vec3_cross(f.axis_n, f.axis_u);
  Vec3 c_uv = vec3_cross(f.axis_u, f.axis_v);
  float det = vec3_dot(f.axis_u, c_vn);
  float scale = vec3_length(f.axis_u) * vec3_length(f.axis_v) * vec3_length(f.axis_n);
  float r2 = PM_FOOTPRINT_FAR;
  if (pm_fabsf(det) > PM_FOOTPRINT_MIN_DET * scale && pm_isfinite(det)) {
    Vec3 r = vec3_sub(x, center);
    float inv = 1.0f / det;
    float cx = vec3_dot(r, c_vn) * inv;
    float cy = vec3_dot(r, c_nu) * inv;
    float cz = vec3_dot(r, c_uv) * inv;
    r2 = cx * cx + cy * cy + cz * cz;
    if (!pm_isfinite(r2)) r2 = PM_FOOTPRINT_FAR;
  }
  if (r2_out) *r2_out = r2;
  return r2 <= 1.0f;
}

/* Density-estimation kernels of eq. 1 as functions of r2 (the squared ellipsoid coordinate from
   footprint_contains). Normalisation: mean 1 over the unit disc, i.e. the integral over the unit
   disc is pi. The gather adds kernel(r2) * Phi / A with A = footprint_area; over the skewed
   ellipse x = X a_u + Y a_v (Jacobian |a_u x a_v|) this integrates to
   Phi * |a_u x a_v| * pi / A = Phi, so a uniform photon density reproduces the exact irradiance.
   (Eq. 1's 1/r_i^2 K form is the same with the pi of A moved into K.) */
PM_DEVICE float kernel_constant(float r2) { return r2 <= 1.0f ? 1.0f : 0.0f; }

/* Epanechnikov: 2 (1 - r2); integral over the unit disc = int_0^1 2 (1 - r^2) 2 pi r dr = pi. */
PM_DEVICE float kernel_epanechnikov(float r2) { return r2 <= 1.0f ? 2.0f * (1.0f - r2) : 0.0f; }

#endif

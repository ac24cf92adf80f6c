/* Rays against the scene's primitives: the watertight ray/triangle test (Woop, Benthin & Wald
   2013, JCGT 2(1)), the ray/box slab test used by both BVH traversals, and the origin offsets of
   secondary rays, relative to the hit's magnitude and the scene's size. */
#ifndef PM_RAY_H
#define PM_RAY_H

#include "vec3.h"

typedef struct Ray {
  Vec3 origin;
  Vec3 direction;
  Vec3 inv_direction;
  /* Watertight test: dominant axis kz, the permuted others kx, ky and the shear constants. */
  int kx, ky, kz;
  float shear_x, shear_y, shear_z;
} Ray;

PM_DEVICE float safe_reciprocal(float x)
{
  /* Zero direction components give signed infinities, which the slab test handles; keep the
     sign of a negative zero. */
  return 1.0f / x;
}

PM_DEVICE Ray ray_make(Vec3 origin, Vec3 direction)
{
  Ray r;
  r.origin = origin;
  r.direction = direction;
  r.inv_direction = vec3(safe_reciprocal(direction.x), safe_reciprocal(direction.y), safe_reciprocal(direction.z));
  float ax = pm_fabsf(direction.x), ay = pm_fabsf(direction.y), az = pm_fabsf(direction.z);
  r.kz = (ax > ay) ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
  r.kx = r.kz == 2 ? 0 : r.kz + 1;
  r.ky = r.kx == 2 ? 0 : r.kx + 1;
  /* Swap to preserve the triangle winding when the dominant component is negative. */
  if (vec3_component(direction, r.kz) < 0.0f) { int t = r.kx; r.kx = r.ky; r.ky = t; }
  float dz = vec3_component(direction, r.kz);
  r.shear_x = vec3_component(direction, r.kx) / dz;
  r.shear_y = vec3_component(direction, r.ky) / dz;
  r.shear_z = 1.0f / dz;
  return r;
}

/* Two-sided watertight intersection. Returns 1 and the distance in *t_out when the ray hits
   the triangle strictly inside (t_min, t_max). */
PM_DEVICE int ray_triangle(const Ray* r, Vec3 v0, Vec3 v1, Vec3 v2, float t_min, float t_max, float* t_out)
{
  Vec3 a = vec3_sub(v0, r->origin), b = vec3_sub(v1, r->origin), c = vec3_sub(v2, r->origin);
  float az = vec3_component(a, r->kz), bz = vec3_component(b, r->kz), cz = vec3_component(c, r->kz);
  /* Unfused products: an FMA would round the two halves of an edge function differently on
     the two triangles sharing the edge, and rays could slip through (or hit point triangles). */
  float ax = vec3_component(a, r->kx) - pm_mul_rn(r->shear_x, az), ay = vec3_component(a, r->ky) - pm_mul_rn(r->shear_y, az);
  float bx = vec3_component(b, r->kx) - pm_mul_rn(r->shear_x, bz), by = vec3_component(b, r->ky) - pm_mul_rn(r->shear_y, bz);
  float cx = vec3_component(c, r->kx) - pm_mul_rn(r->shear_x, cz), cy = vec3_component(c, r->ky) - pm_mul_rn(r->shear_y, cz);
  float u = pm_mul_rn(cx, by) - pm_mul_rn(cy, bx);
  float v = pm_mul_rn(ax, cy) - pm_mul_rn(ay, cx);
  float w = pm_mul_rn(bx, ay) - pm_mul_rn(by, ax);
  if ((u < 0.0f || v < 0.0f || w < 0.0f) && (u > 0.0f || v > 0.0f || w > 0.0f)) return 0;
  float det = u + v + w;
  if (det == 0.0f) return 0;
  float t_scaled = r->shear_z * (u * az + v * bz + w * cz);
  float t = t_scaled / det;
  if (!(t > t_min && t < t_max)) return 0;
  *t_out = t;
  return 1;
}

/* Slab test against a box; returns the entry distance, or +INF-like 1e38 for a miss. The
   max/min order makes NaNs from 0*inf (ray in a slab plane) resolve to "inside" for that axis. */
PM_DEVICE float ray_box_entry(const Ray* r, Vec3 lo, Vec3 hi, float t_max)
{
  float tx0 = (lo.x - r->origin.x) * r->inv_direction.x, tx1 = (hi.x - r->origin.x) * r->inv_direction.x;
  float ty0 = (lo.y - r->origin.y) * r->inv_direction.y, ty1 = (hi.y - r->origin.y) * r->inv_direction.y;
  float tz0 = (lo.z - r->origin.z) * r->inv_direction.z, tz1 = (hi.z - r->origin.z) * r->inv_direction.z;
  float t_enter = pm_fmaxf(pm_fmaxf(pm_fminf(tx0, tx1), pm_fminf(ty0, ty1)), pm_fmaxf(pm_fminf(tz0, tz1), 0.0f));
  float t_exit = pm_fminf(pm_fminf(pm_fmaxf(tx0, tx1), pm_fmaxf(ty0, ty1)), pm_fminf(pm_fmaxf(tz0, tz1), t_max));
  /* A tiny relative slack keeps zero-thickness boxes (flat walls) from being missed. */
  return t_enter <= t_exit * 1.00000024f ? t_enter : 1e38f;
}

/* Secondary rays start a short distance off the surface they leave, along its geometric normal,
   so that rounding cannot make them hit that surface again (shadow acne) and the distance stays
   negligible next to the scene (a light micrometres from a surface in a tiny scene).

   A hit computed as o + t d carries a rounding error of a few ulps of its magnitude
   m = max|o_i| + t; the triangle's plane carries errors of a few ulps of the vertices'
   coordinates, at most the largest coordinate S of the scene. The offset is 2^-17 of both,
   scene_epsilon + 2^-17 m with scene_epsilon = 2^-17 S (LaunchParams.ray_epsilon, set by the host
   from the scene's bounds): 64 to 128 ulps, whatever the scene's size and wherever the hit lies.
   The earlier fixed-point scheme (Waechter & Binder 2019: an absolute 1/65536 within 1/32 of a
   coordinate plane, integer ulps elsewhere) was too small on the coordinate planes of large
   scenes and too large in small ones. */
#define PM_RAY_OFFSET_RELATIVE 7.62939453125e-6f /* 2^-17 */

/* Offset distance for a hit at distance t along a ray from origin (magnitude max|o_i| + t). */
PM_DEVICE float ray_offset_distance(Vec3 origin, float t, float scene_epsilon)
{
  return scene_epsilon + PM_RAY_OFFSET_RELATIVE * (vec3_max_abs(origin) + pm_fabsf(t));
}

/* p moved by `distance` along the unit normal n (pointing to the side the new ray leaves from).
   distance >= 2^-17 |p| exceeds the rounding of the addition (2^-24 |p| per coordinate). */
PM_DEVICE Vec3 offset_ray_origin(Vec3 p, Vec3 n, float distance) { return vec3_madd(p, n, distance); }

#endif

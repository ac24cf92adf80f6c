/* Area lights: triangles whose material emits (Lambertian emitters, radiance L_e from the front
   face, the side of the geometric normal (p1 - p0) x (p2 - p0)). Owns the emitter records and
   every way a stage meets them: light sampling for next-event estimation (camera pass, path
   tracer, radiosity's light links), the emitted radiance a ray sees, and photon emission (S1).

   Records (render/scene_emitters.h builds them, PM_EMITTER_FLOAT4S float4 per emitter):
     [0] v0.xyz, w = the cumulative share of the emitters' power up to and including this one
     [1] v1.xyz, w unused    [2] v2.xyz, w = area (m^2)    [3] L_e rgb, w = mean(L_e)
   An emitter's power is pi A mean(L_e) (a Lambertian surface's flux), p->emitter_power their sum.
   Emitters are chosen in proportion to power and sampled uniformly by area, so the density of a
   light sample per unit area is pdf_A = pi mean(L_e) / emitter_power: it depends on the
   emitter's radiance only, which lets a ray that hits an emitter know the density light
   sampling would have given it (multiple importance sampling in the path tracer). */
#ifndef PM_AREA_LIGHTS_H
#define PM_AREA_LIGHTS_H

#include "brdf.h"
#include "kernel_globals.h"
#include "photon_differentials.h"
#include "rng.h"
#include "scene_traverse.h"

#define PM_STREAM_AREA 0x41524541u /* "AREA": light-sample positions on emitters */

/* The emitted radiance a ray of direction `dir` sees where it hits a triangle of material
   `material_index` with geometric normal `geometric_n` (as stored, any length): L_e when the
   ray meets the front face, else 0. */
PM_DEVICE Vec3 surface_emission(const KernelGlobals* kg, const LaunchParams* p, int material_index, Vec3 geometric_n,
                                Vec3 dir)
{
  if (p->emitter_count == 0u || vec3_dot(geometric_n, dir) >= 0.0f) return vec3_splat(0.0f);
  return vec3_from_float4(PM_LOAD(&kg->material_emission[material_index]));
}

/* Density of light sampling per unit area at a point emitting mean radiance `mean_radiance`. */
PM_DEVICE float area_light_pdf_area(const LaunchParams* p, float mean_radiance)
{
  return p->emitter_power > 0.0f ? PM_PI * mean_radiance / p->emitter_power : 0.0f;
}

/* The emitter whose share of the cumulative power holds u (binary search). */
PM_DEVICE uint area_light_select(const KernelGlobals* kg, const LaunchParams* p, float u)
{
  uint lo = 0u, hi = p->emitter_count - 1u;
  while (lo < hi) {
    uint mid = (lo + hi) >> 1;
    if (u < PM_LOAD(&kg->emitters[PM_EMITTER_FLOAT4S * mid]).w) hi = mid;
    else lo = mid + 1u;
  }
  return lo;
}

typedef struct EmitterPoint {
  Vec3 position, normal; /* normal: unit, the emitting side */
  float4 radiance;       /* rgb L_e, w = mean */
  float area;
} EmitterPoint;

/* A point uniform on emitter e's triangle: barycentrics (1 - sqrt(u1), sqrt(u1) (1 - u2)), ... */
PM_DEVICE EmitterPoint area_light_point(const KernelGlobals* kg, uint e, float u1, float u2)
{
  PM_GLOBAL const float4* r = kg->emitters + PM_EMITTER_FLOAT4S * e;
  Vec3 v0 = vec3_from_float4(PM_LOAD(&r[0])), v1 = vec3_from_float4(PM_LOAD(&r[1]));
  Vec3 v2 = vec3_from_float4(PM_LOAD(&r[2]));
  float s = pm_sqrtf(u1);
  float b1 = s * (1.0f - u2), b2 = s * u2;
  EmitterPoint pt;
  pt.position = vec3_add(v0, vec3_add(vec3_scale(vec3_sub(v1, v0), b1), vec3_scale(vec3_sub(v2, v0), b2)));
  pt.normal = vec3_normalize(vec3_cross(vec3_sub(v1, v0), vec3_sub(v2, v0)));
  pt.radiance = PM_LOAD(&r[3]);
  pt.area = PM_LOAD(&r[2]).w;
  return pt;
}

/* One light sample seen from x (unit normal n on the side it is lit from; the shadow ray starts
   `offset` off the surface along n): wi towards the sample, the irradiance estimate
   L_e cos_x cos_y / (r^2 pdf_A) (0 when the sample faces away, lies below x's horizon or is
   blocked) and light sampling's density per solid angle, pdf_A r^2 / cos_y. */
typedef struct AreaLightSample {
  Vec3 wi;
  Vec3 irradiance;
  float pdf_solid_angle;
} AreaLightSample;

PM_DEVICE AreaLightSample area_light_sample(const KernelGlobals* kg, const LaunchParams* p, Vec3 x, Vec3 n,
                                            float offset, Uniform4 u)
{
  AreaLightSample s;
  s.wi = n;
  s.irradiance = vec3_splat(0.0f);
  s.pdf_solid_angle = 0.0f;
  EmitterPoint pt = area_light_point(kg, area_light_select(kg, p, u.u0), u.u1, u.u2);
  Vec3 to_light = vec3_sub(pt.position, x);
  float dist2 = vec3_dot(to_light, to_light);
  if (!(dist2 > 0.0f)) return s;
  float dist = pm_sqrtf(dist2);
  s.wi = vec3_scale(to_light, 1.0f / dist);
  float cos_x = vec3_dot(n, s.wi), cos_y = -vec3_dot(pt.normal, s.wi);
  if (cos_x <= 0.0f || cos_y <= 0.0f) return s;
  float pdf_area = area_light_pdf_area(p, pt.radiance.w);
  if (!(pdf_area > 0.0f)) return s;
  s.pdf_solid_angle = pdf_area * dist2 / cos_y;
  Vec3 origin = offset_ray_origin(x, n, offset);
  Vec3 shadow_path = vec3_sub(pt.position, origin);
  float shadow_length = vec3_length(shadow_path);
  if (!(shadow_length > 0.0f)) return s;
  /* Stops short of the emitter by 1e-4 of the distance: the sample lies on its triangle. */
  Ray shadow = ray_make(origin, vec3_scale(shadow_path, 1.0f / shadow_length));
  if (scene_trace(kg, &shadow, 0.0f, shadow_length * (1.0f - 1e-4f), 1).triangle >= 0) return s;
  s.irradiance = vec3_scale(vec3_from_float4(pt.radiance), cos_x * cos_y / (dist2 * pdf_area));
  return s;
}

/* Multiple importance sampling, power heuristic (Veach 1997): the weight of the strategy whose
   density is `own` against the other's. */
PM_DEVICE float mis_power_weight(float own, float other)
{
  float a = own * own, b = other * other;
  return a + b > 0.0f ? a / (a + b) : 0.0f;
}

/* S1 from the area lights (section 4.1 for a surface): an emitter chosen by power, a point
   uniform on it (u_select, u_pos1, u_pos2), a cosine-distributed direction (u_dir1, u_dir2); every
   photon carries flux L_e / mean(L_e) * emitter_power / n (the power of the chosen emitter over
   its probability, over n photons).
   Differentials: the emitting surface is treated as a surface that re-emits diffusely every
   photon it received (section 4.3): a photon stands for 1 / (n pdf_A) of the emitter's area,
   and a footprint's area is pi times that area, as for a point light's photon (eq. 9 and 10:
   pi Delta^2 r^2 with Delta^2 = 4 pi / n, while each photon covers 4 pi r^2 / n of the sphere).
   So the incoming footprint is set to A = pi Delta^2 |dp_u x dp_v| = pi / (n pdf_A), i.e.
   |dp_u x dp_v| = 1 / (4 pi pdf_A) with dp_u, dp_v orthogonal in the emitter's plane, and the
   re-emission of eq. 11-13 (photon_reemit_in_frame) turns it into the virtual offset
   v = sqrt(1 / (4 pi pdf_A)) along the eq.-8 directional differentials. For an emitter of uniform
   radiance this is v = sqrt(A_total / (4 pi)). Returns the point's emitting normal (the start
   of the ray is offset along it by the caller). */
PM_DEVICE Vec3 photon_emit_area(const KernelGlobals* kg, const LaunchParams* p, float u_select, float u_pos1,
                                float u_pos2, float u_dir1, float u_dir2, uint emitted, PhotonRay* ray, Vec3* flux)
{
  EmitterPoint pt = area_light_point(kg, area_light_select(kg, p, u_select), u_pos1, u_pos2);
  float pdf_area = area_light_pdf_area(p, pt.radiance.w);
  float side = pdf_area > 0.0f ? pm_sqrtf(1.0f / (4.0f * PM_PI * pdf_area)) : 0.0f;
  Vec3 t, b;
  vec3_onb(pt.normal, &t, &b);
  ray->origin = pt.position;
  ray->dp_u = vec3_scale(t, side);
  ray->dp_v = vec3_scale(b, side);
  LobeSample s = brdf_sample_diffuse(u_dir1, u_dir2);
  photon_reemit_in_frame(ray, t, b, pt.normal, s.cos_theta, s.sin_theta, s.phi);
  float scale = pt.radiance.w > 0.0f ? p->emitter_power / (pt.radiance.w * (float)(emitted > 0u ? emitted : 1u)) : 0.0f;
  *flux = vec3_scale(vec3_from_float4(pt.radiance), scale);
  return pt.normal;
}

#endif

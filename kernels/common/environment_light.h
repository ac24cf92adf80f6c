/* The environment light: radiance arriving from infinitely far away, one constant radiance from
   every direction or an equirectangular map (environment_map.h). Owns every way a stage meets
   it: the radiance a ray that leaves the scene sees, light sampling for next-event estimation
   (camera pass, path tracer with MIS, radiosity's light links) with its density per solid
   angle, and photon emission (S1).

   Sampling: the constant environment uniformly over the sphere (density 1 / (4 pi)); the map
   by its luminance x sin(theta) distribution (density pdf_uv / (2 pi^2 sin theta)).

   Photon emission (docs/algorithm.md, "Environment light"): a direction w towards the
   environment from the sampling above, and an origin uniform on the disk of the scene's
   bounding-sphere radius R centred at C + R w, perpendicular to w, so the disk lies outside the
   sphere and every line of direction -w through the scene crosses it. The photon travels along
   -w and carries L(w) pi R^2 / (pdf(w) n). */
#ifndef PM_ENVIRONMENT_LIGHT_H
#define PM_ENVIRONMENT_LIGHT_H

#include "area_lights.h"
#include "brdf.h"
#include "environment_map.h"
#include "kernel_globals.h"
#include "photon_differentials.h"
#include "rng.h"
#include "scene_traverse.h"

#define PM_STREAM_ENVIRONMENT 0x454e5649u /* "ENVI": environment light samples and photon origins */

/* The radiance arriving along -dir, i.e. seen by a ray of unit direction dir that leaves the
   scene. */
PM_DEVICE Vec3 environment_radiance(const KernelGlobals* kg, const LaunchParams* p, Vec3 dir)
{
  if (p->environment == PM_ENVIRONMENT_CONSTANT) return vec3_from_float4(p->environment_radiance);
  if (p->environment != PM_ENVIRONMENT_MAP) return vec3_splat(0.0f);
  float u, v;
  environment_uv(dir, p->environment_rotation, &u, &v);
  uint texel = environment_texel(u, v, p->environment_width, p->environment_height);
  return vec3_from_float4(PM_LOAD(&kg->environment_texels[texel]));
}

/* Light sampling's density per solid angle for direction dir. */
PM_DEVICE float environment_pdf(const KernelGlobals* kg, const LaunchParams* p, Vec3 dir)
{
  if (p->environment == PM_ENVIRONMENT_CONSTANT) return 1.0f / (4.0f * PM_PI);
  if (p->environment != PM_ENVIRONMENT_MAP) return 0.0f;
  float u, v;
  environment_uv(dir, p->environment_rotation, &u, &v);
  uint texel = environment_texel(u, v, p->environment_width, p->environment_height);
  return environment_map_pdf(PM_LOAD(&kg->environment_texels[texel]).w, v);
}

/* A direction drawn from light sampling: wi towards the environment, the radiance arriving
   from there, and the density per solid angle (0: nothing drawn). */
typedef struct EnvironmentSample {
  Vec3 wi;
  Vec3 radiance;
  float pdf;
} EnvironmentSample;

PM_DEVICE EnvironmentSample environment_sample(const KernelGlobals* kg, const LaunchParams* p, float u1, float u2)
{
  EnvironmentSample s;
  s.wi = vec3(0.0f, 1.0f, 0.0f);
  s.radiance = vec3_splat(0.0f);
  s.pdf = 0.0f;
  if (p->environment == PM_ENVIRONMENT_CONSTANT) {
    s.wi = environment_uniform_direction(u1, u2);
    s.radiance = vec3_from_float4(p->environment_radiance);
    s.pdf = 1.0f / (4.0f * PM_PI);
  } else if (p->environment == PM_ENVIRONMENT_MAP) {
    float u, v;
    uint texel = environment_sample_uv(kg->environment_cdf, p->environment_width, p->environment_height, u1, u2, &u, &v);
    float4 t = PM_LOAD(&kg->environment_texels[texel]);
    s.wi = environment_direction(u, v, p->environment_rotation);
    s.radiance = vec3_from_float4(t);
    s.pdf = environment_map_pdf(t.w, v);
  }
  return s;
}

/* One light sample seen from x (unit normal n on the side it is lit from; the shadow ray starts
   `offset` off the surface along n): wi, the irradiance estimate L cos_x / pdf (0 below x's
   horizon or when the scene blocks the direction) and the density per solid angle, in the area
   lights' sample type (area_lights.h), so that one next-event estimate serves both. */
typedef AreaLightSample EnvironmentLightSample;

PM_DEVICE EnvironmentLightSample environment_light_sample(const KernelGlobals* kg, const LaunchParams* p, Vec3 x, Vec3 n,
                                                          float offset, Uniform4 u)
{
  EnvironmentLightSample out;
  EnvironmentSample s = environment_sample(kg, p, u.u0, u.u1);
  out.wi = s.wi;
  out.irradiance = vec3_splat(0.0f);
  out.pdf_solid_angle = s.pdf;
  float cos_x = vec3_dot(n, s.wi);
  if (!(s.pdf > 0.0f) || cos_x <= 0.0f || vec3_max_component(s.radiance) <= 0.0f) return out;
  Ray shadow = ray_make(offset_ray_origin(x, n, offset), s.wi);
  if (scene_trace(kg, &shadow, 0.0f, 1e30f, 1).triangle >= 0) return out;
  out.irradiance = vec3_scale(s.radiance, cos_x / s.pdf);
  return out;
}

/* S1 from the environment (see above): u_dir1, u_dir2 draw the direction, u_disk1, u_disk2 the
   point on the disk (radius R sqrt(u_disk1), angle 2 pi u_disk2). Differentials: the photons of
   one direction form a parallel beam, so the directional differentials are zero; the positional
   ones give each photon its share of the disk as for an area light (area_lights.h): the
   position density is pdf_A = 1 / (pi R^2), a footprint's area is pi / (n pdf_A) = pi Delta^2
   |dp_u x dp_v| with Delta^2 = 4 pi / n, so dp_u, dp_v are orthogonal in the disk's plane with
   length R / 2 each. Returns 0 (and no photon) where the direction has no density or no light. */
PM_DEVICE int photon_emit_environment(const KernelGlobals* kg, const LaunchParams* p, float u_dir1, float u_dir2,
                                      float u_disk1, float u_disk2, uint emitted, PhotonRay* ray, Vec3* flux)
{
  EnvironmentSample s = environment_sample(kg, p, u_dir1, u_dir2);
  if (!(s.pdf > 0.0f) || vec3_max_component(s.radiance) <= 0.0f) return 0;
  float radius = p->environment_sphere.w;
  Vec3 t, b;
  vec3_onb(s.wi, &t, &b);
  float r = radius * pm_sqrtf(u_disk1), sin_a, cos_a;
  pm_sincosf(PM_TWO_PI * u_disk2, &sin_a, &cos_a);
  Vec3 centre = vec3_madd(vec3_from_float4(p->environment_sphere), s.wi, radius);
  ray->origin = vec3_madd(vec3_madd(centre, t, r * cos_a), b, r * sin_a);
  ray->direction = vec3_neg(s.wi);
  ray->dp_u = vec3_scale(t, 0.5f * radius);
  ray->dp_v = vec3_scale(b, 0.5f * radius);
  ray->dd_u = vec3_splat(0.0f);
  ray->dd_v = vec3_splat(0.0f);
  float area = PM_PI * radius * radius;
  *flux = vec3_scale(s.radiance, area / (s.pdf * (float)(emitted > 0u ? emitted : 1u)));
  return 1;
}

#endif

/* Reflection at a surface: the modified Phong BRDF (Lafortune & Willems 1994, "Using the
   Modified Phong Reflectance Model for Physically Based Rendering") plus a perfect mirror term
   handled by the tracers. f_r = rho_d / pi + rho_s (n + 2) / (2 pi) cos^n(alpha), alpha the angle
   between the mirror direction of wi and wo; energy-conserving when rho_d + rho_s <= 1.
   Also the importance sampling of each lobe, shared by the photon tracer (photon_trace.h) and the
   path tracer (path_trace.h), so both walk the same distributions with the same weights. */
#ifndef PM_BRDF_H
#define PM_BRDF_H

#include "types.h"
#include "vec3.h"


PM_DEVICE Material material_load(PM_GLOBAL const Material* materials, int index)
{
  return materials[index];
}

PM_DEVICE Vec3 material_diffuse(const Material* m) { return vec3(m->diffuse.x, m->diffuse.y, m->diffuse.z); }
PM_DEVICE Vec3 material_glossy(const Material* m) { return vec3(m->glossy.x, m->glossy.y, m->glossy.z); }
PM_DEVICE Vec3 material_mirror(const Material* m) { return vec3(m->mirror.x, m->mirror.y, m->mirror.z); }
PM_DEVICE int material_has_mirror(const Material* m) { return m->mirror.x > 0.0f || m->mirror.y > 0.0f || m->mirror.z > 0.0f; }

/* wi: unit direction towards the light (or where the photon came from), wo: towards the
   viewer, n: unit normal on the side of wo. Zero below the surface. */
PM_DEVICE Vec3 brdf_eval(const Material* m, Vec3 n, Vec3 wi, Vec3 wo)
{
  if (vec3_dot(n, wi) <= 0.0f || vec3_dot(n, wo) <= 0.0f) return vec3_splat(0.0f);
  Vec3 f = vec3_scale(material_diffuse(m), PM_INV_PI);
  Vec3 rho_s = material_glossy(m);
  if (rho_s.x > 0.0f || rho_s.y > 0.0f || rho_s.z > 0.0f) {
    float exponent = m->glossy.w;
    float cos_alpha = vec3_dot(vec3_reflect(vec3_neg(wi), n), wo);
    if (cos_alpha > 0.0f) {
      float lobe = (exponent + 2.0f) * (0.5f * PM_INV_PI) * pm_powf(cos_alpha, exponent);
      f = vec3_madd(f, rho_s, lobe);
    }
  }
  return f;
}

/* Mean of the three channels: the probability of choosing a reflectance's event in Russian
   roulette (photon tracer and path tracer alike). */
PM_DEVICE float channel_mean(Vec3 c) { return (c.x + c.y + c.z) * (1.0f / 3.0f); }

/* A direction sampled about an axis: polar angle (cos, sin) and azimuth phi. */
typedef struct LobeSample {
  float cos_theta, sin_theta, phi;
} LobeSample;

/* Diffuse lobe: cosine-weighted about the normal, cos theta = sqrt(1 - u1), sin theta = sqrt(u1)
   (the same distribution as cos theta = sqrt(u1), but cos theta is never exactly 0, so the
   direction is never tangent to the surface), phi = 2 pi u2. pdf cos theta / pi, so
   f_d cos theta / pdf = rho_d. */
PM_DEVICE LobeSample brdf_sample_diffuse(float u1, float u2)
{
  LobeSample s;
  s.cos_theta = pm_sqrtf(1.0f - u1);
  s.sin_theta = pm_sqrtf(u1);
  s.phi = PM_TWO_PI * u2;
  return s;
}

/* Glossy lobe: about the mirror direction r of the incoming direction, cos alpha = u1^(1/(n+1)),
   phi = 2 pi u2, pdf (n + 1) / (2 pi) cos^n alpha (the lobe's importance sampling, Lafortune &
   Willems 1994). Samples may fall below the surface; brdf_glossy_sample_weight is then 0. */
PM_DEVICE LobeSample brdf_sample_glossy(float exponent, float u1, float u2)
{
  LobeSample s;
  s.cos_theta = pm_powf(pm_fmaxf(u1, 1e-12f), 1.0f / (exponent + 1.0f));
  s.sin_theta = pm_sqrtf(pm_fmaxf(0.0f, 1.0f - s.cos_theta * s.cos_theta));
  s.phi = PM_TWO_PI * u2;
  return s;
}

/* f_s cos theta / pdf of a brdf_sample_glossy direction, per unit rho_s: the lobe's cos^n alpha
   cancels, leaving (n + 2) / (n + 1) cos theta, theta the angle to the normal (0 below it). */
PM_DEVICE float brdf_glossy_sample_weight(float exponent, float cos_theta)
{
  return cos_theta > 0.0f ? (exponent + 2.0f) / (exponent + 1.0f) * cos_theta : 0.0f;
}

/* Directional albedo of the glossy lobe per unit rho_s at cos theta_o = mu: the share of light
   arriving uniformly from the hemisphere that the lobe reflects towards a direction at theta_o
   (by reciprocity, the share of light from that direction that it reflects above the surface),
   a_n(mu) = integral (n + 2) / (2 pi) cos^n(alpha) cos theta_i d omega_i. It is 1 at mu = 1 and
   less towards grazing, where part of the lobe lies below the horizon. Midpoint rule over the
   lobe's importance sampling (brdf_sample_glossy, weight brdf_glossy_sample_weight), 16 x 16
   points: cos theta_i = cos alpha mu + sin alpha sin theta_o cos phi about the mirror direction. */
PM_DEVICE float brdf_glossy_albedo(float exponent, float mu)
{
  float sin_o = pm_sqrtf(pm_fmaxf(0.0f, 1.0f - mu * mu));
  float sum = 0.0f;
  for (int i = 0; i < 16; ++i) {
    float cos_a = pm_powf(((float)i + 0.5f) * (1.0f / 16.0f), 1.0f / (exponent + 1.0f));
    float sin_a = pm_sqrtf(pm_fmaxf(0.0f, 1.0f - cos_a * cos_a));
    for (int j = 0; j < 16; ++j) {
      float cos_i = cos_a * mu + sin_a * sin_o * pm_cosf(PM_TWO_PI * ((float)j + 0.5f) * (1.0f / 16.0f));
      sum += pm_fmaxf(cos_i, 0.0f);
    }
  }
  return (exponent + 2.0f) / (exponent + 1.0f) * sum * (1.0f / 256.0f);
}

/* Density per solid angle of the direction Russian roulette draws at a surface (the photon and
   path tracers): the diffuse lobe (cos theta / pi) with probability p_diffuse, the glossy lobe
   ((n + 1) / (2 pi) cos^n alpha about the mirror direction of wo) with p_glossy. wo and n as
   in brdf_eval. Multiple importance sampling weighs light samples against it. */
PM_DEVICE float brdf_sample_pdf(const Material* m, Vec3 n, Vec3 wo, Vec3 wi, float p_diffuse, float p_glossy)
{
  float cos_i = vec3_dot(n, wi);
  if (cos_i <= 0.0f) return 0.0f;
  float pdf = p_diffuse * cos_i * PM_INV_PI;
  if (p_glossy > 0.0f) {
    float exponent = m->glossy.w;
    float cos_alpha = vec3_dot(vec3_reflect(vec3_neg(wo), n), wi);
    if (cos_alpha > 0.0f) pdf += p_glossy * (exponent + 1.0f) * (0.5f * PM_INV_PI) * pm_powf(cos_alpha, exponent);
  }
  return pdf;
}

/* The sample as a world direction, (t, b, axis) an orthonormal frame. */
PM_DEVICE Vec3 lobe_direction(LobeSample s, Vec3 t, Vec3 b, Vec3 axis)
{
  float sin_phi, cos_phi;
  pm_sincosf(s.phi, &sin_phi, &cos_phi);
  return vec3_frame_to_world(t, b, axis, vec3(cos_phi * s.sin_theta, sin_phi * s.sin_theta, s.cos_theta));
}

#endif

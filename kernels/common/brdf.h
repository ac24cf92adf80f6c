/* Reflection at a surface: the modified Phong BRDF (Lafortune & Willems 1994, "Using the
   Modified Phong Reflectance Model for Physically Based Rendering") plus a perfect mirror term
   handled by the tracers. f_r = rho_d / pi + rho_s (n + 2) / (2 pi) cos^n(alpha), alpha the angle
   between the mirror direction of wi and wo; energy-conserving when rho_d + rho_s <= 1. */
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

#endif

/* Spot lights: a point light whose intensity is restricted to a cone about its axis (glTF
   KHR_lights_punctual "spot"). Owns the falloff every stage applies (camera pass, path tracer,
   radiosity's light links) and the spot's photon emission (S1), so that all of them agree.

   Falloff (the glTF extension's recommended smooth falloff): with c = cos of the angle between
   the axis and the direction from the light, c_o and c_i the cosines of the outer and inner cone
   angles,  f(c) = 0 for c <= c_o,  1 for c >= c_i,  ((c - c_o) / (c_i - c_o))^2 between.
   The intensity towards a direction is I(c) = power / (4 pi) * f(c) (types.h: power is the flux
   of the isotropic light with the same on-axis intensity), so the flux the spot emits is
   power / (4 pi) * integral f d omega = power * T / 2 with
   T = integral_{c_o}^{1} f(c) dc = (1 - c_i) + (c_i - c_o) / 3   (d omega = dc dphi).
   An isotropic point light is the case c_o = c_i = -1: f = 1, T = 2.

   The includer provides a compat header (PM_DEVICE, pm_* math) and vec3.h. */
#ifndef PM_SPOT_LIGHT_H
#define PM_SPOT_LIGHT_H

#include "photon_differentials.h"
#include "types.h"
#include "vec3.h"

/* Largest stretch of a spot photon's u differential (near the outer cone, where f -> 0 and
   photons are rare, their footprints grow without bound; footprints are clamped to r_max later). */
#define PM_SPOT_MAX_STRETCH 1.0e4f

PM_DEVICE int light_is_spot(const PointLight* light) { return light->position.w > -1.0f; }

/* f(c) above; 1 for an isotropic point light. */
PM_DEVICE float spot_falloff_cos(float c, float cos_outer, float cos_inner)
{
  if (c <= cos_outer) return 0.0f;
  if (c >= cos_inner) return 1.0f;
  float t = (c - cos_outer) / (cos_inner - cos_outer);
  return t * t;
}

/* The falloff towards unit direction `from_light` (pointing away from the light). */
PM_DEVICE float light_falloff(const PointLight* light, Vec3 from_light)
{
  if (!light_is_spot(light)) return 1.0f;
  return spot_falloff_cos(vec3_dot(vec3_from_float4(light->axis), from_light), light->position.w, light->power.w);
}

/* T = integral of f over c in [c_o, 1]: the emitted flux is power * T / 2. */
PM_DEVICE float spot_cone_mass(float cos_outer, float cos_inner)
{
  return (1.0f - cos_inner) + (cos_inner - cos_outer) * (1.0f / 3.0f);
}

/* Share of `power` the light emits: T / 2 (1 for a point light). */
PM_DEVICE float light_emitted_fraction(const PointLight* light)
{
  if (!light_is_spot(light)) return 1.0f;
  return 0.5f * spot_cone_mass(light->position.w, light->power.w);
}

/* Inverse of the emission distribution over c, whose density is f(c) / T: u in [0, 1) is the
   share of the mass counted down from c = 1. Above c_i the mass is linear in c (c = 1 - u T);
   below, the mass between c and c_i is (w^3 - (c - c_o)^3) / (3 w^2), w = c_i - c_o, which
   inverts to c = c_o + cbrt(w^3 - 3 w^2 m). */
PM_DEVICE float spot_sample_cos(float u, float cos_outer, float cos_inner)
{
  float mass = u * spot_cone_mass(cos_outer, cos_inner);
  float top = 1.0f - cos_inner;
  if (mass <= top) return 1.0f - mass;
  float w = cos_inner - cos_outer;
  float rest = pm_fmaxf(0.0f, w * w * w - 3.0f * w * w * (mass - top));
  return pm_fminf(cos_inner, cos_outer + pm_cbrtf(rest));
}

/* S1 for a spot (section 4.1 with the spot's distribution): c from spot_sample_cos(u1), phi =
   2 pi u2 about the axis, so every photon carries the same flux (power * T / 2 / n).
   Differentials: eq. 8 is written for the point light's parameters, cos theta = 1 - 2 u1 and
   phi = 2 pi u2, so dd_u = sin(theta) dd/dcos(theta) stands for a step of 2 in cos theta per
   unit u1 (the global Delta of eq. 9 then spaces photons by their share 4 pi / n of the sphere).
   Here dc/du1 = -T / f(c), so the same Delta needs dd_u stretched by (T / f(c)) / 2; dd_v is
   unchanged (phi is mapped alike). With f = 1 and T = 2 this is the point light. Positional
   differentials start at zero as for the point light. */
PM_DEVICE void photon_emit_spot(const PointLight* light, float u1, float u2, PhotonRay* out)
{
  float cos_outer = light->position.w, cos_inner = light->power.w;
  float c = spot_sample_cos(u1, cos_outer, cos_inner);
  float s = pm_sqrtf(pm_fmaxf(0.0f, (1.0f - c) * (1.0f + c)));
  Vec3 d, du, dv;
  photon_sphere_direction(c, s, PM_TWO_PI * u2, &d, &du, &dv);
  Vec3 axis = vec3_from_float4(light->axis), t, b;
  vec3_onb(axis, &t, &b);
  float f = spot_falloff_cos(c, cos_outer, cos_inner);
  float stretch = 0.5f * spot_cone_mass(cos_outer, cos_inner) / pm_fmaxf(f, 1e-30f);
  stretch = pm_fminf(stretch, PM_SPOT_MAX_STRETCH);
  out->origin = vec3_from_float4(light->position);
  out->direction = vec3_frame_to_world(t, b, axis, d);
  out->dd_u = vec3_scale(vec3_frame_to_world(t, b, axis, du), stretch);
  out->dd_v = vec3_frame_to_world(t, b, axis, dv);
  out->dp_u = vec3_splat(0.0f);
  out->dp_v = vec3_splat(0.0f);
}

#endif

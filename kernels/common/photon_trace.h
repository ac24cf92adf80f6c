/* Stages S1 emission and S2 tracing (paper sections 4.1-4.3): one work item per photon emits it
   from its point light, spot light (spot_light.h), the area lights (area_lights.h) or the
   environment (environment_light.h) with pre-scaled differentials (eq. 8), traces it through the scene,
   updates its differentials (Igehy transfer and mirror reflection, Russian roulette rescale,
   diffuse re-emission with the virtual offset of eq. 10-13) and records a hit at every diffuse or
   glossy surface that is not lit directly. Records go to slots [photon * slots_per_photon + k],
   so the result does not depend on scheduling; unused slots are marked empty. */
#ifndef PM_PHOTON_TRACE_H
#define PM_PHOTON_TRACE_H

#include "area_lights.h"
#include "brdf.h"
#include "emission_order.h"
#include "environment_light.h"
#include "kernel_globals.h"
#include "photon_differentials.h"
#include "rng.h"
#include "scene_traverse.h"
#include "spot_light.h"


/* Photons are shared out by power: light l owns pass indices [first, first + count) of
   photon_emitters[l] = (first, count, 0, 0). With area lights, entry light_count holds the
   photons of all emitting triangles together; the environment's share comes last
   (photon_environment_entry). */
PM_DEVICE uint photon_environment_entry(const LaunchParams* p)
{
  return p->light_count + (p->emitter_count > 0u ? 1u : 0u);
}

PM_DEVICE int photon_light_of(const KernelGlobals* kg, const LaunchParams* p, uint photon)
{
  uint emitters = photon_environment_entry(p) + (p->environment != PM_ENVIRONMENT_NONE ? 1u : 0u);
  for (uint l = 0; l < emitters; ++l) {
    uint4 e = kg->photon_emitters[l];
    if (photon >= e.x && photon < e.x + e.y) return (int)l;
  }
  return -1;
}

/* Glossy reflection: a direction from the modified Phong lobe about the mirror direction r
   (cos alpha = u1^(1/(n+1)), the lobe's importance sampling), with eq.-8 differentials in the
   lobe's frame and the same area-preserving virtual offset as diffuse re-emission (eq. 13).
   Returns 0 when the sample falls below the surface. */
PM_DEVICE int photon_glossy_reemit(PhotonRay* ray, Vec3 n, float exponent, float u1, float u2)
{
  Vec3 nf = vec3_dot(ray->direction, n) > 0.0f ? vec3_neg(n) : n;
  Vec3 r = vec3_reflect(ray->direction, nf);
  Vec3 t, b;
  vec3_onb(r, &t, &b);
  LobeSample s = brdf_sample_glossy(exponent, u1, u2);
  photon_reemit_in_frame(ray, t, b, r, s.cos_theta, s.sin_theta, s.phi);
  return vec3_dot(ray->direction, nf) > 0.0f;
}

/* A hit: its flags and the index of its record in its slot (one word), the hit in the record.
   Most slots stay empty (a photon is absorbed or leaves before it fills its slots: three in four
   on Sponza), so the records are taken as hits come, by an atomic counter, and the slot says
   which record is its own; everything after the trace reads in slot order, so the image does not
   depend on the order the records were taken in. Five float4 a record, side by side
   (PM_RECORD_*): the flux rides in the w of the normal and the differentials. A hit beyond the records' room keeps an
   empty slot: the host sees the count over the room, grows the records and traces the pass
   again. */
PM_DEVICE void photon_store_hit(const KernelGlobals* kg, uint slot, const PhotonRay* ray, Vec3 n, Vec3 flux, float delta,
                                uint flags)
{
  uint record = pm_atomic_add_u32(&kg->hit_record_count[0], 1u);
  if (record >= kg->hit_record_count[1]) {
    kg->hit_slots[slot] = 0u;
    return;
  }
  if (vec3_dot(n, ray->direction) > 0.0f) n = vec3_neg(n); /* the side the photon arrived on */
  kg->hit_slots[slot] = flags | (record << PM_HIT_RECORD_SHIFT);
  PM_GLOBAL float4* out = &kg->hit_records[PM_RECORD_FLOAT4S * record];
  out[PM_RECORD_POSITION] = vec3_to_float4(ray->origin, 0.0f);
  out[PM_RECORD_NORMAL] = vec3_to_float4(n, flux.x);
  out[PM_RECORD_INCIDENT] = vec3_to_float4(vec3_neg(ray->direction), delta);
  out[PM_RECORD_DP_U] = vec3_to_float4(ray->dp_u, flux.y);
  out[PM_RECORD_DP_V] = vec3_to_float4(ray->dp_v, flux.z);
}

/* The record of the hit in a slot whose word is `slot_word` (photon_store_hit). */
PM_DEVICE uint photon_hit_record(uint slot_word)
{
  return slot_word >> PM_HIT_RECORD_SHIFT;
}

/* One float4 of a hit record (PM_RECORD_*). */
PM_DEVICE float4 photon_hit_part(const KernelGlobals* kg, uint record, uint part)
{
  return kg->hit_records[PM_RECORD_FLOAT4S * record + part];
}

/* The flux a hit record carries. */
PM_DEVICE Vec3 photon_hit_flux(const KernelGlobals* kg, uint record)
{
  return vec3(photon_hit_part(kg, record, PM_RECORD_NORMAL).w, photon_hit_part(kg, record, PM_RECORD_DP_U).w,
              photon_hit_part(kg, record, PM_RECORD_DP_V).w);
}

PM_DEVICE void kernel_photon_trace(const KernelGlobals* kg, const LaunchParams* p, uint photon)
{
  uint first_slot = photon * p->hit_slots_per_photon;
  uint stored = 0;
  int light_index = photon_light_of(kg, p, photon);
  if (light_index >= 0) {
    /* The area lights' and the environment's shares (photon_light_of). */
    int area = p->emitter_count > 0u && (uint)light_index == p->light_count;
    int environment = p->environment != PM_ENVIRONMENT_NONE && (uint)light_index == photon_environment_entry(p);
    uint4 emitter = kg->photon_emitters[light_index];
    uint emitted = emitter.y;
    float delta = photon_spacing(emitted); /* eq. 9 with n = this light's photons in the pass */
    /* Random numbers: RANDOM keys them by (seed, photon_frame) and the photon's index in the
       frame; HALTON by the seed, the light and the photon's number within that light only, so
       the same lights give the same photons in every frame (types.h). */
    uint rng_frame = p->photon_frame, rng_index = p->photon_offset + photon;
    /* The photon's 64-bit index within the frame: its high word keys the counter's spare word. */
    uint rng_extra = p->photon_offset_hi + (rng_index < p->photon_offset ? 1u : 0u);
    Uniform4 u;
    if (p->photon_sequence == PM_PHOTON_SEQUENCE_HALTON) {
      uint pass = p->photon_count > 0u ? p->photon_offset / p->photon_count : 0u;
      rng_frame = 0u;
      rng_index = pass * emitted + (photon - emitter.x);
      rng_extra = (uint)light_index + 1u;
      /* Halton points (bases 2 and 3), shifted modulo 1 by one random offset per seed and light
         (Cranley-Patterson rotation) so that lights and seeds do not share directions. */
      Bits4 shift = rng_bits4(p->seed, 0u, 0u, 0u, PM_STREAM_HALTON, rng_extra);
      u.u0 = rng_to_unit(radical_inverse2_bits(rng_index) + shift.b0);
      u.u1 = rng_to_unit(radical_inverse3_bits(rng_index) + shift.b1);
      u.u2 = 0.0f;
      u.u3 = 0.0f;
    } else {
      /* Stratified and coherent (emission_order.h): the light's photons of this pass each own a
         stratum, consecutive photons neighbouring ones. */
      Bits4 b = rng_bits4(p->seed, rng_frame, rng_index, 0u, PM_STREAM_PHOTON, rng_extra);
      stratified_emission(photon - emitter.x, emitted, b.b0, b.b1, b.b2, &u.u0, &u.u1);
      u.u2 = 0.0f;
      u.u3 = 0.0f;
    }
    PhotonRay ray;
    Vec3 flux;
    Vec3 start;
    int emits = 1;
    if (environment) {
      /* The point on the disk: a stream of its own, keyed like the direction. */
      Uniform4 w = rng_uniform4_bits(rng_bits4(p->seed, rng_frame, rng_index, 0u, PM_STREAM_ENVIRONMENT, rng_extra));
      emits = photon_emit_environment(kg, p, u.u0, u.u1, w.u0, w.u1, emitted, &ray, &flux);
      start = ray.origin;
    } else if (area) {
      /* The emitter and the point on it: a stream of their own, keyed like the direction. */
      Uniform4 w = rng_uniform4_bits(rng_bits4(p->seed, rng_frame, rng_index, 0u, PM_STREAM_AREA, rng_extra));
      Vec3 normal = photon_emit_area(kg, p, w.u0, w.u1, w.u2, u.u0, u.u1, emitted, &ray, &flux);
      start = offset_ray_origin(ray.origin, normal, ray_offset_distance(ray.origin, 0.0f, p->ray_epsilon));
    } else {
      PointLight light = kg->lights[light_index];
      /* Every photon of a light carries the same flux: its emitted power over its photons. */
      flux = vec3_scale(vec3_from_float4(light.power), light_emitted_fraction(&light) / (float)emitted);
      if (light_is_spot(&light)) photon_emit_spot(&light, u.u0, u.u1, &ray);
      else photon_emit_point(vec3_from_float4(light.position), u.u0, u.u1, &ray);
      start = ray.origin;
    }
    uint diffuse_bounces = 0, specular_bounces = 0;
    for (uint event = 1; emits && event <= p->max_bounces + PM_PHOTON_MAX_SPECULAR + 1; ++event) {
      Ray r = ray_make(start, ray.direction);
      SceneHit hit = scene_trace(kg, &r, 0.0f, 1e30f, 0);
      if (hit.triangle < 0) break;
      Vec3 n = scene_triangle_normal(kg->triangles, hit.triangle);
      /* Differentials travel from the ray origin (the offset start, off the last hit by ray.h's
         offset, a negligible fraction of the path). */
      ray.origin = start;
      photon_transfer(&ray, hit.t, n);
      /* The reflectances at the hit, textured: they choose the photon's event and scale its flux. */
      Material m = surface_material(kg, scene_triangle_material(kg->triangles, hit.triangle), hit.triangle, ray.origin);
      float p_diffuse = channel_mean(material_diffuse(&m));
      float p_glossy = channel_mean(material_glossy(&m));
      float p_mirror = channel_mean(material_mirror(&m));

      /* Hits lit straight from the light are direct light, which the camera pass ray traces. */
      if (p_diffuse + p_glossy > 0.0f && (diffuse_bounces > 0 || specular_bounces > 0) &&
          stored < p->hit_slots_per_photon) {
        uint flags = PM_HIT_VALID | (diffuse_bounces == 0 ? PM_HIT_CAUSTIC : 0u);
        photon_store_hit(kg, first_slot + stored, &ray, n, flux, delta, flags);
        ++stored;
      }

      /* Russian roulette chooses absorption or one reflection event (section 4.2). */
      u = rng_uniform4_bits(rng_bits4(p->seed, rng_frame, rng_index, event, PM_STREAM_PHOTON, rng_extra));
      Vec3 side = vec3_dot(n, ray.direction) > 0.0f ? vec3_neg(n) : n;
      if (u.u2 < p_diffuse + p_glossy) {
        if (diffuse_bounces == p->max_bounces) break; /* its next hit would not be recorded */
        if (u.u2 < p_diffuse) {
          flux = vec3_scale(vec3_mul(flux, material_diffuse(&m)), 1.0f / p_diffuse);
          photon_roulette_rescale(&ray, p_diffuse);
          photon_diffuse_reemit(&ray, n, u.u0, u.u1);
        } else {
          float exponent = m.glossy.w;
          photon_roulette_rescale(&ray, p_glossy);
          if (!photon_glossy_reemit(&ray, n, exponent, u.u0, u.u1)) break;
          float weight = brdf_glossy_sample_weight(exponent, vec3_dot(side, ray.direction));
          flux = vec3_scale(vec3_mul(flux, material_glossy(&m)), weight / p_glossy);
        }
        ++diffuse_bounces;
      } else if (u.u2 < p_diffuse + p_glossy + p_mirror) {
        if (specular_bounces == PM_PHOTON_MAX_SPECULAR) break;
        flux = vec3_scale(vec3_mul(flux, material_mirror(&m)), 1.0f / p_mirror);
        photon_roulette_rescale(&ray, p_mirror);
        photon_reflect_specular(&ray, n);
        ++specular_bounces;
      } else {
        break; /* absorbed */
      }
      start = offset_ray_origin(ray.origin, side, ray_offset_distance(start, hit.t, p->ray_epsilon));
    }
  }
  for (uint k = stored; k < p->hit_slots_per_photon; ++k)
    kg->hit_slots[first_slot + k] = 0u; /* no flags */
}

#endif

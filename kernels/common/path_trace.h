/* The reference path tracer (--method path): from every shading point of the camera pass (S5),
   unidirectional path tracing with next-event estimation to every point and spot light and to
   the area lights at each vertex, and the modified-Phong BRDF and mirror term of brdf.h. Its
   paths are classified by events as the photon tracer's (photon_trace.h), so that its indirect
   layer converges to exactly what the photon mapper's indirect layer estimates (docs/tradeoff.md,
   "Which light paths"); unlike the photon tracer's, its roulette weighs by throughput and
   starts late (PM_PATH_ROULETTE_VERTEX).

   A path x <- v1 <- ... <- vn <- light starts at the shading point x, whose own diffuse and
   glossy lobes choose the first direction (its mirror term belongs to the camera pass), and
   reflects at v1..vn: a diffuse or glossy event (D) or a perfect-mirror event (S). Counted, as
   in the photon tracer: paths with at most max_bounces D events and at most
   PM_PHOTON_MAX_SPECULAR S events among v1..vn, and at least one event (x <- light is direct
   light, the camera pass's). A point or spot light is reached only by a shadow ray from a D
   vertex: a point light seen in a perfect mirror has zero probability under both BRDF sampling
   and next-event estimation (the photon mapper does trace those paths, in its caustic layer and
   part of its indirect layer). An area light is reached both ways: a light sample at each D
   vertex, and a sampled direction that hits an emitter's front face. Where both strategies can
   make the path, multiple importance sampling (power heuristic, Veach 1997) weighs them by their
   densities per solid angle (brdf_sample_pdf, area_lights.h); with path_mis off, light samples
   alone count those paths. A path that meets the emitter after a mirror event only the
   sampled direction can make, so it counts fully. The environment (environment_light.h) is
   met the same two ways: a light sample at each D vertex, and a sampled direction that leaves
   the scene, weighed by MIS against light sampling's density for that direction.

   One work item per pixel (in tile order); each pass adds the mean of path_samples paths per shading point,
   weighted by the shading point's mirror weight, into film_indirect_sum (the caustic sum gets
   nothing). Random numbers: Philox keyed by (seed, path_frame), counter (pixel, depth and
   vertex, PM_STREAM_PATH or PM_STREAM_AREA, path index within the frame). */
#ifndef PM_PATH_TRACE_H
#define PM_PATH_TRACE_H

#include "brdf.h"
#include "camera_pass.h"
#include "film.h"
#include "kernel_globals.h"
#include "pixel_order.h"
#include "rng.h"
#include "sampled_lights.h"
#include "scene_traverse.h"

#define PM_STREAM_PATH 0x50415448u /* "PATH" */
/* The first vertex whose continuation plays Russian roulette on the path's throughput (as
   Mitsuba 3's rr_depth, which counts the camera's hit as depth 1 and starts at 5): the default
   two bounces never reach it; longer paths end there at the odds of their throughput. */
#define PM_PATH_ROULETTE_VERTEX 4u
/* The highest survival probability of the roulette, so that a path of full throughput ends. */
#define PM_PATH_MAX_SURVIVAL 0.95f

/* Samples a direction from the diffuse (glossy == 0) or glossy lobe of m at a point with normal
   n facing wo. Returns f cos / pdf per channel (rho_d, or rho_s times the lobe weight); zero when
   a glossy sample falls below the surface. */
PM_DEVICE Vec3 path_sample_lobe(const Material* m, int glossy, Vec3 n, Vec3 wo, float u1, float u2, Vec3* wi)
{
  Vec3 t, b;
  if (!glossy) {
    vec3_onb(n, &t, &b);
    *wi = lobe_direction(brdf_sample_diffuse(u1, u2), t, b, n);
    return material_diffuse(m);
  }
  Vec3 r = vec3_reflect(vec3_neg(wo), n);
  vec3_onb(r, &t, &b);
  *wi = lobe_direction(brdf_sample_glossy(m->glossy.w, u1, u2), t, b, r);
  return vec3_scale(material_glossy(m), brdf_glossy_sample_weight(m->glossy.w, vec3_dot(n, *wi)));
}

/* The first direction of path `path` from x (m's diffuse or glossy lobe, chosen in proportion
   to their reflectances) and its weight f cos / pdf; zero where x reflects nothing that way or
   the path has no bounce. */
PM_DEVICE Vec3 path_first_direction(const LaunchParams* p, const Material* m, Vec3 n, Vec3 wo, uint pixel, uint depth,
                                    uint path, Vec3* dir)
{
  float p_diffuse = channel_mean(material_diffuse(m)), p_glossy = channel_mean(material_glossy(m));
  if (p->max_bounces == 0u || p_diffuse + p_glossy <= 0.0f) return vec3_splat(0.0f);
  Uniform4 u = rng_uniform4_bits(rng_bits4(p->seed, p->path_frame, pixel, depth << 8, PM_STREAM_PATH, path));
  float p_lobe_diffuse = p_diffuse / (p_diffuse + p_glossy);
  int glossy = u.u2 >= p_lobe_diffuse;
  Vec3 beta = path_sample_lobe(m, glossy, n, wo, u.u0, u.u1, dir);
  return vec3_scale(beta, 1.0f / (glossy ? 1.0f - p_lobe_diffuse : p_lobe_diffuse));
}

/* One path's estimate of the indirect radiance leaving x towards wo (n facing wo). */
PM_DEVICE Vec3 path_radiance(const KernelGlobals* kg, const LaunchParams* p, const Material* m, Vec3 x, Vec3 n, Vec3 wo,
                             uint pixel, uint depth, uint path)
{
  Vec3 radiance = vec3_splat(0.0f);
  uint event_base = depth << 8; /* at most max_bounces + PM_PHOTON_MAX_SPECULAR + 1 < 256 vertices */
  Vec3 dir;
  Vec3 beta = path_first_direction(p, m, n, wo, pixel, depth, path, &dir);
  if (vec3_max_component(beta) <= 0.0f) return radiance;

  Vec3 origin = offset_ray_origin(x, n, ray_offset_distance(x, 0.0f, p->ray_epsilon));
  uint diffuse_events = 0, mirror_events = 0;
  int after_diffuse = 0;  /* the last event was a D event (1) or a mirror event (0), for MIS */
  float direction_pdf = 0.0f; /* density per solid angle of the last D event's direction */
  for (uint vertex = 1; vertex <= p->max_bounces + PM_PHOTON_MAX_SPECULAR; ++vertex) {
    Ray ray = ray_make(origin, dir);
    SceneHit hit = scene_trace(kg, &ray, 0.0f, 1e30f, 0);
    if (hit.triangle < 0) {
      /* The environment reached by the sampled direction (from v2 on, as for an emitter). */
      if (vertex >= 2u && p->environment != PM_ENVIRONMENT_NONE) {
        float weight = 1.0f;
        if (after_diffuse) weight = p->path_mis ? mis_power_weight(direction_pdf, environment_pdf(kg, p, dir)) : 0.0f;
        radiance = vec3_add(radiance, vec3_scale(vec3_mul(beta, environment_radiance(kg, p, dir)), weight));
      }
      break;
    }
    Vec3 pos = vec3_madd(origin, dir, hit.t);
    Vec3 nv = scene_triangle_normal(kg->triangles, hit.triangle);
    int material_index = scene_triangle_material(kg->triangles, hit.triangle);
    /* An emitter reached by the sampled direction (from v2 on: at v1 it is x's direct light). */
    if (vertex >= 2u && p->emitter_count > 0u) {
      Vec3 emitted = surface_emission(kg, p, material_index, nv, dir);
      if (vec3_max_component(emitted) > 0.0f) {
        float weight = 1.0f;
        if (after_diffuse) {
          float cos_y = pm_fabsf(vec3_dot(vec3_normalize(nv), dir));
          float light_pdf = cos_y > 0.0f ? area_light_pdf_area(p, channel_mean(emitted)) * hit.t * hit.t / cos_y : 0.0f;
          weight = p->path_mis ? mis_power_weight(direction_pdf, light_pdf) : 0.0f;
        }
        radiance = vec3_add(radiance, vec3_scale(vec3_mul(beta, emitted), weight));
      }
    }
    if (vec3_dot(nv, dir) > 0.0f) nv = vec3_neg(nv); /* the side the path arrived on */
    Vec3 wv = vec3_neg(dir);
    Material mv = surface_material(kg, material_index, hit.triangle, pos);
    float offset = ray_offset_distance(origin, hit.t, p->ray_epsilon);
    float pd = channel_mean(material_diffuse(&mv)), pg = channel_mean(material_glossy(&mv));
    float pm = channel_mean(material_mirror(&mv));
    /* A further D event leaves max_bounces no room for the next vertex's light. */
    int may_continue = diffuse_events + 1u < p->max_bounces;

    /* Next-event estimation: the paths whose last D event is this vertex. */
    radiance = vec3_add(radiance, vec3_mul(beta, direct_light(kg, p, &mv, pos, nv, wv, offset)));
    for (uint kind = 0; kind < PM_SAMPLED_LIGHT_KINDS; ++kind) {
      if (!sampled_light_present(p, kind)) continue;
      Uniform4 u = rng_uniform4_bits(
          rng_bits4(p->seed, p->path_frame, pixel, event_base + vertex, sampled_light_stream(kind), path));
      AreaLightSample s = sampled_light_sample(kg, p, kind, pos, nv, offset, u);
      if (vec3_max_component(s.irradiance) > 0.0f) {
        float weight = 1.0f;
        if (p->path_mis && may_continue)
          weight = mis_power_weight(s.pdf_solid_angle, brdf_sample_pdf(&mv, nv, wv, s.wi, pd, pg));
        radiance = vec3_add(radiance, vec3_scale(vec3_mul(beta, vec3_mul(brdf_eval(&mv, nv, s.wi, wv), s.irradiance)), weight));
      }
    }

    /* The next event, chosen in proportion to the reflectances of its lobes with no absorption
       (the weight carries the albedo instead), then Russian roulette on the throughput from
       vertex PM_PATH_ROULETTE_VERTEX on. Absorbing at the albedo's complement from v1 on, as the
       photon tracer must (its photons carry fixed power), drops the later vertices' light on
       most paths and returns it at 1 / albedo on the rest: 1.2-1.3 times the variance per path
       of this scheme on the benchmark scenes, 1.16-1.33 times Mitsuba 3's on the Cornell box,
       for 11-32 % less time per path (docs/tradeoff.md, "Noise per path"). */
    Uniform4 u = rng_uniform4_bits(rng_bits4(p->seed, p->path_frame, pixel, event_base + vertex, PM_STREAM_PATH, path));
    float albedo = pd + pg + pm;
    if (!(albedo > 0.0f)) break;
    float pick = u.u2 * albedo;
    if (pick < pd + pg) {
      if (!may_continue) break;
      int lobe_glossy = pick >= pd;
      Vec3 f = path_sample_lobe(&mv, lobe_glossy, nv, wv, u.u0, u.u1, &dir);
      beta = vec3_scale(vec3_mul(beta, f), albedo / (lobe_glossy ? pg : pd));
      if (vec3_max_component(beta) <= 0.0f) break;
      direction_pdf = brdf_sample_pdf(&mv, nv, wv, dir, pd, pg);
      after_diffuse = 1;
      ++diffuse_events;
    } else {
      if (mirror_events == PM_PHOTON_MAX_SPECULAR) break;
      beta = vec3_scale(vec3_mul(beta, material_mirror(&mv)), albedo / pm);
      dir = vec3_reflect(dir, nv);
      after_diffuse = 0;
      ++mirror_events;
    }
    if (vertex >= PM_PATH_ROULETTE_VERTEX) {
      float survive = pm_fminf(vec3_max_component(beta), PM_PATH_MAX_SURVIVAL);
      if (!(u.u3 < survive)) break;
      beta = vec3_scale(beta, 1.0f / survive);
    }
    origin = offset_ray_origin(pos, nv, offset);
  }
  return radiance;
}

/* Work item = pixel in tile order (pixel_order.h). */
PM_DEVICE void kernel_path_trace(const KernelGlobals* kg, const LaunchParams* p, uint item)
{
  uint pixel;
  if (!pixel_of_work_item(item, p->width, p->height, &pixel)) return;
  Vec3 indirect = vec3_splat(0.0f);
  float inv_samples = 1.0f / (float)(p->path_samples > 0u ? p->path_samples : 1u);
  EyePath eye = eye_path_begin(pixel);
  ShadingPoint sp;
  for (uint depth = 0; eye_path_next(kg, p, &eye, &sp); ++depth) {
    Vec3 sum = vec3_splat(0.0f);
    for (uint s = 0; s < p->path_samples; ++s)
      sum = vec3_add(sum, path_radiance(kg, p, &sp.material, sp.position, sp.normal, sp.outgoing, pixel, depth,
                                        p->path_first_sample + s));
    indirect = vec3_add(indirect, vec3_mul(sp.weight, vec3_scale(sum, inv_samples)));
  }
  film_add(kg, p, pixel, indirect, vec3_splat(0.0f));
}

#endif

/* Final gathering over a cached solution (--final-gather N; docs/final-gathering.md; Jensen 1996,
   "Global illumination using photon maps", section 3.3): instead of reading the photon map or the
   radiosity solution at the camera's shading point x, where its blur shows, N rays leave x by its
   own diffuse and glossy lobes, and the cache is read only at their hits y, where that blur is
   averaged over x's hemisphere.

   The light reflected at x then splits by the event at y:
   - the direct light at y, exactly: a shadow ray to every point and spot light (direct_light) and
     next-event estimates of the area lights and the environment (sampled_light_sample);
   - the light that reached y after further bounces, from the cache, solved with one bounce fewer
     (photon_mapping.cpp, vertex_link_radiosity.cpp), so that paths x <- y <- ... keep the method's
     count of diffuse and glossy events:
     PM_FINAL_GATHER_PHOTONS: the photon map traced with max_bounces - 1. Its caustic photons
       (light that reached y through mirrors only) count at y as well, as the photon method counts
       them one bounce later;
     PM_FINAL_GATHER_RADIOSITY: the vertex irradiance gathered over bounces - 1 bounces,
       interpolated at y and reflected as the radiosity image reflects it (radiosity_interpolate.h).
   A gather ray that meets a mirror follows it (up to PM_PHOTON_MAX_SPECULAR times), weighted by the
   mirror's reflectance, to the first surface that reflects diffusely. The emitters and the
   environment a gather ray sees directly are not counted: they are x's direct light (the camera
   pass) or, through mirrors, x's caustic light, which x still reads from the photon map as the
   photon method does.

   Directions: the lobe (diffuse or glossy) in proportion to the reflectances, as the path tracer's
   first vertex (path_trace.h), chosen by the direction's first number. The directions are the
   points of two scrambled Sobol sequences, one for the even passes and one for the odd
   (low_discrepancy.h): pass 2j + r takes the next N points of sequence r, so a pixel's rays over
   the frame spread over its hemisphere as a net does, and its error falls faster than
   independent rays' (docs/final-gathering.md, "Directions from a scrambled sequence"). The
   scrambles are keyed by Philox (seed, photon_frame), counter (pixel, mirror depth, "FGAT", ~0),
   their first digits by (tile, mirror depth, "FGAT", ~1), shared by the pixels of a warp;
   the light samples at a hit by (pixel, mirror depth and vertex, ray index within the frame:
   pass * N + ray), as the camera pass's (sampled_light_direct, one per kind). */
#ifndef PM_FINAL_GATHER_H
#define PM_FINAL_GATHER_H

#include "gather.h"
#include "low_discrepancy.h"
#include "path_trace.h"
#include "radiosity_interpolate.h"
#include "sampled_lights.h"

#define PM_STREAM_FINAL_GATHER 0x46474154u /* "FGAT" */

/* The cache the gather rays read (a constant at each kernel entry, so each kernel keeps only its
   own cache's code and registers). */
#define PM_FINAL_GATHER_PHOTONS 0u
#define PM_FINAL_GATHER_RADIOSITY 1u

/* Radiance leaving y (on scene triangle `leaf`) towards wy (ny facing wy) by one diffuse or glossy
   reflection at y: the direct light, exactly, and the cache's light arriving after further bounces
   (photons read added to *accepted). */
PM_DEVICE Vec3 final_gather_at_hit(const KernelGlobals* kg, const LaunchParams* p, const Material* my, int leaf, Vec3 y,
                                   Vec3 ny, Vec3 wy, float offset, uint pixel, uint event, uint ray, uint* accepted,
                                   uint cache)
{
  Vec3 radiance = direct_light(kg, p, my, y, ny, wy, offset);
  for (uint kind = 0; kind < PM_SAMPLED_LIGHT_KINDS; ++kind)
    radiance = vec3_add(radiance, sampled_light_direct(kg, p, kind, my, y, ny, wy, offset, 1u, pixel, event, ray));
  if (cache == PM_FINAL_GATHER_RADIOSITY) {
    if (p->element_count > 0u)
      radiance = vec3_add(radiance, radiosity_reflected(kg, p, my, leaf, y, ny, pm_fabsf(vec3_dot(wy, ny))));
  } else if (p->hit_count > 0u) {
    Vec3 indirect = vec3_splat(0.0f), caustic = vec3_splat(0.0f);
    gather_at(kg, p, my, y, ny, wy, &indirect, &caustic, accepted, p->facet_weighting != 0u);
    radiance = vec3_add(radiance, vec3_add(indirect, caustic));
  }
  return radiance;
}

/* The radiance a gather ray from origin along dir brings back: at each surface it meets, through
   mirrors, what that surface reflects diffusely towards the ray. */
PM_DEVICE Vec3 final_gather_ray(const KernelGlobals* kg, const LaunchParams* p, Vec3 origin, Vec3 dir, uint pixel,
                                uint event_base, uint ray, uint* accepted, uint cache)
{
  Vec3 radiance = vec3_splat(0.0f), throughput = vec3_splat(1.0f);
  for (uint vertex = 1; vertex <= PM_PHOTON_MAX_SPECULAR + 1u; ++vertex) {
    Ray r = ray_make(origin, dir);
    SceneHit hit = scene_trace(kg, &r, 0.0f, 1e30f, 0);
    if (hit.triangle < 0) break;
    Vec3 pos = vec3_madd(origin, dir, hit.t);
    Vec3 n = scene_triangle_normal(kg->triangles, hit.triangle);
    if (vec3_dot(n, dir) > 0.0f) n = vec3_neg(n); /* the side the ray arrived on */
    Vec3 wo = vec3_neg(dir);
    Material m = surface_material(kg, scene_triangle_material(kg->triangles, hit.triangle), hit.triangle, pos);
    float offset = ray_offset_distance(origin, hit.t, p->ray_epsilon);
    if (channel_mean(material_diffuse(&m)) + channel_mean(material_glossy(&m)) > 0.0f)
      radiance = vec3_add(radiance, vec3_mul(throughput, final_gather_at_hit(kg, p, &m, hit.triangle, pos, n, wo, offset,
                                                                              pixel, event_base + vertex, ray, accepted,
                                                                              cache)));
    Vec3 mirror = material_mirror(&m);
    if (vec3_max_component(mirror) <= 0.0f) break;
    throughput = vec3_mul(throughput, mirror);
    dir = vec3_reflect(dir, n);
    origin = offset_ray_origin(pos, n, offset);
  }
  return radiance;
}

/* Work item = pixel in tile order (pixel_order.h): at each shading point of the mirror chain, the
   mean of the pass's gather rays into the indirect sum and (photons) the map's caustic light there
   into the caustic sum; with collect_stats, the photons read and the shading points gathered, as
   the gather counts them (gather.h). */
PM_DEVICE void final_gather_pixel(const KernelGlobals* kg, const LaunchParams* p, uint item, uint cache)
{
  uint pixel;
  if (!pixel_of_work_item(item, p->width, p->height, &pixel)) return;
  uint rays = p->final_gather_rays > 0u ? p->final_gather_rays : 1u;
  Vec3 indirect = vec3_splat(0.0f), caustic = vec3_splat(0.0f);
  uint accepted = 0, points = 0;
  EyePath eye = eye_path_begin(pixel);
  ShadingPoint sp;
  for (uint depth = 0; eye_path_next(kg, p, &eye, &sp); ++depth) {
    const Material* m = &sp.material;
    float p_diffuse = channel_mean(material_diffuse(m)), p_glossy = channel_mean(material_glossy(m));
    if (p_diffuse + p_glossy <= 0.0f) continue;
    if (cache == PM_FINAL_GATHER_PHOTONS && p->hit_count > 0u) {
      Vec3 unused = vec3_splat(0.0f), point_caustic = vec3_splat(0.0f);
      gather_at(kg, p, m, sp.position, sp.normal, sp.outgoing, &unused, &point_caustic, &accepted,
                p->facet_weighting != 0u);
      caustic = vec3_add(caustic, vec3_mul(sp.weight, point_caustic));
    }
    uint event_base = depth << 8; /* at most PM_PHOTON_MAX_SPECULAR + 2 vertices below x */
    /* The scrambles of the pixel's two replicates, the same in every pass of the frame: the
       first digits the tile's, so that the warp's rays leave together (low_discrepancy.h). */
    FirstBounceKeys keys;
    keys.own = rng_bits4(p->seed, p->photon_frame, pixel, event_base, PM_STREAM_FINAL_GATHER, 0xffffffffu);
    keys.tile = rng_bits4(p->seed, p->photon_frame, tile_of_pixel(pixel, p->width), event_base, PM_STREAM_FINAL_GATHER,
                          0xfffffffeu);
    Vec3 origin = offset_ray_origin(sp.position, sp.normal, ray_offset_distance(sp.position, 0.0f, p->ray_epsilon));
    float p_lobe_diffuse = p_diffuse / (p_diffuse + p_glossy);
    Vec3 sum = vec3_splat(0.0f);
    for (uint s = 0; s < rays; ++s) {
      uint ray = p->pass_index * rays + s;
      float u0, u1;
      first_bounce_point(keys, p->pass_index, rays, s, &u0, &u1);
      int glossy = first_bounce_lobe(p_lobe_diffuse, &u0);
      Vec3 dir;
      Vec3 beta = path_sample_lobe(m, glossy, sp.normal, sp.outgoing, u0, u1, &dir);
      beta = vec3_scale(beta, 1.0f / (glossy ? 1.0f - p_lobe_diffuse : p_lobe_diffuse));
      if (vec3_max_component(beta) <= 0.0f) continue;
      sum = vec3_add(sum, vec3_mul(beta, final_gather_ray(kg, p, origin, dir, pixel, event_base, ray, &accepted, cache)));
    }
    indirect = vec3_add(indirect, vec3_mul(sp.weight, vec3_scale(sum, 1.0f / (float)rays)));
    ++points;
  }
  film_add(kg, p, pixel, indirect, caustic);
  if (cache == PM_FINAL_GATHER_PHOTONS && p->collect_stats) {
    pm_atomic_add_u32(&kg->gather_stats[0], accepted);
    pm_atomic_add_u32(&kg->gather_stats[1], points);
  }
}

PM_DEVICE void kernel_final_gather(const KernelGlobals* kg, const LaunchParams* p, uint item)
{
  final_gather_pixel(kg, p, item, PM_FINAL_GATHER_PHOTONS);
}

PM_DEVICE void kernel_radiosity_final_gather(const KernelGlobals* kg, const LaunchParams* p, uint item)
{
  final_gather_pixel(kg, p, item, PM_FINAL_GATHER_RADIOSITY);
}

#endif

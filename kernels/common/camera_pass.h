/* Stage S5 (paper section 7): one work item per pixel traces the eye ray, follows up to
   mirror_depth perfect-mirror bounces, adds direct light from every point or spot light with a
   shadow ray and from the area lights and the environment by light sampling (area_lights.h,
   environment_light.h), adds the emitted radiance of the emitters it sees and the environment's
   where the eye ray (or its mirror reflection) leaves the scene, and records a shading point per
   depth for the gather (S6) with the triangle it lies on. */
#ifndef PM_CAMERA_PASS_H
#define PM_CAMERA_PASS_H

#include "brdf.h"
#include "kernel_globals.h"
#include "pixel_order.h"
#include "sampled_lights.h"
#include "scene_traverse.h"
#include "spot_light.h"

PM_DEVICE Ray camera_primary_ray(const CameraParams* cam, uint x, uint y, uint width, uint height)
{
  float u = 2.0f * ((float)x + 0.5f) / (float)width - 1.0f;
  float v = 1.0f - 2.0f * ((float)y + 0.5f) / (float)height;
  Vec3 d = vec3_from_float4(cam->forward);
  d = vec3_madd(d, vec3_from_float4(cam->right), u);
  d = vec3_madd(d, vec3_from_float4(cam->up), v);
  return ray_make(vec3_from_float4(cam->position), vec3_normalize(d));
}

/* Radiance reflected towards wo from the direct illumination of every point and spot light:
   L = sum f_r(wi, wo) * Phi / (4 pi r^2) * f * cos(theta_i), shadowed, f the spot falloff
   towards the point (spot_light.h; 1 for a point light). The geometry is that of the
   shading point itself; only the shadow ray starts off the surface, `offset` along n (ray.h). */
PM_DEVICE Vec3 direct_light(const KernelGlobals* kg, const LaunchParams* p, const Material* m, Vec3 pos, Vec3 n,
                            Vec3 wo, float offset)
{
  Vec3 sum = vec3_splat(0.0f);
  Vec3 origin = offset_ray_origin(pos, n, offset);
  for (uint l = 0; l < p->light_count; ++l) {
    PointLight light = kg->lights[l];
    Vec3 light_position = vec3_from_float4(light.position);
    Vec3 to_light = vec3_sub(light_position, pos);
    float dist2 = vec3_dot(to_light, to_light);
    if (!(dist2 > 0.0f)) continue;
    float dist = pm_sqrtf(dist2);
    Vec3 wi = vec3_scale(to_light, 1.0f / dist);
    float cos_i = vec3_dot(n, wi);
    if (cos_i <= 0.0f) continue;
    float falloff = light_falloff(&light, vec3_neg(wi));
    if (falloff <= 0.0f) continue;
    Vec3 f = brdf_eval(m, n, wi, wo);
    if (f.x == 0.0f && f.y == 0.0f && f.z == 0.0f) continue;
    Vec3 shadow_path = vec3_sub(light_position, origin);
    float shadow_length = vec3_length(shadow_path);
    if (!(shadow_length > 0.0f)) continue;
    Ray shadow = ray_make(origin, vec3_scale(shadow_path, 1.0f / shadow_length));
    SceneHit blocker = scene_trace(kg, &shadow, 0.0f, shadow_length * (1.0f - 1e-5f), 1);
    if (blocker.triangle >= 0) continue;
    float irradiance_scale = cos_i * falloff / (4.0f * PM_PI * dist2);
    sum = vec3_add(sum, vec3_scale(vec3_mul(f, vec3_from_float4(light.power)), irradiance_scale));
  }
  return sum;
}

/* A shading point as the methods read it back (gather, path tracer). */
typedef struct ShadingPoint {
  Material material;
  Vec3 position, normal, outgoing; /* normal and outgoing face the viewer */
  Vec3 weight;                     /* product of the eye path's mirror reflectances */
  int triangle;                    /* the scene triangle it lies on (leaf order) */
} ShadingPoint;

/* A pixel's eye path, replayed from its shading points. The frame keeps per shading point only
   the ray's distance to it and its triangle, one float2; the position, the direction towards the
   viewer and the mirrors' product are replayed from the camera ray through the mirrors before
   the point (each mirror's hit at its distance along the ray, the reflected ray leaving it from
   the same offset origin), and the normal and material read from the triangle, as the camera pass
   computed them and by the same operations, so they come out as the same bits: a frame without
   mirrors keeps 8 bytes a pixel for its shading point instead of 64. Each point replays its path from the
   camera (a mirror depth of d reads the d points before it again), so a reader holds nothing
   across its points but the pixel and the depth: carrying the last point's direction and
   mirror from one point to the next instead cost the footprint gather 8 registers (72 -> 80 on
   sm_90) and 4-7 % of its time. Read the points in order: eye_path_begin, then eye_path_next
   until it returns 0. */
typedef struct EyePath {
  uint pixel, depth; /* depth: of the next shading point */
} EyePath;

PM_DEVICE EyePath eye_path_begin(uint pixel)
{
  EyePath e;
  e.pixel = pixel;
  e.depth = 0u;
  return e;
}

/* The normal the camera pass shades a point of `triangle` with: the triangle's, on the side the
   ray travelling along `direction` arrives from. */
PM_DEVICE Vec3 shading_normal_facing(const KernelGlobals* kg, int triangle, Vec3 direction)
{
  Vec3 n = scene_triangle_normal(kg->triangles, triangle);
  return vec3_dot(n, direction) > 0.0f ? vec3_neg(n) : n;
}

/* The material of a shading point, textured (texture.h). */
PM_DEVICE Material shading_point_material(const KernelGlobals* kg, int triangle, Vec3 position)
{
  return surface_material(kg, scene_triangle_material(kg->triangles, triangle), triangle, position);
}

/* The eye path's next shading point in *sp; 0 when the path ended before it (every deeper record
   is empty too). */
PM_DEVICE int eye_path_next(const KernelGlobals* kg, const LaunchParams* p, EyePath* e, ShadingPoint* sp)
{
  if (e->depth > p->mirror_depth) return 0;
  uint pixels = p->width * p->height;
  float2 hit = kg->shade_hit[e->depth * pixels + e->pixel];
  int triangle = PM_AS_INT(hit.y);
  if (triangle < 0) return 0;
  Ray camera = camera_primary_ray(&p->camera, e->pixel % p->width, e->pixel / p->width, p->width, p->height);
  Vec3 origin = camera.origin, direction = camera.direction;
  Vec3 weight = vec3_splat(1.0f);
  for (uint depth = 0u; depth < e->depth; ++depth) { /* the mirrors before it (kernel_camera_pass) */
    float2 mirror_hit = kg->shade_hit[depth * pixels + e->pixel];
    int mirror_triangle = PM_AS_INT(mirror_hit.y);
    Vec3 mirror_position = vec3_madd(origin, direction, mirror_hit.x);
    Material mirror = shading_point_material(kg, mirror_triangle, mirror_position);
    weight = vec3_mul(weight, material_mirror(&mirror));
    Vec3 n = shading_normal_facing(kg, mirror_triangle, direction);
    float offset = ray_offset_distance(origin, mirror_hit.x, p->ray_epsilon);
    origin = offset_ray_origin(mirror_position, n, offset);
    direction = vec3_reflect(direction, n);
  }
  sp->position = vec3_madd(origin, direction, hit.x);
  sp->triangle = triangle;
  sp->material = shading_point_material(kg, triangle, sp->position);
  sp->normal = shading_normal_facing(kg, triangle, direction);
  sp->outgoing = vec3_neg(direction);
  sp->weight = weight;
  ++e->depth;
  return 1;
}

PM_DEVICE void shading_point_clear(const KernelGlobals* kg, uint record)
{
  kg->shade_hit[record] = PM_MAKE_FLOAT2(0.0f, PM_AS_FLOAT(-1));
}

/* Work item = pixel in tile order (pixel_order.h). */
PM_DEVICE void kernel_camera_pass(const KernelGlobals* kg, const LaunchParams* p, uint item)
{
  uint pixel;
  if (!pixel_of_work_item(item, p->width, p->height, &pixel)) return;
  uint pixels = p->width * p->height;
  Ray ray = camera_primary_ray(&p->camera, pixel % p->width, pixel / p->width, p->width, p->height);
  Vec3 throughput = vec3_splat(1.0f);
  Vec3 radiance = vec3_splat(0.0f);
  uint depth = 0;
  for (; depth <= p->mirror_depth; ++depth) {
    uint record = depth * pixels + pixel;
    SceneHit hit = scene_trace(kg, &ray, 0.0f, 1e30f, 0);
    if (hit.triangle < 0) {
      /* The environment seen directly (or in a mirror) is direct light too. */
      radiance = vec3_add(radiance, vec3_mul(throughput, environment_radiance(kg, p, ray.direction)));
      break;
    }
    Vec3 pos = vec3_madd(ray.origin, ray.direction, hit.t);
    Vec3 n = scene_triangle_normal(kg->triangles, hit.triangle);
    int material_index = scene_triangle_material(kg->triangles, hit.triangle);
    /* An emitter seen directly (or in a mirror) is direct light. */
    radiance = vec3_add(radiance, vec3_mul(throughput, surface_emission(kg, p, material_index, n, ray.direction)));
    if (vec3_dot(n, ray.direction) > 0.0f) n = vec3_neg(n); /* shade the side the ray came from */
    Vec3 wo = vec3_neg(ray.direction);
    Material m = surface_material(kg, material_index, hit.triangle, pos); /* texture.h */

    float offset = ray_offset_distance(ray.origin, hit.t, p->ray_epsilon);
    Vec3 direct = direct_light(kg, p, &m, pos, n, wo, offset);
    for (uint kind = 0; kind < PM_SAMPLED_LIGHT_KINDS; ++kind)
      direct = vec3_add(direct, sampled_light_direct(kg, p, kind, &m, pos, n, wo, offset, p->area_light_samples, pixel,
                                                     depth * p->area_light_samples, 0u));
    radiance = vec3_add(radiance, vec3_mul(throughput, direct));
    /* pos, wo, throughput, the normal and the material are not kept: the readers replay them
       (eye_path_next); the triangle also tells radiosity what to interpolate on. */
    kg->shade_hit[record] = PM_MAKE_FLOAT2(hit.t, PM_AS_FLOAT(hit.triangle));

    if (!material_has_mirror(&m) || depth == p->mirror_depth) { ++depth; break; }
    throughput = vec3_mul(throughput, material_mirror(&m));
    ray = ray_make(offset_ray_origin(pos, n, offset), vec3_reflect(ray.direction, n));
  }
  for (; depth <= p->mirror_depth; ++depth) shading_point_clear(kg, depth * pixels + pixel);
  kg->film_direct[pixel] = vec3_to_float4(radiance, 0.0f); /* w: the frame's odd-pass sum starts at 0 (film.h) */
}

#endif

/* Vertex link radiosity, light links (section 3.3): explicit visibility from every point light to
   every element, and the geometry term of eq. 2. For a point light of power Phi the light's side
   of eq. 2 (cos theta_y dA_y) is its intensity Phi / (4 pi), so a surface point receives
   E = Phi / (4 pi r^2) * cos theta_x * V, the same direct light the camera pass computes per
   pixel. The element's outgoing radiance is initialised with rho_d / pi * E (the light it
   received times its BRDF), and the gathered irradiance I_total is reset.

   PM_RADIOSITY_LIGHT_VERTEX evaluates that at the vertex. It aliases (a shadow edge between two
   vertices is missed) and, near a light, over-weights the vertex: a ceiling vertex 1 cm above
   a lamp gets 1 / (4 pi 1e-4) of its power per m^2, and interpolation spreads that over its
   whole one-ring, many times the power that really arrives there.
   PM_RADIOSITY_LIGHT_ONE_RING (default) is the paper's oversampling of the visibility term over
   the one-ring, with the geometry term integrated over it: eq. 2 integrated over a triangle is
   Phi / (4 pi) times the solid angle the triangle subtends at the light (cos theta_x dA / r^2 =
   d omega), exact for any distance. Each one-ring triangle gives its vertex a third of the power
   it receives, times its visibility; the element's irradiance is that power over a third of
   the one-ring's area, so the linearly interpolated irradiance carries exactly the power that
   reaches the surface (unshadowed). Visibility is sampled on the paper's 1:4 subdivision of
   each one-ring triangle, at the centroids of its four sub-triangles, weighted by the vertex's
   hat function integrated over each: A/6, A/24, A/24 and A/12 for the sub-triangles at the
   vertex, at the other two corners and in the middle (4 : 1 : 1 : 2). The centroids lie inside
   the triangle: the 1:4 points themselves (the vertex, the edge midpoints) lie on edges of the
   mesh, and where that edge is the foot of a wall a shadow ray from it starts in the wall's
   plane, and the wall may block it at t = 0. Far from the light both
   modes agree to O(h^2).

   A spot light's falloff (spot_light.h) multiplies each visibility sample, so the one-ring
   mode integrates intensity times solid angle with the same quadrature as the visibility.

   Area lights (area_lights.h) are light links too: each element's direct irradiance from the
   emitters is estimated by light sampling, area_light_samples samples at the vertex, or spread
   over the four quadrature points of each one-ring triangle with their weights, with random
   numbers keyed by the seed and the element, so the solution stays deterministic. Emitting
   elements get no exitance of their own: the light they emit reaches the other elements through
   these links only (as a point light's does), and the camera pass shows the emitter itself.

   The environment (environment_light.h) is gathered the same way: its light samples, with a
   shadow ray each, join the area lights' at the same quadrature points (its own random stream),
   so an element's light link carries the environment's direct irradiance integral
   E = int L(w) cos theta V(w) dw. Link rays that leave the scene make no link, so the light the
   environment sends reaches the elements through these light links alone, and from there
   bounces through the element links like any other direct light. */
#ifndef PM_RADIOSITY_LIGHT_H
#define PM_RADIOSITY_LIGHT_H

#include "area_lights.h"
#include "environment_light.h"
#include "radiosity_mesh.h"
#include "spot_light.h"

/* 1 when the light is in front of the surface at x (normal n) and no triangle blocks it. */
PM_DEVICE float radiosity_light_visible(const KernelGlobals* kg, const LaunchParams* p, Vec3 light_pos, Vec3 x, Vec3 n)
{
  Vec3 origin = offset_ray_origin(x, n, ray_offset_distance(x, 0.0f, p->ray_epsilon));
  Vec3 to_light = vec3_sub(light_pos, origin);
  float dist2 = vec3_dot(to_light, to_light);
  if (!(dist2 > 0.0f) || vec3_dot(n, to_light) <= 0.0f) return 0.0f;
  float dist = pm_sqrtf(dist2);
  Ray shadow = ray_make(origin, vec3_scale(to_light, 1.0f / dist));
  SceneHit blocker = scene_trace(kg, &shadow, 0.0f, dist * (1.0f - 1e-5f), 1);
  return blocker.triangle >= 0 ? 0.0f : 1.0f;
}

/* Eq. 2 at a point for a light of unit power: cos theta_x / (4 pi r^2), unshadowed. */
PM_DEVICE float radiosity_light_geometry(Vec3 light_pos, Vec3 x, Vec3 n)
{
  Vec3 to_light = vec3_sub(light_pos, x);
  float dist2 = vec3_dot(to_light, to_light);
  if (!(dist2 > 0.0f)) return 0.0f;
  float cos_x = vec3_dot(n, to_light) / pm_sqrtf(dist2);
  return cos_x > 0.0f ? cos_x / (4.0f * PM_PI * dist2) : 0.0f;
}

/* Solid angle of triangle (a, b, c) seen from o (Van Oosterom & Strackee 1983):
   tan(omega / 2) = |a . (b x c)| / (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|), corners relative to o. */
PM_DEVICE float radiosity_solid_angle(Vec3 o, Vec3 a, Vec3 b, Vec3 c)
{
  a = vec3_sub(a, o);
  b = vec3_sub(b, o);
  c = vec3_sub(c, o);
  float la = vec3_length(a), lb = vec3_length(b), lc = vec3_length(c);
  float num = pm_fabsf(vec3_dot(a, vec3_cross(b, c)));
  float den = la * lb * lc + vec3_dot(a, b) * lc + vec3_dot(a, c) * lb + vec3_dot(b, c) * la;
  return 2.0f * pm_atan2f(num, den);
}

/* (wa a + wb b + wc c) / 6: a point of triangle (a, b, c) for weights summing to 6. */
PM_DEVICE Vec3 radiosity_affine(Vec3 a, Vec3 b, Vec3 c, float wa, float wb, float wc)
{
  return vec3_scale(vec3_add(vec3_add(vec3_scale(a, wa), vec3_scale(b, wb)), vec3_scale(c, wc)), 1.0f / 6.0f);
}

/* Visibility times the spot falloff towards x (1 for a point light). */
PM_DEVICE float radiosity_light_reaches(const KernelGlobals* kg, const LaunchParams* p, const PointLight* light, Vec3 x,
                                        Vec3 n)
{
  Vec3 light_pos = vec3_from_float4(light->position);
  float falloff = light_falloff(light, vec3_normalize(vec3_sub(x, light_pos)));
  return falloff > 0.0f ? falloff * radiosity_light_visible(kg, p, light_pos, x, n) : 0.0f;
}

/* Element e's irradiance from a light of unit power (see above for the modes). */
PM_DEVICE float radiosity_element_light(const KernelGlobals* kg, const LaunchParams* p, uint e, const PointLight* light)
{
  Vec3 light_pos = vec3_from_float4(light->position);
  Vec3 v = radiosity_element_position(kg, e), n = radiosity_element_normal(kg, e);
  if (p->light_sampling == PM_RADIOSITY_LIGHT_VERTEX) {
    float g = radiosity_light_geometry(light_pos, v, n);
    return g > 0.0f ? g * radiosity_light_reaches(kg, p, light, v, n) : 0.0f;
  }
  uint first = PM_LOAD(&kg->rad_element_ranges[e]).x, end = PM_LOAD(&kg->rad_element_ranges[e + 1u]).x;
  float power = 0.0f, area = 0.0f;
  for (uint r = first; r < end; ++r) {
    Vec3 b, c, face_n;
    float twice_area = radiosity_ring_triangle(kg, e, PM_LOAD(&kg->rad_adjacency[r]), &b, &c, &face_n);
    if (!(twice_area > 0.0f)) continue;
    area += twice_area * (0.5f / 3.0f);
    if (vec3_dot(face_n, vec3_sub(light_pos, v)) <= 0.0f) continue; /* lit from the other side */
    /* Centroids of the 1:4 sub-triangles at v, b, c and in the middle, weighted 4 : 1 : 1 : 2. */
    float visible = 4.0f * radiosity_light_reaches(kg, p, light, radiosity_affine(v, b, c, 4.0f, 1.0f, 1.0f), face_n);
    visible += radiosity_light_reaches(kg, p, light, radiosity_affine(v, b, c, 1.0f, 4.0f, 1.0f), face_n);
    visible += radiosity_light_reaches(kg, p, light, radiosity_affine(v, b, c, 1.0f, 1.0f, 4.0f), face_n);
    visible += 2.0f * radiosity_light_reaches(kg, p, light, radiosity_affine(v, b, c, 2.0f, 2.0f, 2.0f), face_n);
    power += (1.0f / 3.0f) * (0.125f * visible) * radiosity_solid_angle(light_pos, v, b, c) * (1.0f / (4.0f * PM_PI));
  }
  return area > 0.0f ? power / area : 0.0f;
}

/* Mean of `samples` light samples' irradiance at x (normal n) from the area lights and from the
   environment (one of each per sample, when the scene has them), random numbers keyed by the
   seed and (element, first_event + k). */
PM_DEVICE Vec3 radiosity_sampled_irradiance_at(const KernelGlobals* kg, const LaunchParams* p, uint e, Vec3 x, Vec3 n,
                                            uint samples, uint first_event)
{
  Vec3 sum = vec3_splat(0.0f);
  float offset = ray_offset_distance(x, 0.0f, p->ray_epsilon);
  for (uint k = 0; k < samples; ++k) {
    if (p->emitter_count > 0u) {
      Uniform4 u = rng_uniform4_bits(rng_bits4(p->seed, 0u, e, first_event + k, PM_STREAM_AREA, 0x52414449u));
      sum = vec3_add(sum, area_light_sample(kg, p, x, n, offset, u).irradiance);
    }
    if (p->environment != PM_ENVIRONMENT_NONE) {
      Uniform4 u = rng_uniform4_bits(rng_bits4(p->seed, 0u, e, first_event + k, PM_STREAM_ENVIRONMENT, 0x52414449u));
      sum = vec3_add(sum, environment_light_sample(kg, p, x, n, offset, u).irradiance);
    }
  }
  return vec3_scale(sum, 1.0f / (float)samples);
}

/* Element e's direct irradiance from the area lights and the environment (see above). In one-ring mode each of the
   ring's quadrature points takes a quarter of the samples (at least one), weighted 4 : 1 : 1 : 2
   over each triangle and by a third of the triangle's area over the ring, as the hat function's
   integral asks. */
PM_DEVICE Vec3 radiosity_element_sampled_light(const KernelGlobals* kg, const LaunchParams* p, uint e)
{
  Vec3 v = radiosity_element_position(kg, e), n = radiosity_element_normal(kg, e);
  uint samples = p->area_light_samples > 0u ? p->area_light_samples : 1u;
  if (p->light_sampling == PM_RADIOSITY_LIGHT_VERTEX) return radiosity_sampled_irradiance_at(kg, p, e, v, n, samples, 0u);
  uint per_point = samples / 4u > 0u ? samples / 4u : 1u;
  uint first = PM_LOAD(&kg->rad_element_ranges[e]).x, end = PM_LOAD(&kg->rad_element_ranges[e + 1u]).x;
  Vec3 sum = vec3_splat(0.0f);
  float area = 0.0f;
  uint event = 0u;
  for (uint r = first; r < end; ++r) {
    Vec3 b, c, face_n;
    float twice_area = radiosity_ring_triangle(kg, e, PM_LOAD(&kg->rad_adjacency[r]), &b, &c, &face_n);
    if (!(twice_area > 0.0f)) continue;
    float third = twice_area * (0.5f / 3.0f);
    area += third;
    Vec3 e_tri = vec3_scale(radiosity_sampled_irradiance_at(kg, p, e, radiosity_affine(v, b, c, 4.0f, 1.0f, 1.0f), face_n, per_point, event), 4.0f);
    e_tri = vec3_add(e_tri, radiosity_sampled_irradiance_at(kg, p, e, radiosity_affine(v, b, c, 1.0f, 4.0f, 1.0f), face_n, per_point, event + per_point));
    e_tri = vec3_add(e_tri, radiosity_sampled_irradiance_at(kg, p, e, radiosity_affine(v, b, c, 1.0f, 1.0f, 4.0f), face_n, per_point, event + 2u * per_point));
    e_tri = vec3_madd(e_tri, radiosity_sampled_irradiance_at(kg, p, e, radiosity_affine(v, b, c, 2.0f, 2.0f, 2.0f), face_n, per_point, event + 3u * per_point), 2.0f);
    event += 4u * per_point;
    sum = vec3_madd(sum, e_tri, third * 0.125f);
  }
  return area > 0.0f ? vec3_scale(sum, 1.0f / area) : vec3_splat(0.0f);
}

/* One work item per element: direct irradiance from every light, outgoing radiance of bounce 0
   into half 0 of rad_radiance, I_total (half 0 of rad_irradiance) reset. */
PM_DEVICE void kernel_radiosity_light_links(const KernelGlobals* kg, const LaunchParams* p, uint e)
{
  Vec3 irradiance = vec3_splat(0.0f);
  for (uint l = 0; l < p->light_count; ++l) {
    PointLight light = kg->lights[l];
    float g = radiosity_element_light(kg, p, e, &light);
    irradiance = vec3_madd(irradiance, vec3_from_float4(light.power), g);
  }
  if (p->emitter_count > 0u || p->environment != PM_ENVIRONMENT_NONE)
    irradiance = vec3_add(irradiance, radiosity_element_sampled_light(kg, p, e));
  /* The part of the one-ring inside other geometry is shadowed: the light is what the seen part
     received, over the seen part (the link build counted the hidden origins, radiosity_links.h). */
  uint hidden = PM_LOAD(&kg->rad_element_ranges[e]).w;
  if (hidden > 0u && hidden < p->link_directions)
    irradiance = vec3_scale(irradiance, (float)p->link_directions / (float)(p->link_directions - hidden));
  Vec3 radiance = vec3_scale(vec3_mul(radiosity_element_reflectance(kg, e), irradiance), PM_INV_PI);
  kg->rad_radiance[e] = vec3_to_float4(radiance, 0.0f);
  kg->rad_irradiance[e] = PM_MAKE_FLOAT4(0.0f, 0.0f, 0.0f, 0.0f);
}

#endif

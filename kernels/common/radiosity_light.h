/* Vertex link radiosity, light links (section 3.3): explicit visibility from every point light to
   every element, and the geometry term of eq. 2. For a point light of power Phi the light's side
   of eq. 2 (cos theta_y dA_y) is its intensity Phi / (4 pi), so the irradiance at the vertex is
   E = Phi / (4 pi r^2) * cos theta_x * V, the same direct light the camera pass computes per
   pixel. The element's outgoing radiance is initialised with rho_d / pi * E (the light it
   received times its BRDF), and the gathered irradiance I_total is reset.

   Sampling V only at the vertex aliases (a shadow edge between two vertices is missed). With
   PM_RADIOSITY_LIGHT_ONE_RING the paper's oversampling of the visibility term is used: rays also
   go from the light to the points the 1:4 subdivision adds around the vertex, the midpoints of
   its one-ring edges, and V becomes their weighted mean. The weights are a quadrature of the
   vertex's hat function phi over its one-ring: on a triangle of area A, splitting it 1:4 and
   using each sub-triangle's corner average gives A/12 * (1, 3/2, 3/2) for the vertex and the
   two edge midpoints, summing to A/3 = the integral of phi. The geometry term stays the
   vertex's, so unshadowed elements get exactly the vertex's irradiance in both modes. */
#ifndef PM_RADIOSITY_LIGHT_H
#define PM_RADIOSITY_LIGHT_H

#include "radiosity_mesh.h"

/* 1 when the light is in front of the surface at x (normal n) and no triangle blocks it. */
PM_DEVICE float radiosity_light_visible(const KernelGlobals* kg, Vec3 light_pos, Vec3 x, Vec3 n)
{
  Vec3 origin = offset_ray_origin(x, n);
  Vec3 to_light = vec3_sub(light_pos, origin);
  float dist2 = vec3_dot(to_light, to_light);
  if (!(dist2 > 0.0f) || vec3_dot(n, to_light) <= 0.0f) return 0.0f;
  float dist = pm_sqrtf(dist2);
  Ray shadow = ray_make(origin, vec3_scale(to_light, 1.0f / dist));
  SceneHit blocker = scene_trace(kg->scene_nodes, kg->triangles, &shadow, 0.0f, dist * (1.0f - 1e-5f), 1);
  return blocker.triangle >= 0 ? 0.0f : 1.0f;
}

/* The geometry term of eq. 2 at the vertex for a light of unit power: cos theta_x / (4 pi r^2). */
PM_DEVICE float radiosity_light_geometry(Vec3 light_pos, Vec3 x, Vec3 n)
{
  Vec3 to_light = vec3_sub(light_pos, x);
  float dist2 = vec3_dot(to_light, to_light);
  if (!(dist2 > 0.0f)) return 0.0f;
  float cos_x = vec3_dot(n, to_light) / pm_sqrtf(dist2);
  return cos_x > 0.0f ? cos_x / (4.0f * PM_PI * dist2) : 0.0f;
}

/* The visibility term for element e: at the vertex, or its hat-weighted mean over the one-ring. */
PM_DEVICE float radiosity_element_visibility(const KernelGlobals* kg, const LaunchParams* p, uint e, Vec3 light_pos)
{
  Vec3 v = radiosity_element_position(kg, e), n = radiosity_element_normal(kg, e);
  float at_vertex = radiosity_light_visible(kg, light_pos, v, n);
  if (p->light_sampling == PM_RADIOSITY_LIGHT_VERTEX) return at_vertex;
  uint first = PM_LOAD(&kg->rad_element_ranges[e]).x, end = PM_LOAD(&kg->rad_element_ranges[e + 1u]).x;
  float sum = 0.0f, weight_sum = 0.0f;
  for (uint r = first; r < end; ++r) {
    uint ring = PM_LOAD(&kg->rad_adjacency[r]);
    uint tri = ring >> 2, corner = ring & 3u;
    uint4 front = PM_LOAD(&kg->rad_triangles[2u * tri]);
    uint4 back = PM_LOAD(&kg->rad_triangles[2u * tri + 1u]);
    /* The other two corners' positions (either side's element has the vertex's position). */
    uint ids[3];
    ids[0] = front.x != PM_RADIOSITY_NONE ? front.x : back.x;
    ids[1] = front.y != PM_RADIOSITY_NONE ? front.y : back.y;
    ids[2] = front.z != PM_RADIOSITY_NONE ? front.z : back.z;
    Vec3 b = radiosity_element_position(kg, ids[(corner + 1u) % 3u]);
    Vec3 c = radiosity_element_position(kg, ids[(corner + 2u) % 3u]);
    Vec3 cross = vec3_cross(vec3_sub(b, v), vec3_sub(c, v));
    float twice_area = vec3_length(cross);
    if (!(twice_area > 0.0f)) continue;
    Vec3 face_n = vec3_scale(cross, 1.0f / twice_area);
    if (vec3_dot(face_n, n) < 0.0f) face_n = vec3_neg(face_n); /* the element's side */
    float visible = at_vertex;
    visible += 1.5f * radiosity_light_visible(kg, light_pos, vec3_scale(vec3_add(v, b), 0.5f), face_n);
    visible += 1.5f * radiosity_light_visible(kg, light_pos, vec3_scale(vec3_add(v, c), 0.5f), face_n);
    float area = 0.5f * twice_area;
    sum += area * (1.0f / 12.0f) * visible;
    weight_sum += area * (1.0f / 3.0f);
  }
  return weight_sum > 0.0f ? sum / weight_sum : at_vertex;
}

/* One work item per element: direct irradiance from every light, outgoing radiance of bounce 0
   into half 0 of rad_radiance, I_total (half 0 of rad_irradiance) reset. */
PM_DEVICE void kernel_radiosity_light_links(const KernelGlobals* kg, const LaunchParams* p, uint e)
{
  Vec3 irradiance = vec3_splat(0.0f);
  for (uint l = 0; l < p->light_count; ++l) {
    PointLight light = kg->lights[l];
    Vec3 light_pos = vec3_from_float4(light.position);
    float g = radiosity_light_geometry(light_pos, radiosity_element_position(kg, e), radiosity_element_normal(kg, e));
    if (g > 0.0f) g *= radiosity_element_visibility(kg, p, e, light_pos); /* eq. 2 times V */
    irradiance = vec3_madd(irradiance, vec3_from_float4(light.power), g);
  }
  Vec3 radiance = vec3_scale(vec3_mul(radiosity_element_reflectance(kg, e), irradiance), PM_INV_PI);
  kg->rad_radiance[e] = vec3_to_float4(radiance, 0.0f);
  kg->rad_irradiance[e] = PM_MAKE_FLOAT4(0.0f, 0.0f, 0.0f, 0.0f);
}

#endif

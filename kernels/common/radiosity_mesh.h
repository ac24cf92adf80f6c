/* Vertex link radiosity (the 2008 explicit-visibility link radiosity paper, section 3;
   docs/radiosity.md): the refined mesh as the device sees it. Elements are the refined mesh's
   vertices, one per side, feature-edge group and material; each refined triangle knows its
   corner elements on both sides. The scene BVH still holds the original triangles: a point on
   an original triangle is mapped to its refined triangle by the refinement tree, so link rays
   and shading points need no second BVH. Also the hemisphere directions of the link rays. */
#ifndef PM_RADIOSITY_MESH_H
#define PM_RADIOSITY_MESH_H

#include "brdf.h"
#include "kernel_globals.h"
#include "rng.h"
#include "scene_traverse.h"

#define PM_STREAM_RADIOSITY 0x52414449u /* "RADI": the azimuth of each element's directions */

PM_DEVICE Vec3 radiosity_element_position(const KernelGlobals* kg, uint e)
{
  return vec3_from_float4(PM_LOAD(&kg->rad_elements[2u * e]));
}

PM_DEVICE int radiosity_element_material(const KernelGlobals* kg, uint e)
{
  return PM_AS_INT(PM_LOAD(&kg->rad_elements[2u * e]).w);
}

/* Unit normal on the element's side (its w: radiosity_element_reflectance's glossy albedo). */
PM_DEVICE Vec3 radiosity_element_normal(const KernelGlobals* kg, uint e)
{
  return vec3_from_float4(PM_LOAD(&kg->rad_elements[2u * e + 1u]));
}

/* Reflectance of the element's material as the method's diffuse f_d = rho / pi (eq. 4): rho_d
   plus the glossy lobe's rho_s times its albedo for light arriving uniformly from the hemisphere
   (the cosine-weighted mean of brdf_glossy_albedo over theta_o, computed per material on the host
   and kept in the normal's w). The method carries no directions, so the glossy lobe's light
   leaves diffusely; dropping it would lose all the light the scene's glossy surfaces reflect.
   A textured material's element takes its texture's mean over the element's one-ring, weighted
   by the element's hat function (rad_texture_tint, render/radiosity/radiosity_texture_tint.h):
   the element stands for that whole area, so it reflects what the area reflects on average. */
PM_DEVICE Vec3 radiosity_element_reflectance(const KernelGlobals* kg, uint e)
{
  Material m = material_load(kg->materials, radiosity_element_material(kg, e));
  if (material_base_texture(&m) != 0u) material_apply_tint(&m, vec3_from_float4(PM_LOAD(&kg->rad_texture_tint[e])));
  float glossy_albedo = PM_LOAD(&kg->rad_elements[2u * e + 1u]).w;
  return vec3_madd(material_diffuse(&m), material_glossy(&m), glossy_albedo);
}

/* Barycentric weights of the point (u, v) of the original triangle's parameter plane in the
   tree node's triangle, whose corners are given in that plane. */
PM_DEVICE void radiosity_node_weights(float4 corners01, float4 corners2, float u, float v, float* w)
{
  float ax = corners01.x, ay = corners01.y, bx = corners01.z, by = corners01.w, cx = corners2.x, cy = corners2.y;
  float det = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
  float px = u - ax, py = v - ay;
  w[1] = (px * (cy - ay) - py * (cx - ax)) / det;
  w[2] = ((bx - ax) * py - (by - ay) * px) / det;
  w[0] = 1.0f - w[1] - w[2];
}

typedef struct RadiosityLocation {
  uint triangle; /* refined triangle */
  float w[3];    /* barycentric weights of its corners, each >= 0, summing to 1 */
} RadiosityLocation;

/* The refined triangle of original triangle `root` that holds parameter point (u, v), and the
   point's weights there. Tree node n is rad_tree[2n], rad_tree[2n + 1]:
     (u0, v0, u1, v1), (u2, v2, first child or refined triangle as uint bits, child count)
   corners in the original triangle's (u, v) plane; nodes 0 .. T-1 are the original triangles.
   Children tile their parent; a point on a shared edge goes to the child it is deepest in. */
PM_DEVICE RadiosityLocation radiosity_locate(PM_GLOBAL const float4* tree, uint root, float u, float v)
{
  RadiosityLocation loc;
  uint node = root;
  for (int level = 0; level < PM_RADIOSITY_MAX_TREE_DEPTH; ++level) {
    float4 b = PM_LOAD(&tree[2u * node + 1u]);
    uint first = PM_AS_UINT(b.z), count = PM_AS_UINT(b.w);
    if (count == 0u) break;
    uint best = first;
    float best_score = -1e30f;
    for (uint c = 0; c < count; ++c) {
      float w[3];
      radiosity_node_weights(PM_LOAD(&tree[2u * (first + c)]), PM_LOAD(&tree[2u * (first + c) + 1u]), u, v, w);
      float score = pm_fminf(w[0], pm_fminf(w[1], w[2]));
      if (score > best_score) { best_score = score; best = first + c; }
    }
    node = best;
  }
  float4 a = PM_LOAD(&tree[2u * node]), b = PM_LOAD(&tree[2u * node + 1u]);
  radiosity_node_weights(a, b, u, v, loc.w);
  /* Rounding can leave a point a hair outside its triangle: clamp and renormalise. */
  float sum = 0.0f;
  for (int k = 0; k < 3; ++k) { loc.w[k] = pm_fmaxf(loc.w[k], 0.0f); sum += loc.w[k]; }
  for (int k = 0; k < 3; ++k) loc.w[k] = sum > 0.0f ? loc.w[k] / sum : 1.0f / 3.0f;
  loc.triangle = PM_AS_UINT(b.z);
  return loc;
}

/* The elements at the corners of the refined triangle on the side the normal n faces, for the
   point p on scene triangle `leaf` (BVH leaf order), with their barycentric weights. Corners
   without an element (one-sided surfaces seen from behind) are PM_RADIOSITY_NONE. */
PM_DEVICE RadiosityLocation radiosity_surface_point(const KernelGlobals* kg, int leaf, Vec3 p, Vec3 n, uint* elements)
{
  Vec3 a = scene_triangle_vertex(kg->triangles, leaf, 0);
  Vec3 b = scene_triangle_vertex(kg->triangles, leaf, 1);
  Vec3 c = scene_triangle_vertex(kg->triangles, leaf, 2);
  uint original = PM_AS_UINT(PM_LOAD(&kg->triangles[3 * leaf + 1]).w);
  float u, v;
  triangle_barycentrics(p, a, b, c, &u, &v); /* triangles.h */
  RadiosityLocation loc = radiosity_locate(kg->rad_tree, original, u, v);
  /* The winding normal tells which side: refined triangles keep the original winding. */
  int front = vec3_dot(vec3_cross(vec3_sub(b, a), vec3_sub(c, a)), n) >= 0.0f;
  uint4 corners = PM_LOAD(&kg->rad_triangles[2u * loc.triangle + (front ? 0u : 1u)]);
  elements[0] = corners.x;
  elements[1] = corners.y;
  elements[2] = corners.z;
  return loc;
}

/* Triangle `ring_entry` of element e's one-ring (an rad_adjacency entry: refined triangle << 2 |
   the element's corner): the other two corners b and c, in the triangle's winding after the
   element's vertex, and the face normal turned to the element's side. Returns twice the
   triangle's area; 0 for a degenerate triangle (b, c and the normal then undefined). */
PM_DEVICE float radiosity_ring_triangle(const KernelGlobals* kg, uint e, uint ring_entry, Vec3* b, Vec3* c, Vec3* face_n)
{
  uint tri = ring_entry >> 2, corner = ring_entry & 3u;
  uint4 front = PM_LOAD(&kg->rad_triangles[2u * tri]);
  uint4 back = PM_LOAD(&kg->rad_triangles[2u * tri + 1u]);
  /* The other two corners' positions (either side's element has the vertex's position). */
  uint ids[3];
  ids[0] = front.x != PM_RADIOSITY_NONE ? front.x : back.x;
  ids[1] = front.y != PM_RADIOSITY_NONE ? front.y : back.y;
  ids[2] = front.z != PM_RADIOSITY_NONE ? front.z : back.z;
  Vec3 v = radiosity_element_position(kg, e);
  *b = radiosity_element_position(kg, ids[(corner + 1u) % 3u]);
  *c = radiosity_element_position(kg, ids[(corner + 2u) % 3u]);
  Vec3 cross = vec3_cross(vec3_sub(*b, v), vec3_sub(*c, v));
  float twice_area = vec3_length(cross);
  if (!(twice_area > 0.0f)) return 0.0f;
  *face_n = vec3_scale(cross, 1.0f / twice_area);
  if (vec3_dot(*face_n, radiosity_element_normal(kg, e)) < 0.0f) *face_n = vec3_neg(*face_n);
  return twice_area;
}

/* Direction k of nC in the element's frame: cosine-weighted over the hemisphere by mapping an
   area-uniform point of the unit disk straight up (Malley's method), the disk points on
   Vogel's golden-angle spiral so that any nC covers the disk evenly (the paper maps a 16 x 16
   grid with Shirley's concentric map; both are stratified). `rotation` turns the spiral
   about the normal (radians). z is the normal axis. */
PM_DEVICE Vec3 radiosity_direction(uint k, uint count, float rotation)
{
  float r2 = ((float)k + 0.5f) / (float)count;
  float r = pm_sqrtf(r2);
  float s, c;
  pm_sincosf(2.39996322972865332f * (float)k + rotation, &s, &c);
  return vec3(r * c, r * s, pm_sqrtf(pm_fmaxf(0.0f, 1.0f - r2)));
}

/* Each element turns its spiral by its own angle, so that neighbouring elements do not sample
   the same directions (no banding); a pure function of the element, the same on every device. */
PM_DEVICE float radiosity_rotation(uint element)
{
  return PM_TWO_PI * rng_uniform4(0u, 0u, element, 0u, PM_STREAM_RADIOSITY).u0;
}

/* Direction k of element e's link rays in world space. */
PM_DEVICE Vec3 radiosity_world_direction(Vec3 n, uint e, uint k, uint count)
{
  Vec3 t, b;
  vec3_onb(n, &t, &b);
  Vec3 d = radiosity_direction(k, count, radiosity_rotation(e));
  return vec3_normalize(vec3_add(vec3_add(vec3_scale(t, d.x), vec3_scale(b, d.y)), vec3_scale(n, d.z)));
}

#endif

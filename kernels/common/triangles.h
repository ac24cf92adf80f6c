/* The scene's triangle records as the device reads them (render/scene_bvh.h writes them: 3 float4
   per triangle in BVH leaf order, v0.w the material index with PM_TRIANGLE_MASKED, v1.w the
   original index, v2.w the object) and the barycentric coordinates of a point on one, which
   texture lookups, the radiosity mesh and the alpha-mask test share. */
#ifndef PM_TRIANGLES_H
#define PM_TRIANGLES_H

#include "types.h"
#include "vec3.h"

PM_DEVICE Vec3 scene_triangle_vertex(PM_GLOBAL const float4* triangles, int tri, int corner)
{
  float4 v = PM_LOAD(&triangles[3 * tri + corner]);
  return vec3(v.x, v.y, v.z);
}

/* The material index of a triangle, without the mask flag. */
PM_DEVICE int scene_triangle_material(PM_GLOBAL const float4* triangles, int tri)
{
  return (int)(PM_AS_UINT(PM_LOAD(&triangles[3 * tri]).w) & PM_TRIANGLE_MATERIAL_BITS);
}

/* Geometric normal (unnormalised orientation follows the stored winding). */
PM_DEVICE Vec3 scene_triangle_normal(PM_GLOBAL const float4* triangles, int tri)
{
  Vec3 v0 = scene_triangle_vertex(triangles, tri, 0);
  Vec3 e1 = vec3_sub(scene_triangle_vertex(triangles, tri, 1), v0);
  Vec3 e2 = vec3_sub(scene_triangle_vertex(triangles, tri, 2), v0);
  return vec3_normalize(vec3_cross(e1, e2));
}

/* Barycentric coordinates (u, v) of p in triangle (a, b, c): p = (1 - u - v) a + u b + v c,
   for p in the triangle's plane; (1/3, 1/3) for a degenerate triangle. */
PM_DEVICE void triangle_barycentrics(Vec3 p, Vec3 a, Vec3 b, Vec3 c, float* u, float* v)
{
  Vec3 e1 = vec3_sub(b, a), e2 = vec3_sub(c, a), d = vec3_sub(p, a);
  float d00 = vec3_dot(e1, e1), d01 = vec3_dot(e1, e2), d11 = vec3_dot(e2, e2);
  float d20 = vec3_dot(d, e1), d21 = vec3_dot(d, e2);
  float denom = d00 * d11 - d01 * d01;
  if (!(denom > 1e-30f * (d00 * d11))) { *u = 1.0f / 3.0f; *v = 1.0f / 3.0f; return; }
  *u = (d11 * d20 - d01 * d21) / denom;
  *v = (d00 * d21 - d01 * d20) / denom;
}

/* Barycentric coordinates of p on the scene's leaf-order triangle tri. */
PM_DEVICE void scene_triangle_barycentrics(PM_GLOBAL const float4* triangles, int tri, Vec3 p, float* u, float* v)
{
  triangle_barycentrics(p, scene_triangle_vertex(triangles, tri, 0), scene_triangle_vertex(triangles, tri, 1),
                        scene_triangle_vertex(triangles, tri, 2), u, v);
}

#endif

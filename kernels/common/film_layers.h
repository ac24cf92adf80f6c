/* The film's extra layers for compositing and denoising (docs/layers.md), read from the shading
   points the camera pass (S5) recorded, so they cost no ray of their own and every method gets
   them. One work item per pixel writes:
     film_albedo   rgb: reflectance of the first non-specular surface on the eye path, times the
                   product of the mirror reflectances before it; w: that first hit's material
                   index as int bits (-1: miss)
     film_normal   xyz: unit normal of that non-specular surface, facing the viewer; w: distance
                   from the camera to the first hit (PM_LAYER_MISS_DEPTH for a miss)
     film_position xyz: world position of the first hit; w: its object index as int bits (-1)
   Albedo and normal follow the denoisers' convention (through perfect mirrors to the first
   diffuse or glossy surface); depth, position and the ids describe what the camera sees first,
   mirror or not, as compositors expect of Z-depth and ID mattes. The camera pass traces one ray
   through each pixel's centre, so there is nothing to average. */
#ifndef PM_FILM_LAYERS_H
#define PM_FILM_LAYERS_H

#include "brdf.h"
#include "camera_pass.h"
#include "kernel_globals.h"
#include "scene_traverse.h"

/* Depth written for pixels whose eye ray hits nothing: large and finite (half files clamp it to
   65504, the largest half). Cycles' depth pass uses the same value for its background. */
#define PM_LAYER_MISS_DEPTH 1.0e10f

/* A surface the layers look through: a perfect mirror with no diffuse or glossy part. */
PM_DEVICE int material_is_pure_mirror(const Material* m)
{
  Vec3 rest = vec3_add(material_diffuse(m), material_glossy(m));
  return material_has_mirror(m) && rest.x == 0.0f && rest.y == 0.0f && rest.z == 0.0f;
}

/* The reflectance a denoiser wants as albedo: the diffuse plus the glossy reflectance (the modified
   Phong lobe's albedo at normal incidence), so a glossy-only surface is not taken for black. */
PM_DEVICE Vec3 material_layer_albedo(const Material* m) { return vec3_add(material_diffuse(m), material_glossy(m)); }

/* Object index of a triangle (leaf order), stored by the host in its third vertex's w. */
PM_DEVICE int scene_triangle_object(PM_GLOBAL const float4* triangles, int tri)
{
  return PM_AS_INT(PM_LOAD(&triangles[3 * tri + 2]).w);
}

PM_DEVICE void kernel_film_layers(const KernelGlobals* kg, const LaunchParams* p, uint pixel)
{
  EyePath eye = eye_path_begin(pixel);
  ShadingPoint sp;
  if (!eye_path_next(kg, p, &eye, &sp)) {
    kg->film_albedo[pixel] = PM_MAKE_FLOAT4(0.0f, 0.0f, 0.0f, PM_AS_FLOAT(-1));
    kg->film_normal[pixel] = PM_MAKE_FLOAT4(0.0f, 0.0f, 0.0f, PM_LAYER_MISS_DEPTH);
    kg->film_position[pixel] = PM_MAKE_FLOAT4(0.0f, 0.0f, 0.0f, PM_AS_FLOAT(-1));
    return;
  }
  Vec3 first = sp.position;
  int first_triangle = sp.triangle;
  int first_material = scene_triangle_material(kg->triangles, first_triangle);
  float depth = vec3_length(vec3_sub(first, vec3_from_float4(p->camera.position)));
  kg->film_position[pixel] = vec3_to_float4(first, PM_AS_FLOAT(scene_triangle_object(kg->triangles, first_triangle)));

  /* Through the mirrors the camera pass followed; none left (the path ended at a mirror or left
     the scene after one): no surface to describe, black albedo and a zero normal, as for the
     background. */
  Vec3 albedo = vec3_splat(0.0f), normal = vec3_splat(0.0f);
  do {
    if (material_is_pure_mirror(&sp.material)) continue;
    albedo = vec3_mul(sp.weight, material_layer_albedo(&sp.material));
    normal = sp.normal;
    break;
  } while (eye_path_next(kg, p, &eye, &sp));
  kg->film_albedo[pixel] = vec3_to_float4(albedo, PM_AS_FLOAT(first_material));
  kg->film_normal[pixel] = vec3_to_float4(normal, depth);
}

#endif

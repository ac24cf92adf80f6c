/* Vertex link radiosity, the image (section 3.4): at every shading point of the camera pass the
   gathered indirect irradiance is interpolated barycentrically from the corner elements of the
   refined triangle the point lies on, on the side the viewer sees, and reflected diffusely:
   L_indirect = weight * rho_d / pi * sum_k w_k I_total(element_k). Direct light stays the
   camera pass's exact ray-traced direct light (the paper used shadow maps). A glossy lobe
   reflects the interpolated irradiance as if it arrived uniformly from the hemisphere: rho_d
   becomes rho_d + rho_s a_n(cos theta_o) (brdf_glossy_albedo), the light the lobe sends towards
   the viewer. The result is
   added into film_indirect_sum like a photon-mapping pass; the caustic layer gets nothing (the
   method is diffuse only). */
#ifndef PM_RADIOSITY_INTERPOLATE_H
#define PM_RADIOSITY_INTERPOLATE_H

#include "camera_pass.h"
#include "film.h"
#include "pixel_order.h"
#include "radiosity_mesh.h"

/* Gathered irradiance at point x of scene triangle `leaf`, seen from the side of normal n. */
PM_DEVICE Vec3 radiosity_irradiance_at(const KernelGlobals* kg, const LaunchParams* p, int leaf, Vec3 x, Vec3 n)
{
  PM_GLOBAL const float4* irradiance = kg->rad_irradiance + p->radiosity_source * p->element_count;
  uint elements[3];
  RadiosityLocation loc = radiosity_surface_point(kg, leaf, x, n, elements);
  Vec3 sum = vec3_splat(0.0f);
  for (int k = 0; k < 3; ++k)
    if (elements[k] != PM_RADIOSITY_NONE) sum = vec3_madd(sum, vec3_from_float4(PM_LOAD(&irradiance[elements[k]])), loc.w[k]);
  return sum;
}

/* Radiance that material m at point x of scene triangle `leaf` (normal n towards the viewer, cos_o
   the cosine of the direction it is seen from) reflects of the gathered irradiance there: diffusely
   with rho_d, and with the glossy lobe's albedo towards the viewer. */
PM_DEVICE Vec3 radiosity_reflected(const KernelGlobals* kg, const LaunchParams* p, const Material* m, int leaf, Vec3 x,
                                   Vec3 n, float cos_o)
{
  Vec3 rho = material_diffuse(m), rho_s = material_glossy(m);
  if (rho_s.x > 0.0f || rho_s.y > 0.0f || rho_s.z > 0.0f) rho = vec3_madd(rho, rho_s, brdf_glossy_albedo(m->glossy.w, cos_o));
  if ((rho.x <= 0.0f && rho.y <= 0.0f && rho.z <= 0.0f) || leaf < 0) return vec3_splat(0.0f);
  return vec3_scale(vec3_mul(rho, radiosity_irradiance_at(kg, p, leaf, x, n)), PM_INV_PI);
}

/* One work item per pixel (in tile order, pixel_order.h), over its shading points (mirror depths). */
PM_DEVICE void kernel_radiosity_interpolate(const KernelGlobals* kg, const LaunchParams* p, uint item)
{
  uint pixel;
  if (!pixel_of_work_item(item, p->width, p->height, &pixel)) return;
  Vec3 indirect = vec3_splat(0.0f);
  EyePath eye = eye_path_begin(pixel);
  ShadingPoint sp; /* its material: the texture at the pixel's own point (the elements carry
                      irradiance, the image its detail) */
  while (eye_path_next(kg, p, &eye, &sp)) {
    float cos_o = pm_fabsf(vec3_dot(sp.outgoing, sp.normal));
    Vec3 l = radiosity_reflected(kg, p, &sp.material, sp.triangle, sp.position, sp.normal, cos_o);
    indirect = vec3_add(indirect, vec3_mul(sp.weight, l));
  }
  film_add(kg, p, pixel, indirect, vec3_splat(0.0f));
}

#endif

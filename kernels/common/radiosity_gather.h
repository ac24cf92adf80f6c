/* Vertex link radiosity, light exchange (section 3.3): gathering over the links, one bounce per
   launch, and the one-ring smoothing of the result.

   Gathering (eq. 3, 4): element x collects the outgoing radiance of the previous bounce over
   its links, E_i(x) = pi * sum_links w * L_{i-1}(y) (the links carry V G as weights, link
   weights are cosine-weighted ray fractions, so pi * w is the solid-angle measure); the sum is
   added to the total incoming irradiance I_total (eq. 3), and x's new outgoing radiance is
   f_d * E_i(x) = rho_d / pi * E_i(x) (eq. 4). Bounce i reads half (i mod 2) of rad_radiance
   and writes the other. After nB launches I_total holds bounces 1..nB: the indirect light of
   the photon mapper's --bounces, without the direct light (the camera pass's).

   Smoothing (eq. 5, 6): I_smooth(v) = I(v) + sum_{v_i in N^(v)} w_i (I(v_i) - I(v)) with N^(v)
   the one-ring neighbours whose normals are within the feature angle alpha_f
   (n_v . n_vi > cos alpha_f), so that radiance is never averaged over a feature edge. Eq. 5 takes
   the plain mean, w_i = 1 / (|N^(v)| + 1); here w_i weighs the area v and v_i share
   (radiosity_elements.h), which equals eq. 5 on a regular mesh and, unlike it, keeps the power
   of the interpolated irradiance on any mesh, at a feature edge too. */
#ifndef PM_RADIOSITY_GATHER_H
#define PM_RADIOSITY_GATHER_H

#include "radiosity_links.h"

/* One work item per element: one bounce (eq. 3, 4). */
PM_DEVICE void kernel_radiosity_gather(const KernelGlobals* kg, const LaunchParams* p, uint e)
{
  PM_GLOBAL const float4* source = kg->rad_radiance + p->radiosity_source * p->element_count;
  PM_GLOBAL float4* target = kg->rad_radiance + (1u - p->radiosity_source) * p->element_count;
  uint first = PM_LOAD(&kg->rad_element_ranges[e]).z, end = PM_LOAD(&kg->rad_element_ranges[e + 1u]).z;
  Vec3 sum = vec3_splat(0.0f);
  uint y = 0;
  for (uint at = first; at < end;) {
    float w;
    y = radiosity_next_link(kg->rad_links, &at, y, &w);
    sum = vec3_madd(sum, vec3_from_float4(PM_LOAD(&source[y])), w);
  }
  Vec3 gathered = vec3_scale(sum, PM_PI);
  kg->rad_irradiance[e] = vec3_to_float4(vec3_add(vec3_from_float4(kg->rad_irradiance[e]), gathered), 0.0f);
  target[e] = vec3_to_float4(vec3_scale(vec3_mul(radiosity_element_reflectance(kg, e), gathered), PM_INV_PI), 0.0f);
}

/* One work item per element: one smoothing pass (eq. 5 over N^ of eq. 6), from half
   radiosity_source of rad_irradiance into the other half. */
PM_DEVICE void kernel_radiosity_smooth(const KernelGlobals* kg, const LaunchParams* p, uint e)
{
  PM_GLOBAL const float4* source = kg->rad_irradiance + p->radiosity_source * p->element_count;
  PM_GLOBAL float4* target = kg->rad_irradiance + (1u - p->radiosity_source) * p->element_count;
  Vec3 n = radiosity_element_normal(kg, e);
  uint first = PM_LOAD(&kg->rad_element_ranges[e]).y, end = PM_LOAD(&kg->rad_element_ranges[e + 1u]).y;
  uint weights_first = PM_LOAD(&kg->rad_element_ranges[p->element_count]).x;
  Vec3 own = vec3_from_float4(source[e]);
  Vec3 moved = vec3_splat(0.0f);
  for (uint j = first; j < end; ++j) {
    uint v = PM_LOAD(&kg->rad_adjacency[j]);
    if (vec3_dot(n, radiosity_element_normal(kg, v)) <= p->feature_cos) continue; /* eq. 6 */
    float w = PM_LOAD(&kg->rad_smooth_weights[j - weights_first]);
    moved = vec3_madd(moved, vec3_sub(vec3_from_float4(source[v]), own), w);
  }
  target[e] = vec3_to_float4(vec3_add(own, moved), 0.0f);
}

#endif

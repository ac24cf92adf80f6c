/* Stage S7, the film: the direct layer is written once per frame by the camera pass; the methods'
   passes add their indirect and caustic estimates into film_indirect_sum and film_caustic_sum
   (weight 1 each). The resolve is the one place that normalises: each sum divided by the number
   of passes, combined = direct + indirect + caustic. It is also the last guard of the "no NaN or
   Inf in an image" rule: a non-finite pixel becomes black in every output layer and is counted,
   so the host can report it instead of writing a corrupt image. The sums stay untouched, so more
   passes can follow a resolve. */
#ifndef PM_FILM_H
#define PM_FILM_H

#include "kernel_globals.h"
#include "vec3.h"

PM_DEVICE int film_finite(float4 v) { return pm_isfinite(v.x) && pm_isfinite(v.y) && pm_isfinite(v.z); }

PM_DEVICE void kernel_film_resolve(const KernelGlobals* kg, const LaunchParams* p, uint pixel)
{
  float scale = 1.0f / (float)(p->film_passes > 0u ? p->film_passes : 1u);
  Vec3 direct = vec3_from_float4(kg->film_direct[pixel]);
  Vec3 indirect = vec3_scale(vec3_from_float4(kg->film_indirect_sum[pixel]), scale);
  Vec3 caustic = vec3_scale(vec3_from_float4(kg->film_caustic_sum[pixel]), scale);
  float4 sum = vec3_to_float4(vec3_add(vec3_add(direct, indirect), caustic), 0.0f);
  if (!film_finite(sum)) {
    float4 zero = PM_MAKE_FLOAT4(0.0f, 0.0f, 0.0f, 0.0f);
    kg->film_direct[pixel] = zero;
    kg->film_indirect[pixel] = zero;
    kg->film_caustic[pixel] = zero;
    sum = zero;
    sum.w = 1.0f; /* marks the pixel as repaired; the host counts these */
  } else {
    kg->film_indirect[pixel] = vec3_to_float4(indirect, 0.0f);
    kg->film_caustic[pixel] = vec3_to_float4(caustic, 0.0f);
  }
  kg->film_combined[pixel] = sum;
}

/* A pass's estimate at a pixel added to the film sums (one work item per pixel: no atomics). */
PM_DEVICE void film_add(const KernelGlobals* kg, uint pixel, Vec3 indirect, Vec3 caustic)
{
  kg->film_indirect_sum[pixel] = vec3_to_float4(vec3_add(vec3_from_float4(kg->film_indirect_sum[pixel]), indirect), 0.0f);
  kg->film_caustic_sum[pixel] = vec3_to_float4(vec3_add(vec3_from_float4(kg->film_caustic_sum[pixel]), caustic), 0.0f);
}

#endif

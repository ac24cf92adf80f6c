/* Stage S7: the combined layer is direct + indirect + caustic. It is also the last guard of the
   "no NaN or Inf in an image" rule: a non-finite pixel becomes black in every layer and is
   counted, so the host can report it instead of writing a corrupt image. */
#ifndef PM_FILM_H
#define PM_FILM_H

#include "kernel_globals.h"
#include "vec3.h"

PM_DEVICE int film_finite(float4 v) { return pm_isfinite(v.x) && pm_isfinite(v.y) && pm_isfinite(v.z); }

PM_DEVICE void kernel_film_resolve(const KernelGlobals* kg, const LaunchParams* p, uint pixel)
{
  float4 direct = kg->film_direct[pixel];
  float4 indirect = kg->film_indirect ? kg->film_indirect[pixel] : PM_MAKE_FLOAT4(0.0f, 0.0f, 0.0f, 0.0f);
  float4 caustic = kg->film_caustic ? kg->film_caustic[pixel] : PM_MAKE_FLOAT4(0.0f, 0.0f, 0.0f, 0.0f);
  float4 sum = PM_MAKE_FLOAT4(direct.x + indirect.x + caustic.x, direct.y + indirect.y + caustic.y,
                              direct.z + indirect.z + caustic.z, 0.0f);
  if (!film_finite(sum)) {
    float4 zero = PM_MAKE_FLOAT4(0.0f, 0.0f, 0.0f, 0.0f);
    kg->film_direct[pixel] = zero;
    if (kg->film_indirect) kg->film_indirect[pixel] = zero;
    if (kg->film_caustic) kg->film_caustic[pixel] = zero;
    sum = zero;
    sum.w = 1.0f; /* marks the pixel as repaired; the host counts these */
  }
  kg->film_combined[pixel] = sum;
}

#endif

/* Stage S7, the film: the direct layer is written once per frame by the camera pass; the methods'
   passes add their indirect and caustic estimates into film_indirect_sum and film_caustic_sum
   (weight 1 each). The caustic sum exists only in a scene with mirrors, the only way a photon
   reaches a diffuse surface by specular bounces alone (p->film_caustic; elsewhere the caustic
   light is zero and film_caustic reads it so). The host resolves the film when it reads it back
   (Renderer::read_image, film_combine): each sum divided by the number of passes
   (film_resolved), combined = direct + indirect + caustic, so the device keeps no resolved copy
   of any layer. That is also the last guard of the "no NaN or Inf in an image" rule: a
   non-finite pixel becomes black in every output layer and is counted, so the host can report
   it instead of writing a corrupt image. The sums stay untouched, so more passes can follow a
   read.

   The error estimate: odd passes also go into an odd-pass sum of indirect + caustic, so the mean
   of the even passes and the mean of the odd passes are two independent estimates of the same
   image. Its red and green ride in the w of film_direct and film_indirect_sum, which their RGB
   layers leave free, its blue in film_odd_blue (film_odd_sum; the camera pass writes the direct
   layer with w = 0 at the start of a frame). Their difference is noise only; film_error_tiles
   sums it per tile of PM_FILM_ERROR_TILE pixels, and the host turns it into the expected relative
   error of the mean of all passes (render/progressive.h). */
#ifndef PM_FILM_H
#define PM_FILM_H

#include "kernel_globals.h"
#include "vec3.h"

PM_DEVICE int film_finite(float4 v) { return pm_isfinite(v.x) && pm_isfinite(v.y) && pm_isfinite(v.z); }

/* A film sum resolved: divided by the pass count (at least 1). */
PM_DEVICE Vec3 film_resolved(float4 sum, uint passes)
{
  return vec3_scale(vec3_from_float4(sum), 1.0f / (float)(passes > 0u ? passes : 1u));
}

/* A pixel resolved over `passes`: its combined value direct + indirect + caustic in *combined;
   returns 0 when that is not finite, and the pixel is then to be black in every layer. */
PM_DEVICE int film_combine(float4 direct, float4 indirect_sum, float4 caustic_sum, uint passes, Vec3* combined)
{
  *combined = vec3_add(vec3_add(vec3_from_float4(direct), film_resolved(indirect_sum, passes)),
                       film_resolved(caustic_sum, passes));
  return film_finite(vec3_to_float4(*combined, 0.0f));
}

/* The caustic sum at a pixel: zero in a film without one (a scene without mirrors). */
PM_DEVICE Vec3 film_caustic(const KernelGlobals* kg, const LaunchParams* p, uint pixel)
{
  return p->film_caustic ? vec3_from_float4(kg->film_caustic_sum[pixel]) : vec3_splat(0.0f);
}

/* The odd passes' sum of indirect + caustic at a pixel. */
PM_DEVICE Vec3 film_odd_sum(const KernelGlobals* kg, uint pixel)
{
  return vec3(kg->film_direct[pixel].w, kg->film_indirect_sum[pixel].w, kg->film_odd_blue[pixel]);
}

/* A pass's estimate at a pixel added to the film sums (one work item per pixel: no atomics). The
   caustic estimate is zero where the film has no caustic sum. */
PM_DEVICE void film_add(const KernelGlobals* kg, const LaunchParams* p, uint pixel, Vec3 indirect, Vec3 caustic)
{
  float4 indirect_sum = kg->film_indirect_sum[pixel];
  float odd_green = indirect_sum.w;
  if (p->pass_index & 1u) {
    Vec3 odd = vec3_add(film_odd_sum(kg, pixel), vec3_add(indirect, caustic));
    kg->film_direct[pixel].w = odd.x;
    odd_green = odd.y;
    kg->film_odd_blue[pixel] = odd.z;
  }
  kg->film_indirect_sum[pixel] = vec3_to_float4(vec3_add(vec3_from_float4(indirect_sum), indirect), odd_green);
  if (p->film_caustic)
    kg->film_caustic_sum[pixel] = vec3_to_float4(vec3_add(vec3_from_float4(kg->film_caustic_sum[pixel]), caustic), 0.0f);
}

#define PM_FILM_ERROR_TILE 256

/* Work item = tile of PM_FILM_ERROR_TILE pixels, with film_passes passes in the film of which
   film_odd_passes odd, both kinds at least one: the sums over its pixels and channels of
   |mean of even passes - mean of odd passes| and of |mean of all passes|, for the indirect +
   caustic light. */
PM_DEVICE void kernel_film_error_tiles(const KernelGlobals* kg, const LaunchParams* p, uint tile)
{
  uint pixels = p->width * p->height;
  uint begin = tile * PM_FILM_ERROR_TILE;
  uint end = pm_min_u(begin + PM_FILM_ERROR_TILE, pixels);
  float odd_passes = (float)p->film_odd_passes, even_passes = (float)(p->film_passes - p->film_odd_passes);
  float difference = 0.0f, level = 0.0f;
  for (uint i = begin; i < end; ++i) {
    Vec3 all = vec3_add(vec3_from_float4(kg->film_indirect_sum[i]), film_caustic(kg, p, i));
    Vec3 odd = film_odd_sum(kg, i);
    Vec3 even_mean = vec3_scale(vec3_sub(all, odd), 1.0f / even_passes);
    Vec3 odd_mean = vec3_scale(odd, 1.0f / odd_passes);
    Vec3 d = vec3_sub(even_mean, odd_mean);
    float diff = pm_fabsf(d.x) + pm_fabsf(d.y) + pm_fabsf(d.z);
    float lvl = (pm_fabsf(all.x) + pm_fabsf(all.y) + pm_fabsf(all.z)) / (even_passes + odd_passes);
    if (pm_isfinite(diff) && pm_isfinite(lvl)) {
      difference += diff;
      level += lvl;
    }
  }
  kg->film_error_partials[tile] = PM_MAKE_FLOAT4(difference, level, 0.0f, 0.0f);
}

#endif

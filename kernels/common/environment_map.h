/* The environment map's geometry and its importance-sampling distribution, as pure functions of
   the map's buffers (no traversal, no scene): the equirectangular (lat-long) parameterisation,
   the texel a direction falls in, and sampling a texel in proportion to luminance x sin(theta)
   with the marginal and conditional CDFs that render/scene_environment.h builds.

   Parameterisation (u, v) in [0, 1)^2, u along a row (left to right), v down the rows (top row
   first): theta = pi v from +y (the top row is the zenith), phi = 2 pi u, and the map's own
   direction d = (-sin theta sin phi, cos theta, sin theta cos phi): the centre column (u = 1/2)
   faces -z and u = 3/4 faces +x, so a viewer inside looking at -z sees the map as it is drawn.
   The map is turned by `rotation` radians about +y (right-handed): world = R_y(rotation) d.

   The map is piecewise constant (nearest texel), and so is its sampling density over (u, v):
   texel (i, j) carries pdf_uv = f_ij W H / sum f, f_ij = luminance_ij sin(theta_j) at the row's
   centre. A direction's density per solid angle follows from d omega = 2 pi^2 sin(theta) du dv:
   pdf_omega = pdf_uv / (2 pi^2 sin theta), exact for the continuous theta of the sample.

   Buffers: environment_texels (W H float4: rgb radiance with the scale applied, w = pdf_uv) and
   environment_cdf (H floats of the marginal CDF over rows, then W floats per row of that row's
   conditional CDF; each CDF ends at exactly 1). */
#ifndef PM_ENVIRONMENT_MAP_H
#define PM_ENVIRONMENT_MAP_H

#include "types.h"
#include "vec3.h"

/* The map's direction of (u, v), turned by `rotation` about +y. */
PM_DEVICE Vec3 environment_direction(float u, float v, float rotation)
{
  float sin_theta, cos_theta, sin_phi, cos_phi, sin_rot, cos_rot;
  pm_sincosf(PM_PI * v, &sin_theta, &cos_theta);
  pm_sincosf(PM_TWO_PI * u, &sin_phi, &cos_phi);
  pm_sincosf(rotation, &sin_rot, &cos_rot);
  float x = -sin_theta * sin_phi, z = sin_theta * cos_phi;
  return vec3(x * cos_rot + z * sin_rot, cos_theta, -x * sin_rot + z * cos_rot);
}

/* The inverse: (u, v) of a unit world direction. */
PM_DEVICE void environment_uv(Vec3 d, float rotation, float* u, float* v)
{
  float sin_rot, cos_rot;
  pm_sincosf(rotation, &sin_rot, &cos_rot);
  /* Undo the turn: R_y(-rotation). */
  float x = d.x * cos_rot - d.z * sin_rot, z = d.x * sin_rot + d.z * cos_rot;
  float phi = pm_atan2f(-x, z);
  if (phi < 0.0f) phi += PM_TWO_PI;
  float uu = phi * (1.0f / PM_TWO_PI);
  *u = uu < 1.0f ? uu : 0.0f;
  *v = pm_acosf(pm_fminf(1.0f, pm_fmaxf(-1.0f, d.y))) * PM_INV_PI;
}

/* The texel (row-major, top row first) holding (u, v). */
PM_DEVICE uint environment_texel(float u, float v, uint width, uint height)
{
  uint i = (uint)pm_fmaxf(0.0f, u * (float)width), j = (uint)pm_fmaxf(0.0f, v * (float)height);
  if (i >= width) i = width - 1u;
  if (j >= height) j = height - 1u;
  return j * width + i;
}

/* The first entry of a CDF of `count` entries above u (binary search). An entry whose own
   probability is zero (equal to its predecessor) is never returned for u >= the predecessor. */
PM_DEVICE uint environment_cdf_find(PM_GLOBAL const float* cdf, uint count, float u)
{
  uint lo = 0u, hi = count - 1u;
  while (lo < hi) {
    uint mid = (lo + hi) >> 1;
    if (u < PM_LOAD(&cdf[mid])) hi = mid;
    else lo = mid + 1u;
  }
  return lo;
}

/* Where u falls within entry k of a CDF, rescaled to [0, 1): reuses the bits the search did not
   consume, so one uniform number picks the entry and the point inside it. */
PM_DEVICE float environment_cdf_remainder(PM_GLOBAL const float* cdf, uint k, float u)
{
  float lo = k > 0u ? PM_LOAD(&cdf[k - 1u]) : 0.0f, hi = PM_LOAD(&cdf[k]);
  float t = hi > lo ? (u - lo) / (hi - lo) : 0.5f;
  return pm_fminf(pm_fmaxf(t, 0.0f), 0.99999994f);
}

/* A point (u, v) drawn from the map's distribution: a row from the marginal CDF by u1, a texel
   of that row from its conditional CDF by u2, uniform within the texel. Returns the texel. */
PM_DEVICE uint environment_sample_uv(PM_GLOBAL const float* cdf, uint width, uint height, float u1, float u2, float* u,
                                     float* v)
{
  uint row = environment_cdf_find(cdf, height, u1);
  float dv = environment_cdf_remainder(cdf, row, u1);
  PM_GLOBAL const float* conditional = cdf + height + row * width;
  uint column = environment_cdf_find(conditional, width, u2);
  float du = environment_cdf_remainder(conditional, column, u2);
  *u = ((float)column + du) / (float)width;
  *v = ((float)row + dv) / (float)height;
  return row * width + column;
}

/* Density per solid angle of the map's sampling at (v, its texel's pdf_uv): pdf_uv / (2 pi^2
   sin theta); 0 at the poles, where the map cannot be sampled. */
PM_DEVICE float environment_map_pdf(float pdf_uv, float v)
{
  float sin_theta = pm_sinf(PM_PI * v);
  return sin_theta > 0.0f ? pdf_uv / (2.0f * PM_PI * PM_PI * sin_theta) : 0.0f;
}

/* A direction uniform on the sphere (the constant environment's sampling, density 1 / (4 pi)). */
PM_DEVICE Vec3 environment_uniform_direction(float u1, float u2)
{
  float cos_theta = 1.0f - 2.0f * u1;
  float sin_theta = 2.0f * pm_sqrtf(pm_fmaxf(0.0f, u1 * (1.0f - u1)));
  float sin_phi, cos_phi;
  pm_sincosf(PM_TWO_PI * u2, &sin_phi, &cos_phi);
  return vec3(sin_theta * cos_phi, cos_theta, sin_theta * sin_phi);
}

#endif

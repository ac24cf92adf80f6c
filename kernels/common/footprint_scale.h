/* Automatic smoothing (`--smoothing auto`, render/footprint_scale.h): the reduction that sizes
   the diffuse footprints of a batch from its own photons. Per tile of hit slots it sums the area
   of every diffusely reflected hit's footprint at s = 1 without the r_max clamp,
   pi |a_u x a_v| with |a_x| = Delta |dp_x|^(1/4) (footprint.h), and counts those hits. The host
   then chooses s so that the batch's diffuse footprints cover the scene's surface a set number of
   times on average: s^2 * sum = overlap * scene area. */
#ifndef PM_FOOTPRINT_SCALE_H
#define PM_FOOTPRINT_SCALE_H

#include "footprint.h"
#include "kernel_globals.h"
#include "photon_map.h"
#include "photon_trace.h"

/* Work item = tile of PM_PHOTON_MAP_BOUNDS_TILE slots. Writes map_partials[2 tile] =
   (area sum at s = 1, 0, 0, 0); [2 tile + 1] is left alone. */
PM_DEVICE void kernel_photon_footprint_scale(const KernelGlobals* kg, const LaunchParams* p, uint tile)
{
  uint slots = p->photon_count * p->hit_slots_per_photon;
  uint begin = tile * PM_PHOTON_MAP_BOUNDS_TILE;
  uint end = pm_min_u(begin + PM_PHOTON_MAP_BOUNDS_TILE, slots);
  float area = 0.0f;
  for (uint i = begin; i < end; ++i) {
    uint flags = kg->hit_slots[i];
    if ((flags & PM_HIT_VALID) == 0u || (flags & PM_HIT_CAUSTIC) != 0u) continue;
    uint record = photon_hit_record(flags);
    float delta = photon_hit_part(kg, record, PM_RECORD_INCIDENT).w;
    Vec3 a_u = footprint_semiaxis(vec3_from_float4(photon_hit_part(kg, record, PM_RECORD_DP_U)), delta, 1.0f, PM_FOOTPRINT_FAR, 0);
    Vec3 a_v = footprint_semiaxis(vec3_from_float4(photon_hit_part(kg, record, PM_RECORD_DP_V)), delta, 1.0f, PM_FOOTPRINT_FAR, 0);
    float a = PM_PI * vec3_length(vec3_cross(a_u, a_v));
    if (!pm_isfinite(a)) continue;
    area += a;
  }
  kg->map_partials[2 * tile] = PM_MAKE_FLOAT4(area, 0.0f, 0.0f, 0.0f);
}

#endif

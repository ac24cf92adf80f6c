/* Automatic smoothing (`--smoothing auto`, render/footprint_scale.h): the reduction that sizes
   the diffuse footprints of a batch from its own photons. Per tile of hit slots it sums the area
   of every diffusely reflected hit's footprint at s = 1 without the r_max clamp,
   pi |a_u x a_v| with |a_x| = Delta |dp_x|^(1/4) (footprint.h). The host
   then chooses s so that the batch's diffuse footprints cover the scene's surface a set number of
   times on average: s^2 * sum = overlap * scene area. */
#ifndef PM_FOOTPRINT_SCALE_H
#define PM_FOOTPRINT_SCALE_H

#include "footprint.h"
#include "kernel_globals.h"
#include "photon_map.h"
#include "photon_trace.h"

/* Slots per work item: an eighth of the bounds reduction's tile, so that map_partials, which
   holds eight floats per bounds tile, holds one float per tile here. With the bounds' 256 slots a
   work item, a 1M-photon batch was 8192 work items each waiting on 256 dependent loads: 0.33 ms
   at 6 % of the GPU's warps (docs/benchmarks.md, "The automatic smoothing's tiles"). */
#define PM_FOOTPRINT_SCALE_TILE (PM_PHOTON_MAP_BOUNDS_TILE / 8u)

PM_DEVICE uint footprint_scale_tile_count(uint slots)
{
  return (slots + PM_FOOTPRINT_SCALE_TILE - 1u) / PM_FOOTPRINT_SCALE_TILE;
}

/* Work item = tile of PM_FOOTPRINT_SCALE_TILE slots. Writes float `tile` of map_partials (read
   as floats): the tile's area sum at s = 1. The slot words of a batch are loaded first, then the
   records of its valid diffuse hits, so that the loads are in flight together. */
PM_DEVICE void kernel_photon_footprint_scale(const KernelGlobals* kg, const LaunchParams* p, uint tile)
{
  uint slots = p->photon_count * p->hit_slots_per_photon;
  uint begin = tile * PM_FOOTPRINT_SCALE_TILE;
  uint end = pm_min_u(begin + PM_FOOTPRINT_SCALE_TILE, slots);
  float area = 0.0f;
  for (uint first = begin; first < end; first += PM_PHOTON_MAP_HIT_BATCH) {
    uint flags[PM_PHOTON_MAP_HIT_BATCH];
    for (uint j = 0; j < PM_PHOTON_MAP_HIT_BATCH; ++j) flags[j] = first + j < end ? kg->hit_slots[first + j] : 0u;
    for (uint j = 0; j < PM_PHOTON_MAP_HIT_BATCH; ++j) {
      if ((flags[j] & PM_HIT_VALID) == 0u || (flags[j] & PM_HIT_CAUSTIC) != 0u) continue;
      uint record = photon_hit_record(flags[j]);
      float delta = photon_hit_part(kg, record, PM_RECORD_INCIDENT).w;
      Vec3 a_u = footprint_semiaxis(vec3_from_float4(photon_hit_part(kg, record, PM_RECORD_DP_U)), delta, 1.0f,
                                    PM_FOOTPRINT_FAR, 0);
      Vec3 a_v = footprint_semiaxis(vec3_from_float4(photon_hit_part(kg, record, PM_RECORD_DP_V)), delta, 1.0f,
                                    PM_FOOTPRINT_FAR, 0);
      float a = PM_PI * vec3_length(vec3_cross(a_u, a_v));
      if (pm_isfinite(a)) area += a;
    }
  }
  ((PM_GLOBAL float*)kg->map_partials)[tile] = area;
}

#endif

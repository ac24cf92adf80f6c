/* Stage S4 as kernels: binds the photon map steps of photon_map.h to the frame's buffers. Morton
   keys of empty slots are above every 30-bit code, so after the sort the hit_count valid hits
   form the prefix the tree is built over. */
#ifndef PM_PHOTON_MAP_STAGE_H
#define PM_PHOTON_MAP_STAGE_H

#include "kernel_globals.h"
#include "photon_map.h"
#include "photon_trace.h"

#define PM_MORTON_EMPTY_KEY 0x7FFFFFFFu
#define PM_MORTON_SORT_BITS 31

PM_DEVICE void kernel_photon_morton(const KernelGlobals* kg, const LaunchParams* p, uint slot)
{
  float4 c = kg->footprint_center[slot];
  uint key = PM_MORTON_EMPTY_KEY;
  if (PM_AS_UINT(c.w) & PM_HIT_VALID)
    key = morton_code(vec3_from_float4(c), vec3_from_float4(p->hit_bounds_lo), vec3_from_float4(p->hit_bounds_hi));
  kg->sort_keys[slot] = key;
  kg->sort_values[slot] = slot;
}

PM_DEVICE void kernel_photon_map_nodes(const KernelGlobals* kg, const LaunchParams* p, uint i)
{
  photon_map_build_node(i, p->hit_count, kg->sort_keys, kg->map_node_parent, kg->map_leaf_parent, kg->map_visits);
}

PM_DEVICE void kernel_photon_map_bottom_up(const KernelGlobals* kg, const LaunchParams* p, uint k)
{
  photon_map_bottom_up(k, p->hit_count, p->leaf_threshold, kg->sort_values, kg->footprint_lo, kg->footprint_hi,
                       kg->map_node_parent, kg->map_leaf_parent, kg->map_visits, kg->map_nodes, kg->map_lo,
                       kg->map_hi);
}

/* Gather data into sorted order, so a leaf's hits are contiguous for the gather. */
PM_DEVICE void kernel_photon_map_reorder(const KernelGlobals* kg, const LaunchParams* p, uint k)
{
  uint slot = kg->sort_values[k];
  kg->map_center[k] = kg->footprint_center[slot];
  kg->map_row_u[k] = kg->footprint_row_u[slot];
  kg->map_row_v[k] = kg->footprint_row_v[slot];
  kg->map_row_n[k] = kg->footprint_row_n[slot];
  kg->map_power[k] = kg->footprint_power[slot];
  kg->map_incident[k] = kg->hit_incident[slot];
  kg->map_cut[k] = kg->footprint_cut[slot];
}

#endif

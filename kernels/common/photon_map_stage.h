/* Stages S3 (bounds reduction) and S4 as kernels: binds the photon map steps of photon_map.h to
   the frame's buffers. Only the hit_count valid hits get Morton keys (compacted per tile), so the
   sort and the tree see nothing else. */
#ifndef PM_PHOTON_MAP_STAGE_H
#define PM_PHOTON_MAP_STAGE_H

#include "kernel_globals.h"
#include "photon_map.h"
#include "photon_trace.h"

/* Work item = tile of hit slots: bounds, footprint area and count of the valid hits (S3's
   reduction, read back for the Morton bounds and T_auto). */
PM_DEVICE void kernel_photon_reduce(const KernelGlobals* kg, const LaunchParams* p, uint tile)
{
  photon_map_bounds_tile(tile, p->photon_count * p->hit_slots_per_photon, kg->footprint_center, kg->footprint_lo,
                         kg->footprint_partials);
}

/* Work item = tile: the valid hits' Morton keys, compacted, for a sort of hit_count pairs. */
PM_DEVICE void kernel_photon_morton(const KernelGlobals* kg, const LaunchParams* p, uint tile)
{
  photon_map_morton_tile(tile, p->photon_count * p->hit_slots_per_photon, kg->footprint_center, kg->map_tile_offsets,
                         p->hit_bounds_lo, p->hit_bounds_hi, kg->morton_keys, kg->morton_slots);
}

PM_DEVICE void kernel_photon_map_nodes(const KernelGlobals* kg, const LaunchParams* p, uint i)
{
  photon_map_build_node(i, p->hit_count, kg->sorted_keys, kg->map_node_parent, kg->map_leaf_parent, kg->map_visits);
}

PM_DEVICE void kernel_photon_map_bottom_up(const KernelGlobals* kg, const LaunchParams* p, uint k)
{
  photon_map_bottom_up(k, p->hit_count, p->leaf_threshold, kg->sorted_slots, kg->footprint_lo, kg->footprint_hi,
                       kg->map_node_parent, kg->map_leaf_parent, kg->map_visits, kg->map_nodes, kg->map_lo,
                       kg->map_hi);
}

/* Gather data into sorted order, so a leaf's hits are contiguous for the gather. */
PM_DEVICE void kernel_photon_map_reorder(const KernelGlobals* kg, const LaunchParams* p, uint k)
{
  uint slot = kg->sorted_slots[k];
  kg->map_center[k] = kg->footprint_center[slot];
  kg->map_row_u[k] = kg->footprint_row_u[slot];
  kg->map_row_v[k] = kg->footprint_row_v[slot];
  kg->map_row_n[k] = kg->footprint_row_n[slot];
  kg->map_power[k] = kg->footprint_power[slot];
  kg->map_incident[k] = kg->hit_incident[slot];
  kg->map_cut[k] = kg->footprint_cut[slot];
}

#endif

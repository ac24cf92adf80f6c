/* Stage S4 as kernels, and the reductions around it: binds the photon map steps of photon_map.h
   to the frame's buffers. Only the hit_count valid hits get Morton keys (compacted per tile), so
   the sort, the footprints (S3, after the sort, in sorted order) and the tree see nothing else. */
#ifndef PM_PHOTON_MAP_STAGE_H
#define PM_PHOTON_MAP_STAGE_H

#include "kernel_globals.h"
#include "photon_map.h"
#include "photon_trace.h"

/* Work item = tile of hit slots: bounds and count of the valid hits (the slots' flags, the
   records' positions), read back for the Morton bounds and the compaction. */
PM_DEVICE void kernel_photon_reduce(const KernelGlobals* kg, const LaunchParams* p, uint tile)
{
  photon_map_bounds_tile(tile, p->photon_count * p->hit_slots_per_photon, kg->hit_slots,
                         kg->hit_records + PM_RECORD_POSITION, PM_RECORD_FLOAT4S, 0, kg->map_partials);
}

/* Work item = tile of sorted positions: the footprints' total area, for T_auto (section 5.3). */
PM_DEVICE void kernel_photon_map_area(const KernelGlobals* kg, const LaunchParams* p, uint tile)
{
  photon_map_bounds_tile(tile, p->hit_count, 0, kg->map_center, 1u, kg->map_lo, kg->map_partials);
}

/* Work item = tile: the valid hits' Morton keys, compacted, for a sort of hit_count pairs. */
PM_DEVICE void kernel_photon_morton(const KernelGlobals* kg, const LaunchParams* p, uint tile)
{
  photon_map_morton_tile(tile, p->photon_count * p->hit_slots_per_photon, kg->hit_slots,
                         kg->hit_records + PM_RECORD_POSITION, PM_RECORD_FLOAT4S, kg->map_tile_offsets,
                         p->hit_bounds_lo, p->hit_bounds_hi, PM_SORT_KEYS(kg), PM_SORT_SLOTS(kg));
}

/* The tree's nodes, build links and visit counters take the memory of what the pass has spent
   by then, and the sort's input that of gather arrays not yet written (PM_MAP_NODES and the
   rest, buffers.h). */
PM_DEVICE void kernel_photon_map_nodes(const KernelGlobals* kg, const LaunchParams* p, uint i)
{
  photon_map_build_node(i, p->hit_count, kg->sorted_keys, PM_MAP_NODE_PARENT(kg, p->hit_count),
                        PM_MAP_LEAF_PARENT(kg, p->hit_count), PM_MAP_VISITS(kg));
}

PM_DEVICE void kernel_photon_map_bottom_up(const KernelGlobals* kg, const LaunchParams* p, uint k)
{
  photon_map_bottom_up(k, p->hit_count, p->leaf_threshold, kg->map_lo, kg->map_hi,
                       PM_MAP_NODE_PARENT(kg, p->hit_count), PM_MAP_LEAF_PARENT(kg, p->hit_count), PM_MAP_VISITS(kg),
                       PM_MAP_NODES(kg));
}

#endif

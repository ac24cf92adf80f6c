/* Portable least-significant-digit radix sort of (key, value) pairs, PM_SORT_RADIX_BITS per
   pass, for backends without a library sort (OpenCL; CUDA uses CUB). Each work item owns a tile
   of PM_SORT_TILE consecutive keys and walks it in order, so the scatter is stable without
   local memory or barriers: one pass is histogram -> scan -> scatter.
   Histogram layout: counts[digit * tile_count + tile], digit-major, so one exclusive scan over
   it yields every tile's first output position for every digit. The scan runs in chunks of
   PM_SORT_TILE counts; chunk totals live after the counts and are scanned by one work item. */
#ifndef PM_RADIX_SORT_H
#define PM_RADIX_SORT_H

#include "kernel_globals.h"

PM_DEVICE uint radix_digit(uint key, uint shift) { return (key >> shift) & (PM_SORT_RADIX - 1); }

PM_DEVICE uint radix_count_entries(const LaunchParams* p) { return PM_SORT_RADIX * p->sort_tile_count; }

PM_DEVICE uint radix_chunk_count(const LaunchParams* p)
{
  return (radix_count_entries(p) + PM_SORT_TILE - 1) / PM_SORT_TILE;
}

/* Work item = tile. */
PM_DEVICE void kernel_sort_histogram(const KernelGlobals* kg, const LaunchParams* p, uint tile)
{
  uint counts[PM_SORT_RADIX];
  for (int d = 0; d < PM_SORT_RADIX; ++d) counts[d] = 0;
  uint begin = tile * PM_SORT_TILE;
  uint end = pm_min_u(begin + PM_SORT_TILE, p->sort_count);
  for (uint i = begin; i < end; ++i) counts[radix_digit(kg->sort_keys[i], p->sort_shift)]++;
  for (int d = 0; d < PM_SORT_RADIX; ++d) kg->sort_histogram[d * p->sort_tile_count + tile] = counts[d];
}

/* Work item = chunk of PM_SORT_TILE counts: exclusive scan in place, total stored after. */
PM_DEVICE void kernel_sort_scan_chunks(const KernelGlobals* kg, const LaunchParams* p, uint chunk)
{
  uint entries = radix_count_entries(p);
  uint begin = chunk * PM_SORT_TILE;
  uint end = pm_min_u(begin + PM_SORT_TILE, entries);
  uint running = 0;
  for (uint i = begin; i < end; ++i) {
    uint c = kg->sort_histogram[i];
    kg->sort_histogram[i] = running;
    running += c;
  }
  kg->sort_histogram[entries + chunk] = running;
}

/* Single work item: exclusive scan of the chunk totals. */
PM_DEVICE void kernel_sort_scan_totals(const KernelGlobals* kg, const LaunchParams* p, uint unused)
{
  uint entries = radix_count_entries(p);
  uint chunks = radix_chunk_count(p);
  uint running = 0;
  for (uint c = 0; c < chunks; ++c) {
    uint total = kg->sort_histogram[entries + c];
    kg->sort_histogram[entries + c] = running;
    running += total;
  }
}

/* Work item = tile: stable scatter of its keys to sort_keys_alt / sort_values_alt. */
PM_DEVICE void kernel_sort_scatter(const KernelGlobals* kg, const LaunchParams* p, uint tile)
{
  uint entries = radix_count_entries(p);
  uint offsets[PM_SORT_RADIX];
  for (int d = 0; d < PM_SORT_RADIX; ++d) {
    uint entry = d * p->sort_tile_count + tile;
    offsets[d] = kg->sort_histogram[entry] + kg->sort_histogram[entries + entry / PM_SORT_TILE];
  }
  uint begin = tile * PM_SORT_TILE;
  uint end = pm_min_u(begin + PM_SORT_TILE, p->sort_count);
  for (uint i = begin; i < end; ++i) {
    uint key = kg->sort_keys[i];
    uint dst = offsets[radix_digit(key, p->sort_shift)]++;
    kg->sort_keys_alt[dst] = key;
    kg->sort_values_alt[dst] = kg->sort_values[i];
  }
}

#endif

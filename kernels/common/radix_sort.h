/* Portable least-significant-digit radix sort of (key, value) pairs, PM_SORT_RADIX_BITS per
   pass, for backends without a library sort (OpenCL; CUDA uses CUB). Without local memory or
   barriers, one pass is histogram -> chunk scan -> chunk-total scan -> scatter:

   - The keys fall into tiles of PM_SORT_TILE consecutive keys, and each tile is walked by
     PM_SORT_RADIX work items, one per digit ("digit lanes"): lane d counts, then moves, the
     tile's keys of digit d, in order, so the scatter is stable. The lanes of a tile read the
     same key at each step (one broadcast load on a GPU, and 32 lanes fill a warp), and no lane
     indexes an array by a digit, which would put the array in slow private memory. One work item
     walking its tile for every digit kept a GPU to a few thousand threads, each stalling on
     its counters: 1.2-1.4 ms per million keys on NVIDIA's OpenCL against CUB's 0.09 ms.
   - Histogram layout: counts[digit * tile_count + tile], digit-major, so one exclusive scan over
     it yields every tile's first output position for every digit. The scan runs in chunks of
     PM_SORT_SCAN_CHUNK counts, one work item each; then every chunk's first position is the sum
     of the totals before it, each chunk summing them for itself (a few hundred loads at most,
     the same for the neighbouring work items), where one work item scanning them all in turn
     was the slowest launch of a pass on a GPU.

   Buffer sort_histogram: [0, entries) counts, then chunk totals [entries, entries + chunks),
   then chunk offsets [entries + chunks, entries + 2 chunks). */
#ifndef PM_RADIX_SORT_H
#define PM_RADIX_SORT_H

#include "kernel_globals.h"

PM_DEVICE uint radix_digit(uint key, uint shift) { return (key >> shift) & (PM_SORT_RADIX - 1); }

PM_DEVICE uint radix_count_entries(const LaunchParams* p) { return PM_SORT_RADIX * p->sort_tile_count; }

PM_DEVICE uint radix_chunk_count(const LaunchParams* p)
{
  return (radix_count_entries(p) + PM_SORT_SCAN_CHUNK - 1) / PM_SORT_SCAN_CHUNK;
}

/* Work item = (tile, digit) lane: how many of the tile's keys have the lane's digit. */
PM_DEVICE void kernel_sort_histogram(const KernelGlobals* kg, const LaunchParams* p, uint lane)
{
  uint tile = lane / PM_SORT_RADIX, digit = lane % PM_SORT_RADIX;
  uint begin = tile * PM_SORT_TILE;
  uint end = pm_min_u(begin + PM_SORT_TILE, p->sort_count);
  uint count = 0;
  for (uint i = begin; i < end; ++i) count += radix_digit(PM_LOAD(&kg->sort_keys[i]), p->sort_shift) == digit;
  kg->sort_histogram[digit * p->sort_tile_count + tile] = count;
}

/* Work item = chunk of PM_SORT_SCAN_CHUNK counts: exclusive scan in place, its total stored
   after the counts. */
PM_DEVICE void kernel_sort_scan_chunks(const KernelGlobals* kg, const LaunchParams* p, uint chunk)
{
  uint entries = radix_count_entries(p);
  uint begin = chunk * PM_SORT_SCAN_CHUNK;
  uint end = pm_min_u(begin + PM_SORT_SCAN_CHUNK, entries);
  uint running = 0;
  for (uint i = begin; i < end; ++i) {
    uint c = kg->sort_histogram[i];
    kg->sort_histogram[i] = running;
    running += c;
  }
  kg->sort_histogram[entries + chunk] = running;
}

/* Work item = chunk: its first output position, the sum of the totals of the chunks before it,
   stored after the totals. */
PM_DEVICE void kernel_sort_scan_totals(const KernelGlobals* kg, const LaunchParams* p, uint chunk)
{
  uint entries = radix_count_entries(p);
  uint before = 0;
  for (uint c = 0; c < chunk; ++c) before += PM_LOAD(&kg->sort_histogram[entries + c]);
  kg->sort_histogram[entries + radix_chunk_count(p) + chunk] = before;
}

/* Work item = (tile, digit) lane: moves the tile's keys of the lane's digit, in order, to
   sort_keys_alt / sort_values_alt from the digit's first position for the tile on. */
PM_DEVICE void kernel_sort_scatter(const KernelGlobals* kg, const LaunchParams* p, uint lane)
{
  uint tile = lane / PM_SORT_RADIX, digit = lane % PM_SORT_RADIX;
  uint entries = radix_count_entries(p);
  uint entry = digit * p->sort_tile_count + tile;
  uint dst = PM_LOAD(&kg->sort_histogram[entry]) +
             PM_LOAD(&kg->sort_histogram[entries + radix_chunk_count(p) + entry / PM_SORT_SCAN_CHUNK]);
  uint begin = tile * PM_SORT_TILE;
  uint end = pm_min_u(begin + PM_SORT_TILE, p->sort_count);
  for (uint i = begin; i < end; ++i) {
    uint key = PM_LOAD(&kg->sort_keys[i]);
    if (radix_digit(key, p->sort_shift) != digit) continue;
    kg->sort_keys_alt[dst] = key;
    kg->sort_values_alt[dst] = PM_LOAD(&kg->sort_values[i]);
    ++dst;
  }
}

#endif

/* Portable least-significant-digit radix sort of (key, value) pairs, PM_SORT_RADIX_BITS per
   pass, for backends without a library sort (OpenCL; CUDA uses CUB). Without local memory or
   barriers, one pass is two launches, histogram and scatter:

   - The keys fall into tiles of PM_SORT_TILE consecutive keys, and each tile is walked by
     PM_SORT_RADIX work items, one per digit ("digit lanes"): lane d counts, then moves, the
     tile's keys of digit d, in order, so the scatter is stable. The lanes of a tile read the
     same keys at each step (one broadcast load on a GPU; 32 lanes fill a warp), and no lane
     indexes an array by a digit, which would put the array in slow private memory.
   - Where a lane's keys go: after every key of a smaller digit, and after its digit's keys in
     the tiles before it. The histogram lane stores its count and adds it (atomically: integer
     sums do not depend on the order) to its digit's total and to its group's total, a group
     being PM_SORT_GROUP consecutive tiles of one digit. The scatter lane then sums at most 31
     digit totals, the totals of its digit's groups before its own and the counts of its
     group's tiles before its own (a million keys: at most 31 + 63 + 63 loads).
   - The totals come in two sets, one per pass parity: each scatter zeroes the set the next
     pass's histogram adds into, so a pass needs no launch or fill of its own beyond its two.

   On NVIDIA's OpenCL a pass of the earlier scheme (one work item per tile counting every digit,
   then a chunked scan in two launches) was four launches, and the sort of 0.1 to 1 million keys
   took 1.2-1.6 ms against CUB's 0.07-0.10 ms, its time nearly independent of the key count.

   Buffer sort_histogram: counts [0, entries) at [digit * tile_count + tile], then the two sets
   of totals, each radix_totals_size entries: group totals [digit * groups + group], then the
   PM_SORT_RADIX digit totals. */
#ifndef PM_RADIX_SORT_H
#define PM_RADIX_SORT_H

#include "kernel_globals.h"

PM_DEVICE uint radix_digit(uint key, uint shift) { return (key >> shift) & (PM_SORT_RADIX - 1); }

PM_DEVICE uint radix_count_entries(const LaunchParams* p) { return PM_SORT_RADIX * p->sort_tile_count; }

PM_DEVICE uint radix_groups(const LaunchParams* p) { return (p->sort_tile_count + PM_SORT_GROUP - 1) / PM_SORT_GROUP; }

/* Entries of one set of totals: the group totals of every digit, then the digit totals. */
PM_DEVICE uint radix_totals_size(const LaunchParams* p) { return PM_SORT_RADIX * (radix_groups(p) + 1); }

/* The set of totals that pass `pass` (sort_shift / PM_SORT_RADIX_BITS) adds into and reads. */
PM_DEVICE uint radix_totals_base(const LaunchParams* p, uint pass)
{
  return radix_count_entries(p) + (pass & 1u) * radix_totals_size(p);
}

/* Entries [i, i + PM_SORT_BLOCK) of `from` below `end` into out, 0 past it. The loads go out
   together, so a work item waits on memory once per block rather than once per entry. */
#define PM_SORT_BLOCK 16u

PM_DEVICE void radix_load_block(PM_GLOBAL const uint* from, uint i, uint end, uint* out)
{
  for (uint j = 0; j < PM_SORT_BLOCK; ++j) out[j] = i + j < end ? PM_LOAD(&from[i + j]) : 0u;
}

/* Sum of from[begin, end). */
PM_DEVICE uint radix_sum(PM_GLOBAL const uint* from, uint begin, uint end)
{
  uint sum = 0;
  for (uint i = begin; i < end; i += PM_SORT_BLOCK) {
    uint block[PM_SORT_BLOCK];
    radix_load_block(from, i, end, block);
    for (uint j = 0; j < PM_SORT_BLOCK; ++j) sum += block[j];
  }
  return sum;
}

/* Work item = (tile, digit) lane: how many of the tile's keys have the lane's digit, stored and
   added to the digit's total and its group's. */
PM_DEVICE void kernel_sort_histogram(const KernelGlobals* kg, const LaunchParams* p, uint lane)
{
  uint tile = lane / PM_SORT_RADIX, digit = lane % PM_SORT_RADIX;
  uint begin = tile * PM_SORT_TILE;
  uint end = pm_min_u(begin + PM_SORT_TILE, p->sort_count);
  uint count = 0;
  for (uint i = begin; i < end; i += PM_SORT_BLOCK) {
    uint keys[PM_SORT_BLOCK];
    radix_load_block(kg->sort_keys, i, end, keys);
    for (uint j = 0; j < PM_SORT_BLOCK; ++j) count += i + j < end && radix_digit(keys[j], p->sort_shift) == digit;
  }
  kg->sort_histogram[digit * p->sort_tile_count + tile] = count;
  if (count == 0) return;
  uint totals = radix_totals_base(p, p->sort_shift / PM_SORT_RADIX_BITS), groups = radix_groups(p);
  pm_atomic_add_u32(&kg->sort_histogram[totals + digit * groups + tile / PM_SORT_GROUP], count);
  pm_atomic_add_u32(&kg->sort_histogram[totals + PM_SORT_RADIX * groups + digit], count);
}

/* Work item = (tile, digit) lane: moves the tile's keys of the lane's digit, in order, to
   sort_keys_alt / sort_values_alt; and zeroes the next pass's totals. */
PM_DEVICE void kernel_sort_scatter(const KernelGlobals* kg, const LaunchParams* p, uint lane)
{
  uint tile = lane / PM_SORT_RADIX, digit = lane % PM_SORT_RADIX;
  uint pass = p->sort_shift / PM_SORT_RADIX_BITS, groups = radix_groups(p), group = tile / PM_SORT_GROUP;
  uint totals = radix_totals_base(p, pass);
  PM_GLOBAL const uint* counts = kg->sort_histogram + digit * p->sort_tile_count;
  uint dst = radix_sum(kg->sort_histogram, totals + PM_SORT_RADIX * groups, totals + PM_SORT_RADIX * groups + digit) +
             radix_sum(kg->sort_histogram, totals + digit * groups, totals + digit * groups + group) +
             radix_sum(counts, group * PM_SORT_GROUP, tile);
  uint begin = tile * PM_SORT_TILE;
  uint end = pm_min_u(begin + PM_SORT_TILE, p->sort_count);
  for (uint i = begin; i < end; i += PM_SORT_BLOCK) {
    uint keys[PM_SORT_BLOCK], values[PM_SORT_BLOCK];
    radix_load_block(kg->sort_keys, i, end, keys);
    radix_load_block(kg->sort_values, i, end, values);
    for (uint j = 0; j < PM_SORT_BLOCK; ++j) {
      if (i + j >= end || radix_digit(keys[j], p->sort_shift) != digit) continue;
      kg->sort_keys_alt[dst] = keys[j];
      kg->sort_values_alt[dst] = values[j];
      ++dst;
    }
  }
  uint next = radix_totals_base(p, pass + 1u), size = radix_totals_size(p), lanes = radix_count_entries(p);
  for (uint z = lane; z < size; z += lanes) kg->sort_histogram[next + z] = 0u;
}

#endif

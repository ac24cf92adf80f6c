/* Host "backend" for the photon map kernels (kernels/common/photon_map.h), for the unit tests:
   runs every step's work-item function over all its items, in forward, reverse or shuffled
   order, exactly as a device launch would call it (one call per item, no shared state besides
   the buffers). The (code, index) sort is std::sort, standing in for the device library. */
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <utility>
#include <vector>

// clang-format off
#include "kernels/common/compat_host.h"
#include "kernels/common/vec3.h"
#include "kernels/common/types.h"
#include "kernels/common/photon_map.h"
#include "kernels/common/photon_map_query.h"
// clang-format on

namespace pm_photon_map_test {

enum class Order { kForward, kReverse, kRandom };

template <class F>
void run_items(uint count, Order order, uint32_t seed, F&& item)
{
  std::vector<uint> ids(count);
  std::iota(ids.begin(), ids.end(), 0u);
  if (order == Order::kReverse) std::reverse(ids.begin(), ids.end());
  if (order == Order::kRandom) std::shuffle(ids.begin(), ids.end(), std::mt19937(seed));
  for (uint i : ids) item(i);
}

struct HostPhotonMap {
  uint n = 0;
  uint threshold = 1;
  std::vector<uint> codes;         // sorted
  std::vector<uint> sorted_index;  // sorted position -> original hit
  std::vector<float4> sorted_lo, sorted_hi;
  std::vector<uint> node_parent, leaf_parent, visits;
  std::vector<float4> nodes;       // 4 per inner node
};

// Never written by a correct build: lets the tests see any slot the bottom-up pass missed.
constexpr uint kPoison = 0x7FBADBADu;

// Hits with their positions in place, as the gather data keeps them: position with PM_HIT_VALID
// in w (or 0: an empty slot), and the footprint area in w of the second array.
inline float4 valid_center(float4 p) { return PM_MAKE_FLOAT4(p.x, p.y, p.z, PM_UINT_AS_FLOAT(PM_HIT_VALID)); }

// The same hits as the trace leaves them (photon_trace.h): a word per slot (the flags and the
// index of the hit's record), the positions in records of `stride` float4 at offset
// PM_RECORD_POSITION, the records handed out in an order of their own (as an atomic counter
// would), and an empty slot's word 0.
struct SlotLayout {
  std::vector<uint> words;
  std::vector<float4> records;
  uint stride = PM_RECORD_FLOAT4S;
  const float4* positions() const { return records.data() + PM_RECORD_POSITION; }
};

inline SlotLayout slot_layout(const std::vector<float4>& centers, uint32_t seed)
{
  SlotLayout layout;
  std::vector<uint> valid;
  for (uint i = 0; i < (uint)centers.size(); ++i)
    if (PM_AS_UINT(centers[i].w) & PM_HIT_VALID) valid.push_back(i);
  std::vector<uint> record_of(valid.size());
  std::iota(record_of.begin(), record_of.end(), 0u);
  std::shuffle(record_of.begin(), record_of.end(), std::mt19937(seed));
  float poison = PM_UINT_AS_FLOAT(kPoison);
  layout.words.assign(centers.size(), 0u);
  layout.records.assign(layout.stride * valid.size(), PM_MAKE_FLOAT4(poison, poison, poison, poison));
  for (size_t k = 0; k < valid.size(); ++k) {
    const uint i = valid[k], r = record_of[k];
    layout.words[i] = (PM_AS_UINT(centers[i].w) & PM_HIT_SLOT_FLAGS) | (r << PM_HIT_RECORD_SHIFT);
    float4 c = centers[i];
    c.w = 0.0f;
    layout.records[layout.stride * r + PM_RECORD_POSITION] = c;
  }
  return layout;
}

// Step 1 as the pipeline runs it: one tile per work item, the partials combined on the host. The
// hits in place (`centers`), or in the trace's layout when `slots` is given (no areas there).
inline PhotonMapBounds reduce_bounds(const std::vector<float4>& centers, const std::vector<float4>& areas,
                                     std::vector<float4>* partials_out = nullptr, const SlotLayout* slots = nullptr)
{
  uint count = (uint)centers.size();
  uint tiles = photon_map_bounds_tile_count(count);
  std::vector<float4> partials(2 * (size_t)tiles);
  run_items(tiles, Order::kReverse, 0, [&](uint t) {
    if (slots)
      photon_map_bounds_tile(t, count, slots->words.data(), slots->positions(), slots->stride, nullptr,
                             partials.data());
    else
      photon_map_bounds_tile(t, count, nullptr, centers.data(), 1u, areas.data(), partials.data());
  });
  if (partials_out) *partials_out = partials;
  return photon_map_combine_partials(partials.data(), tiles);
}

// Step 2 as the pipeline runs it: the valid slots' keys, compacted per tile at the host-computed
// offsets, in any order of the tiles.
inline void morton_keys(const std::vector<float4>& centers, const std::vector<float4>& areas, Order order,
                        std::vector<uint>* codes, std::vector<uint>* slots, const SlotLayout* layout = nullptr)
{
  std::vector<float4> partials;
  PhotonMapBounds b = reduce_bounds(centers, areas, &partials, layout);
  uint count = (uint)centers.size();
  uint tiles = photon_map_bounds_tile_count(count);
  std::vector<uint> first_out(tiles);
  photon_map_tile_offsets(partials.data(), tiles, first_out.data());
  codes->assign(b.count, kPoison);
  slots->assign(b.count, kPoison);
  run_items(tiles, order, 5, [&](uint t) {
    if (layout)
      photon_map_morton_tile(t, count, layout->words.data(), layout->positions(), layout->stride, first_out.data(),
                             b.lo, b.hi, codes->data(), slots->data());
    else
      photon_map_morton_tile(t, count, nullptr, centers.data(), 1u, first_out.data(), b.lo, b.hi, codes->data(),
                             slots->data());
  });
}

inline void sort_pairs(std::vector<uint>* codes, std::vector<uint>* indices)
{
  std::vector<std::pair<uint, uint>> pairs(codes->size());
  for (size_t i = 0; i < pairs.size(); ++i) pairs[i] = {(*codes)[i], (*indices)[i]};
  std::sort(pairs.begin(), pairs.end());
  for (size_t i = 0; i < pairs.size(); ++i) {
    (*codes)[i] = pairs[i].first;
    (*indices)[i] = pairs[i].second;
  }
}

// Steps 4 and 5 from already sorted codes (lets tests build adversarial code sequences).
inline HostPhotonMap build_from_sorted(std::vector<uint> codes, std::vector<uint> sorted_index,
                                       const std::vector<float4>& lo, const std::vector<float4>& hi,
                                       uint threshold, Order order, uint32_t seed)
{
  HostPhotonMap m;
  m.n = (uint)codes.size();
  m.threshold = threshold;
  m.codes = std::move(codes);
  m.sorted_index = std::move(sorted_index);
  uint inner = m.n > 1 ? m.n - 1 : 0;
  float poison = PM_UINT_AS_FLOAT(kPoison);
  m.nodes.assign(4 * (size_t)inner, PM_MAKE_FLOAT4(poison, poison, poison, poison));
  m.node_parent.assign(inner, kPoison);
  m.leaf_parent.assign(m.n, kPoison);
  m.visits.assign(inner, 7u);  // step 4 must zero them
  m.sorted_lo.assign(m.n, PM_MAKE_FLOAT4(poison, poison, poison, poison));
  m.sorted_hi = m.sorted_lo;
  run_items(inner, order, seed, [&](uint i) {
    photon_map_build_node(i, m.n, m.codes.data(), m.node_parent.data(), m.leaf_parent.data(), m.visits.data());
  });
  // The footprint stage writes the boxes in sorted order (photon_footprint.h).
  for (uint k = 0; k < m.n; ++k) {
    m.sorted_lo[k] = lo[m.sorted_index[k]];
    m.sorted_hi[k] = hi[m.sorted_index[k]];
  }
  run_items(m.n, order, seed + 1, [&](uint k) {
    photon_map_bottom_up(k, m.n, threshold, m.sorted_lo.data(), m.sorted_hi.data(), m.node_parent.data(),
                         m.leaf_parent.data(), m.visits.data(), m.nodes.data());
  });
  return m;
}

// The whole stage S4 on the host.
inline HostPhotonMap build(const std::vector<float4>& positions, const std::vector<float4>& lo,
                           const std::vector<float4>& hi, uint threshold, Order order, uint32_t seed)
{
  uint n = (uint)positions.size();
  std::vector<float4> centers(n);
  for (uint i = 0; i < n; ++i) centers[i] = valid_center(positions[i]);
  std::vector<uint> codes, indices;
  morton_keys(centers, lo, order, &codes, &indices);
  sort_pairs(&codes, &indices);
  return build_from_sorted(std::move(codes), std::move(indices), lo, hi, threshold, order, seed + 2);
}

struct QueryResult {
  std::vector<uint> hits;  // original hit indices, in the order the iterator gave them
  uint nodes_visited = 0;
  uint overflows = 0;
};

inline QueryResult run_query(const HostPhotonMap& m, PhotonMapQuery* q)
{
  QueryResult r;
  for (int k; (k = photon_map_query_next(q, m.nodes.data(), m.sorted_lo.data(), m.sorted_hi.data())) >= 0;)
    r.hits.push_back(m.sorted_index[k]);
  r.nodes_visited = q->nodes_visited;
  r.overflows = q->overflows;
  return r;
}

inline QueryResult query(const HostPhotonMap& m, Vec3 x, uint stack_limit)
{
  PhotonMapQuery q;
  photon_map_query_begin(&q, x, m.n, stack_limit);
  return run_query(m, &q);
}

// The hits whose boxes meet [lo, hi], in the order the iterator gives them.
inline QueryResult query_box(const HostPhotonMap& m, Vec3 lo, Vec3 hi)
{
  PhotonMapQuery q;
  photon_map_query_begin_box(&q, lo, hi, m.n, PM_TRAVERSAL_STACK);
  return run_query(m, &q);
}

}  // namespace pm_photon_map_test

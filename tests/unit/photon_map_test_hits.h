// Photon hits and query points for the photon map's tests (photon_map_test.cpp and
// photon_map_query_test.cpp): random hits with boxes, the checks every built tree must pass, query
// points in and around the hits' boxes, and the brute-force answer a query must equal.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

#include "photon_map_host_driver.h"

namespace pm_photon_map_test {

struct Hits {
  std::vector<float4> pos, lo, hi;
};

// Random hits in [-1, 3]^3 with AABBs of half-size up to max_r per axis (some exactly points).
// grid > 0 snaps positions to grid^3 points, so many hits share a Morton code.
inline Hits make_hits(uint n, uint32_t seed, int grid, float max_r)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  Hits h;
  for (uint i = 0; i < n; ++i) {
    float c[3];
    for (float& v : c) v = grid > 0 ? -1.0f + 4.0f * (float)(rng() % grid) / (float)grid : -1.0f + 4.0f * u(rng);
    float r[3];
    bool point = rng() % 10 == 0;
    for (float& v : r) v = point ? 0.0f : max_r * u(rng);
    h.pos.push_back(PM_MAKE_FLOAT4(c[0], c[1], c[2], 0.0f));
    h.lo.push_back(PM_MAKE_FLOAT4(c[0] - r[0], c[1] - r[1], c[2] - r[2], 0.0f));
    h.hi.push_back(PM_MAKE_FLOAT4(c[0] + r[0], c[1] + r[1], c[2] + r[2], 0.0f));
  }
  return h;
}

inline uint w_bits(float4 v) { return PM_AS_UINT(v.w); }

// Walks the tree from the root and checks every property the traversal relies on.
struct TreeChecker {
  const HostPhotonMap& m;
  const Hits& h;
  std::vector<int> seen;
  uint max_depth = 0;
  uint leaves = 0;

  uint64_t key(uint k) const { return ((uint64_t)m.codes[k] << 32) | k; }

  // Exact union of the original hit boxes of sorted positions [first, first + count).
  void expect_box(float4 lo, float4 hi, uint first, uint count) const
  {
    Vec3 ulo = vec3_splat(INFINITY), uhi = vec3_splat(-INFINITY);
    for (uint k = first; k < first + count; ++k) {
      ulo = vec3_min(ulo, vec3_from_float4(h.lo[m.sorted_index[k]]));
      uhi = vec3_max(uhi, vec3_from_float4(h.hi[m.sorted_index[k]]));
    }
    ASSERT_TRUE(lo.x == ulo.x && lo.y == ulo.y && lo.z == ulo.z && hi.x == uhi.x && hi.y == uhi.y && hi.z == uhi.z)
        << "child box is not the union of its hits' AABBs, interval " << first << "+" << count;
  }

  // Returns the interval of the slot's subtree.
  std::pair<uint, uint> slot(uint node, uint side, uint parent_count, uint depth)
  {
    float4 lo = m.nodes[4 * node + 2 * side], hi = m.nodes[4 * node + 2 * side + 1];
    uint ref = w_bits(lo), count = w_bits(hi);
    std::pair<uint, uint> span;
    if (ref & PM_PHOTON_MAP_LEAF) {
      span = {ref & ~PM_PHOTON_MAP_LEAF, count};
      EXPECT_GE(count, 1u);
      EXPECT_LE(count, std::max(m.threshold, 1u)) << "leaf larger than T";
      if (node != 0) {
        EXPECT_GT(parent_count, m.threshold) << "leaf could have been fused with its sibling";
      }
      EXPECT_LE(span.first + count, m.n);
      for (uint k = span.first; k < span.first + count && k < m.n; ++k) seen[k]++;
      leaves++;
      max_depth = std::max(max_depth, depth + 1);
    } else {
      EXPECT_GT(count, m.threshold) << "inner child at or under T was not fused";
      EXPECT_LT(ref, m.n - 1);
      if (ref >= m.n - 1) return {0, 0};
      span = node_check(ref, depth + 1);
      EXPECT_EQ(span.second, count) << "stored count differs from the hits below";
      // Karras: inner node index = right end of a left child's range, left end of a right child's.
      EXPECT_EQ(ref, side == 0 ? span.first + span.second - 1 : span.first);
    }
    expect_box(lo, hi, span.first, span.second);
    return span;
  }

  std::pair<uint, uint> node_check(uint node, uint depth)
  {
    uint count = w_bits(m.nodes[4 * node + 1]) + w_bits(m.nodes[4 * node + 3]);
    std::pair<uint, uint> l = slot(node, 0, count, depth), r = slot(node, 1, count, depth);
    EXPECT_EQ(l.first + l.second, r.first) << "children not adjacent at node " << node;
    uint first = l.first, last = r.first + r.second - 1;
    // Independent top-down radix split: the first key with the range's highest differing bit set.
    if (last > first && last < m.n) {
      uint64_t diff = key(first) ^ key(last);
      uint64_t bit = 1ull << (63 - __builtin_clzll(diff));
      uint split = first;
      while (!(key(split + 1) & bit)) ++split;
      EXPECT_EQ(l.first + l.second - 1, split) << "split differs from the top-down radix split";
    }
    return {first, count};
  }

  void run()
  {
    seen.assign(m.n, 0);
    if (m.n < 2) return;
    std::pair<uint, uint> root = node_check(0, 0);
    EXPECT_EQ(root.first, 0u);
    EXPECT_EQ(root.second, m.n);
    for (uint k = 0; k < m.n; ++k) ASSERT_EQ(seen[k], 1) << "hit at sorted position " << k;
  }
};

inline std::vector<uint> brute_force(const Hits& h, Vec3 x)
{
  std::vector<uint> r;
  for (uint i = 0; i < h.lo.size(); ++i)
    if (h.lo[i].x <= x.x && h.lo[i].y <= x.y && h.lo[i].z <= x.z && x.x <= h.hi[i].x && x.y <= h.hi[i].y &&
        x.z <= h.hi[i].z)
      r.push_back(i);
  return r;
}

// Query points: random in and around the bounds, on faces / corners of hit boxes, far outside.
inline std::vector<Vec3> make_queries(const Hits& h, uint count, uint32_t seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Vec3> q;
  for (uint i = 0; i < count; ++i) {
    const uint hit = rng() % h.lo.size();
    const float4 lo = h.lo[hit], hi = h.hi[hit];
    switch (i % 4) {
      // Coordinates drawn in sequence, z first (as gcc evaluated the arguments when the expected
      // counts were set): the order of function arguments is unspecified and clang's differs.
      case 0: {
        const float z = u(rng), y = u(rng), x = u(rng);
        q.push_back(vec3(-1.5f + 5.0f * x, -1.5f + 5.0f * y, -1.5f + 5.0f * z));
        break;
      }
      case 1: {  // on a face: one coordinate snapped to lo or hi
        const float uz = u(rng), uy = u(rng), ux = u(rng);
        Vec3 x = vec3(lo.x + (hi.x - lo.x) * ux, lo.y + (hi.y - lo.y) * uy, lo.z + (hi.z - lo.z) * uz);
        float* c[3] = {&x.x, &x.y, &x.z};
        const float los[3] = {lo.x, lo.y, lo.z}, his[3] = {hi.x, hi.y, hi.z};
        uint axis = rng() % 3;
        *c[axis] = rng() % 2 ? los[axis] : his[axis];
        q.push_back(x);
        break;
      }
      case 2: q.push_back(rng() % 2 ? vec3(lo.x, lo.y, lo.z) : vec3(hi.x, hi.y, hi.z)); break;  // corners
      default: q.push_back(vec3(10.0f + u(rng), -7.0f, 0.5f)); break;                          // outside
    }
  }
  return q;
}

}  // namespace pm_photon_map_test

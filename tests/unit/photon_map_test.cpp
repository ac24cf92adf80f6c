// Stage S4 photon map LBVH (kernels/common/photon_map.h): bounds reduction, tree structure
// against an independent top-down radix split, bottom-up boxes and counts, leaf fusion under T,
// order independence of the bottom-up pass, and queries against brute force (incl. the stack
// overflow fallback). Built and run through the host driver in photon_map_host_driver.h.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>

#include "photon_map_host_driver.h"

namespace pm_photon_map_test {
namespace {

struct Hits {
  std::vector<float4> pos, lo, hi;
};

// Random hits in [-1, 3]^3 with AABBs of half-size up to max_r per axis (some exactly points).
// grid > 0 snaps positions to grid^3 points, so many hits share a Morton code.
Hits make_hits(uint n, uint32_t seed, int grid, float max_r)
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

uint w_bits(float4 v) { return PM_AS_UINT(v.w); }

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

void check_sorted_boxes(const HostPhotonMap& m, const Hits& h)
{
  for (uint k = 0; k < m.n; ++k) {
    ASSERT_EQ(0, memcmp(&m.sorted_lo[k], &h.lo[m.sorted_index[k]], 12));
    ASSERT_EQ(0, memcmp(&m.sorted_hi[k], &h.hi[m.sorted_index[k]], 12));
  }
}

std::vector<uint> brute_force(const Hits& h, Vec3 x)
{
  std::vector<uint> r;
  for (uint i = 0; i < h.lo.size(); ++i)
    if (h.lo[i].x <= x.x && h.lo[i].y <= x.y && h.lo[i].z <= x.z && x.x <= h.hi[i].x && x.y <= h.hi[i].y &&
        x.z <= h.hi[i].z)
      r.push_back(i);
  return r;
}

// Query points: random in and around the bounds, on faces / corners of hit boxes, far outside.
std::vector<Vec3> make_queries(const Hits& h, uint count, uint32_t seed)
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

// Returns the number of queries that needed the overflow fallback.
uint expect_queries_exact(const HostPhotonMap& m, const Hits& h, const std::vector<Vec3>& queries,
                          uint stack_limit)
{
  uint overflowed = 0;
  for (const Vec3& x : queries) {
    QueryResult r = query(m, x, stack_limit);
    std::vector<uint> got = r.hits;
    std::sort(got.begin(), got.end());
    EXPECT_TRUE(std::adjacent_find(got.begin(), got.end()) == got.end()) << "a hit was returned twice";
    EXPECT_EQ(got, brute_force(h, x)) << "query (" << x.x << ", " << x.y << ", " << x.z << "), n=" << m.n
                                      << " T=" << m.threshold << " stack " << stack_limit;
    if (got != brute_force(h, x)) return overflowed;  // one report per call is enough
    overflowed += r.overflows > 0;
  }
  return overflowed;
}

TEST(PhotonMapBounds, TilesGiveBoundsCountAndAreaOfValidHitsOnly)
{
  for (uint n : {1u, 255u, 256u, 257u, 513u, 70000u}) {
    Hits h = make_hits(n, 11 + n, 0, 0.1f);
    // Put the extremes at tile edges and ends, where an off-by-one in a tile's range shows.
    for (uint at : {0u, 255u, 256u, 511u, 512u, n - 1}) {
      if (at >= n) continue;
      std::vector<float4> centers(n), areas(n);
      for (uint i = 0; i < n; ++i) {
        centers[i] = valid_center(h.pos[i]);
        areas[i] = PM_MAKE_FLOAT4(0.0f, 0.0f, 0.0f, 0.25f * float(i % 7));
      }
      centers[at] = valid_center(PM_MAKE_FLOAT4(50.0f, -50.0f, 0.5f, 0.0f));
      centers[n - 1 - at].z = -60.0f;
      // Empty slots far outside, with an area: they must count for nothing.
      uint empty = 0;
      for (uint i = 3; i < n; i += 97, ++empty) {
        if (i == at || i == n - 1 - at) continue;
        centers[i] = PM_MAKE_FLOAT4(1e6f, 1e6f, -1e6f, PM_UINT_AS_FLOAT(0u));
      }
      PhotonMapBounds b = reduce_bounds(centers, areas);
      Vec3 elo = vec3_splat(INFINITY), ehi = vec3_splat(-INFINITY);
      double area = 0;
      uint count = 0;
      for (uint i = 0; i < n; ++i) {
        if ((PM_AS_UINT(centers[i].w) & PM_HIT_VALID) == 0u) continue;
        elo = vec3_min(elo, vec3_from_float4(centers[i]));
        ehi = vec3_max(ehi, vec3_from_float4(centers[i]));
        area += areas[i].w;
        ++count;
      }
      EXPECT_TRUE(b.lo.x == elo.x && b.lo.y == elo.y && b.lo.z == elo.z) << n << " at " << at;
      EXPECT_TRUE(b.hi.x == ehi.x && b.hi.y == ehi.y && b.hi.z == ehi.z) << n << " at " << at;
      EXPECT_EQ(b.count, count) << n << " at " << at;
      EXPECT_NEAR(b.area, area, 1e-6 * area + 1e-9) << n << " at " << at;
    }
  }
}

TEST(PhotonMapMorton, OnlyValidHitsGetKeysInSlotOrder)
{
  // Valid and empty slots mixed across tile edges: the keys of the valid ones, compacted, in slot
  // order whatever order the tiles run in.
  const uint n = 1000;
  Hits h = make_hits(n, 77, 0, 0.1f);
  std::vector<float4> centers(n), areas(n, PM_MAKE_FLOAT4(0.0f, 0.0f, 0.0f, 1.0f));
  std::vector<uint> expected_slots;
  for (uint i = 0; i < n; ++i) {
    const bool valid = (i * 7919u) % 5u != 0u && !(i >= 250 && i < 270);
    centers[i] = valid ? valid_center(h.pos[i]) : PM_MAKE_FLOAT4(9.0f, 9.0f, 9.0f, PM_UINT_AS_FLOAT(0u));
    if (valid) expected_slots.push_back(i);
  }
  for (Order order : {Order::kForward, Order::kReverse, Order::kRandom}) {
    std::vector<uint> codes, slots;
    morton_keys(centers, areas, order, &codes, &slots);
    EXPECT_EQ(slots, expected_slots);
    PhotonMapBounds b = reduce_bounds(centers, areas);
    for (size_t k = 0; k < slots.size(); ++k) {
      EXPECT_EQ(codes[k], photon_map_morton_key(centers[slots[k]], b.lo, b.hi));
      EXPECT_LT(codes[k], 1u << PM_MORTON_SORT_BITS);
    }
  }
}

// Steps 1 and 2 over the trace's hit slots (a word per slot, the position in a record taken in
// any order, photon_trace.h) give the bounds, counts, keys and slots of the same hits in place,
// bit for bit (the records' other float4 are poison: reading one would show).
TEST(PhotonMapMorton, HitSlotsAndRecordsGiveTheKeysOfTheHitsInPlace)
{
  for (uint n : {1u, 256u, 257u, 1000u, 70000u}) {
    Hits h = make_hits(n, 31 + n, n == 1000 ? 4 : 0, 0.1f);
    std::vector<float4> centers(n), areas(n, PM_MAKE_FLOAT4(0.0f, 0.0f, 0.0f, 0.0f));
    for (uint i = 0; i < n; ++i) {
      const bool valid = (i * 7919u) % 5u != 0u || n == 1;
      centers[i] = valid ? valid_center(h.pos[i]) : PM_MAKE_FLOAT4(0.0f, 0.0f, 0.0f, PM_UINT_AS_FLOAT(0u));
      if (valid && i % 3 == 1) centers[i].w = PM_UINT_AS_FLOAT(PM_HIT_VALID | PM_HIT_CAUSTIC);
    }
    const SlotLayout layout = slot_layout(centers, n);
    PhotonMapBounds in_place = reduce_bounds(centers, areas), slotted = reduce_bounds(centers, areas, nullptr, &layout);
    EXPECT_EQ(std::memcmp(&in_place.lo, &slotted.lo, sizeof(float4)), 0) << n;
    EXPECT_EQ(std::memcmp(&in_place.hi, &slotted.hi, sizeof(float4)), 0) << n;
    EXPECT_EQ(slotted.count, in_place.count) << n;
    ASSERT_GT(slotted.count, 0u);
    for (Order order : {Order::kForward, Order::kRandom}) {
      std::vector<uint> codes, slots, slotted_codes, slotted_slots;
      morton_keys(centers, areas, order, &codes, &slots);
      morton_keys(centers, areas, order, &slotted_codes, &slotted_slots, &layout);
      EXPECT_EQ(slotted_codes, codes) << n;
      EXPECT_EQ(slotted_slots, slots) << n;
    }
  }
}

// Step 4 alone: every hit and every inner node but the root has one parent, every inner node
// exactly one left and one right child (a broken split shows here, before the bottom-up pass
// would follow the bad links out of bounds).
TEST(PhotonMapTree, BuildLinksEveryChildOnce)
{
  for (uint n : {2u, 3u, 1000u, 50000u}) {
    Hits h = make_hits(n, 200 + n, n == 1000 ? 4 : 0, 0.05f);
    std::vector<uint> codes, index;
    std::vector<float4> centers(n);
    for (uint i = 0; i < n; ++i) centers[i] = valid_center(h.pos[i]);
    morton_keys(centers, h.pos, Order::kForward, &codes, &index);
    sort_pairs(&codes, &index);
    std::vector<uint> node_parent(n - 1, kPoison), leaf_parent(n, kPoison), visits(n - 1, 7u);
    run_items(n - 1, Order::kRandom, n, [&](uint i) {
      photon_map_build_node(i, n, codes.data(), node_parent.data(), leaf_parent.data(), visits.data());
    });
    std::vector<int> children(2 * (n - 1), 0);
    ASSERT_EQ(node_parent[0], PM_PHOTON_MAP_NO_PARENT);
    for (uint i = 1; i < n - 1; ++i) {
      ASSERT_LT(node_parent[i] >> 1, n - 1) << "inner node " << i << " has no parent";
      children[node_parent[i]]++;
    }
    for (uint k = 0; k < n; ++k) {
      ASSERT_LT(leaf_parent[k] >> 1, n - 1) << "leaf " << k << " has no parent";
      children[leaf_parent[k]]++;
    }
    for (uint c = 0; c < 2 * (n - 1); ++c) ASSERT_EQ(children[c], 1) << "node " << c / 2 << " side " << c % 2;
    for (uint v : visits) ASSERT_EQ(v, 0u);
  }
}

TEST(PhotonMapTree, StructureBoxesCountsAndFusion)
{
  for (uint n : {1u, 2u, 3u, 1000u, 50000u}) {
    for (int grid : {0, 6}) {  // 6^3 = 216 distinct positions: long runs of duplicate codes
      Hits h = make_hits(n, 100 + n + grid, grid, 0.05f);
      for (uint T : {1u, 2u, 4u, 32u}) {
        SCOPED_TRACE(::testing::Message() << "n=" << n << " grid=" << grid << " T=" << T);
        HostPhotonMap m = build(h.pos, h.lo, h.hi, T, Order::kRandom, 7 * n + T);
        ASSERT_TRUE(std::is_sorted(m.codes.begin(), m.codes.end()));
        check_sorted_boxes(m, h);
        TreeChecker c{m, h, {}};
        c.run();
        if (n >= 2 && T == 1) {
          EXPECT_EQ(c.leaves, n) << "T = 1 must not fuse";
        }
        if (n >= 1000 && T > 1) {
          EXPECT_GT((double)n / c.leaves, 0.5 * T) << "threshold fused too little";
        }
        if (n >= 1000) {
          EXPECT_LE(c.max_depth, 62u);
        }
      }
    }
  }
}

TEST(PhotonMapTree, BottomUpIndependentOfWorkItemOrder)
{
  for (uint n : {2u, 3u, 1000u, 50000u}) {
    Hits h = make_hits(n, 300 + n, n == 50000 ? 6 : 0, 0.05f);
    for (uint T : {1u, 8u}) {
      HostPhotonMap fwd = build(h.pos, h.lo, h.hi, T, Order::kForward, 1);
      HostPhotonMap rev = build(h.pos, h.lo, h.hi, T, Order::kReverse, 1);
      HostPhotonMap rnd = build(h.pos, h.lo, h.hi, T, Order::kRandom, 99);
      size_t bytes = fwd.nodes.size() * sizeof(float4);
      EXPECT_EQ(0, memcmp(fwd.nodes.data(), rev.nodes.data(), bytes)) << n;
      EXPECT_EQ(0, memcmp(fwd.nodes.data(), rnd.nodes.data(), bytes)) << n;
      for (const float4& v : fwd.nodes) ASSERT_NE(PM_AS_UINT(v.w), kPoison) << "slot never written";
      for (uint v : fwd.visits) ASSERT_EQ(v, 2u) << "every inner node is reached by both children";
    }
  }
}

TEST(PhotonMapQuery, EqualsBruteForce)
{
  for (uint n : {1u, 2u, 3u, 1000u, 50000u}) {
    Hits h = make_hits(n, 500 + n, n == 1000 ? 5 : 0, n >= 1000 ? 0.08f : 1.0f);
    std::vector<Vec3> queries = make_queries(h, n == 50000 ? 400 : 200, n);
    for (uint T : {1u, 4u, 32u}) {
      HostPhotonMap m = build(h.pos, h.lo, h.hi, T, Order::kRandom, n + T);
      EXPECT_EQ(expect_queries_exact(m, h, queries, PM_TRAVERSAL_STACK), 0u);
    }
  }
}

// The gather's pixel tiles (kernels/common/gather_tiles.h) walk the map with their points' box and
// keep, at each point, the hits whose own box holds it: that must be the point query's hits in
// the point query's order, for the sums to be the same bits. Boxes from a point (empty extent) to
// the whole map, some with a face on a hit box's face.
TEST(PhotonMapQuery, ABoxQueryKeptAtAPointIsThatPointsQueryInItsOrder)
{
  std::mt19937 rng(4242);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (uint n : {2u, 3u, 1000u, 50000u}) {
    Hits h = make_hits(n, 700 + n, n == 1000 ? 5 : 0, n >= 1000 ? 0.08f : 1.0f);
    std::vector<Vec3> points = make_queries(h, n == 50000 ? 150 : 100, n + 1);
    for (uint T : {1u, 4u, 32u}) {
      HostPhotonMap m = build(h.pos, h.lo, h.hi, T, Order::kRandom, n + T + 5);
      for (size_t i = 0; i < points.size(); ++i) {
        const Vec3 x = points[i];
        const float reach = (i % 4 == 0) ? 0.0f : (i % 4 == 1) ? 0.02f : (i % 4 == 2) ? 0.3f : 6.0f;
        const Vec3 lo = vec3(x.x - reach * u(rng), x.y - reach * u(rng), x.z - reach * u(rng));
        const Vec3 hi = vec3(x.x + reach * u(rng), x.y + reach * u(rng), x.z + reach * u(rng));
        const std::vector<uint> met = query_box(m, lo, hi).hits;
        std::vector<uint> sorted_met = met, expected_met;
        std::sort(sorted_met.begin(), sorted_met.end());
        for (uint k = 0; k < n; ++k)
          if (h.lo[k].x <= hi.x && lo.x <= h.hi[k].x && h.lo[k].y <= hi.y && lo.y <= h.hi[k].y &&
              h.lo[k].z <= hi.z && lo.z <= h.hi[k].z)
            expected_met.push_back(k);
        ASSERT_EQ(sorted_met, expected_met) << "the box query's hits, n=" << n << " T=" << T << " point " << i;
        std::vector<uint> kept;
        for (uint k : met)
          if (photon_map_box_contains(h.lo[k], h.hi[k], x)) kept.push_back(k);
        ASSERT_EQ(kept, query(m, x, PM_TRAVERSAL_STACK).hits) << "n=" << n << " T=" << T << " point " << i;
      }
    }
  }
}

TEST(PhotonMapQuery, PrunesTheTree)
{
  Hits h = make_hits(50000, 77, 0, 0.05f);
  HostPhotonMap m = build(h.pos, h.lo, h.hi, 1, Order::kForward, 0);
  double visited = 0;
  std::vector<Vec3> queries = make_queries(h, 400, 78);
  for (const Vec3& x : queries) visited += query(m, x, PM_TRAVERSAL_STACK).nodes_visited;
  EXPECT_LT(visited / queries.size(), 500.0) << "traversal visits most of the 49999 nodes";
}

TEST(PhotonMapQuery, AllHitsAtOnePointAndFlatBounds)
{
  const uint n = 3000;
  Hits h = make_hits(n, 21, 0, 0.3f);
  for (uint i = 0; i < n; ++i) {  // one position; boxes of all sizes around it, some points
    float4 d = PM_MAKE_FLOAT4(h.pos[i].x - 1.0f, h.pos[i].y - 1.0f, h.pos[i].z - 1.0f, 0.0f);
    h.pos[i] = PM_MAKE_FLOAT4(1.0f, 1.0f, 1.0f, 0.0f);
    h.lo[i] = PM_MAKE_FLOAT4(1.0f - std::fabs(d.x) * 0.1f, 1.0f - std::fabs(d.y) * 0.1f, 1.0f, 0.0f);
    h.hi[i] = PM_MAKE_FLOAT4(1.0f + std::fabs(d.z) * 0.1f, 1.0f, 1.0f + std::fabs(d.x) * 0.1f, 0.0f);
  }
  std::vector<Vec3> queries = make_queries(h, 300, 5);
  queries.push_back(vec3(1.0f, 1.0f, 1.0f));
  for (uint T : {1u, 4u, 32u}) {
    HostPhotonMap m = build(h.pos, h.lo, h.hi, T, Order::kReverse, T);
    for (uint c : m.codes) ASSERT_EQ(c, 0u);
    TreeChecker c{m, h, {}};
    c.run();
    EXPECT_EQ(expect_queries_exact(m, h, queries, PM_TRAVERSAL_STACK), 0u);
    EXPECT_EQ(query(m, vec3(1.0f, 1.0f, 1.0f), PM_TRAVERSAL_STACK).hits.size(), n);
  }
  // Flat along z: every position in one plane.
  Hits f = make_hits(2000, 22, 0, 0.1f);
  for (float4& p : f.pos) p.z = 0.25f;
  HostPhotonMap m = build(f.pos, f.lo, f.hi, 4, Order::kRandom, 3);
  TreeChecker c{m, f, {}};
  c.run();
  expect_queries_exact(m, f, make_queries(f, 200, 6), PM_TRAVERSAL_STACK);
}

// Deepest trees the code space allows: a chain of codes 0, 1, 2, 4, ..., 2^29 (one new level per
// bit) hanging off a long run of duplicate code 0 (index bits add more levels). The tree stays
// under 62 inner levels, so the full stack never overflows; smaller stack limits force the
// fallback, which must stay exact.
TEST(PhotonMapQuery, StackOverflowFallbackIsExact)
{
  const uint dup = 4096;
  std::vector<uint> codes(dup, 0u);
  for (uint b = 0; b < 30; ++b) codes.push_back(1u << b);
  for (uint b = 1; b < 30; ++b) codes.push_back((1u << b) | 1u);  // a second chain, interleaved
  std::sort(codes.begin(), codes.end());
  const uint n = (uint)codes.size();
  Hits h = make_hits(n, 31, 0, 2.0f);  // large boxes: many hits contain each query point
  std::vector<uint> index(n);
  std::iota(index.begin(), index.end(), 0u);
  std::vector<Vec3> queries = make_queries(h, 120, 32);
  for (uint T : {1u, 4u}) {
    HostPhotonMap m = build_from_sorted(codes, index, h.lo, h.hi, T, Order::kRandom, T);
    TreeChecker c{m, h, {}};
    c.run();
    if (T == 1) {
      EXPECT_GE(c.max_depth, 40u);
    }
    EXPECT_LE(c.max_depth, 62u);
    EXPECT_EQ(expect_queries_exact(m, h, queries, PM_TRAVERSAL_STACK), 0u);
    for (uint limit : {0u, 1u, 2u, 3u, 8u, 20u}) {
      SCOPED_TRACE(::testing::Message() << "T=" << T << " stack limit " << limit);
      uint overflowed = expect_queries_exact(m, h, queries, limit);
      if (limit <= 8) {
        EXPECT_GT(overflowed, 0u) << "fallback never exercised";
      }
    }
  }
  // Random data, tiny stacks.
  Hits r = make_hits(5000, 33, 0, 0.3f);
  HostPhotonMap m = build(r.pos, r.lo, r.hi, 1, Order::kForward, 0);
  for (uint limit : {1u, 2u, 4u}) EXPECT_GT(expect_queries_exact(m, r, make_queries(r, 100, 34), limit), 0u);
}

TEST(PhotonMapAutoLeafSize, RoundsRatioAndGuards)
{
  EXPECT_EQ(photon_map_auto_leaf_size(0.0f, 10.0f, 5.0f), 1u);
  EXPECT_EQ(photon_map_auto_leaf_size(2.0f, 10.0f, 5.0f), 1u);    // 1.0
  EXPECT_EQ(photon_map_auto_leaf_size(10.0f, 10.0f, 4.4f), 4u);   // 4.4
  EXPECT_EQ(photon_map_auto_leaf_size(10.0f, 10.0f, 4.6f), 5u);   // 4.6
  EXPECT_EQ(photon_map_auto_leaf_size(300.0f, 4.0f, 0.56f), 42u); // 42.0
  EXPECT_EQ(photon_map_auto_leaf_size(1.0f, 0.0f, 1.0f), 1u);     // no scene area
  EXPECT_EQ(photon_map_auto_leaf_size(NAN, 1.0f, 1.0f), 1u);
  EXPECT_EQ(photon_map_auto_leaf_size(1.0f, -1.0f, -1.0f), 1u);
  EXPECT_EQ(photon_map_auto_leaf_size(1e30f, 1e-30f, 1.0f), 1u << 30);  // ratio overflows to inf
  EXPECT_EQ(photon_map_auto_leaf_size(1e20f, 1.0f, 1.0f), 1u << 30);
}

}  // namespace
}  // namespace pm_photon_map_test

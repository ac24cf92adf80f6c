// Stage S4 photon map LBVH (kernels/common/photon_map.h): bounds reduction, tree structure
// against an independent top-down radix split, bottom-up boxes and counts, leaf fusion under T,
// order independence of the bottom-up pass, and the automatic leaf size (the queries:
// photon_map_query_test.cpp). Built and run through the host driver in photon_map_host_driver.h.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>

#include "photon_map_host_driver.h"
#include "photon_map_test_hits.h"

namespace pm_photon_map_test {
namespace {

void check_sorted_boxes(const HostPhotonMap& m, const Hits& h)
{
  for (uint k = 0; k < m.n; ++k) {
    ASSERT_EQ(0, memcmp(&m.sorted_lo[k], &h.lo[m.sorted_index[k]], 12));
    ASSERT_EQ(0, memcmp(&m.sorted_hi[k], &h.hi[m.sorted_index[k]], 12));
  }
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

TEST(PhotonMapAutoLeafSize, HeldWithinTheBoundsOfHowTheMapIsWalked)
{
  const uint32_t most = 1u << 30;
  EXPECT_EQ(photon_map_leaf_size_within(9u, PM_TILE_WALK_LEAF_MIN, PM_TILE_WALK_LEAF_MAX), 16u);   // Sponza, 1080p
  EXPECT_EQ(photon_map_leaf_size_within(23u, PM_TILE_WALK_LEAF_MIN, PM_TILE_WALK_LEAF_MAX), 23u);  // Sibenik
  EXPECT_EQ(photon_map_leaf_size_within(120u, PM_TILE_WALK_LEAF_MIN, PM_TILE_WALK_LEAF_MAX), 32u); // Conference
  EXPECT_EQ(photon_map_leaf_size_within(most, PM_TILE_WALK_LEAF_MIN, PM_TILE_WALK_LEAF_MAX), 32u);
  EXPECT_EQ(photon_map_leaf_size_within(1u, PM_RAY_HIT_WALK_LEAF_MIN, most), 8u);  // final gathering's map
  EXPECT_EQ(photon_map_leaf_size_within(40u, PM_RAY_HIT_WALK_LEAF_MIN, most), 40u);
  EXPECT_EQ(photon_map_leaf_size_within(1u, 1u, most), 1u);  // the paper's T_auto (CPUs)
}

}  // namespace
}  // namespace pm_photon_map_test

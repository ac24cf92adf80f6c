// The photon map's queries (kernels/common/photon_map_query.h) against brute force: point queries
// over maps of many sizes and leaf thresholds, box queries kept at a point (the gather's pixel
// tiles), pruning, degenerate maps, and the stack overflow fallback. Built and run through the
// host driver in photon_map_host_driver.h.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <numeric>
#include <random>

#include "photon_map_host_driver.h"
#include "photon_map_test_hits.h"

namespace pm_photon_map_test {
namespace {

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

}  // namespace
}  // namespace pm_photon_map_test

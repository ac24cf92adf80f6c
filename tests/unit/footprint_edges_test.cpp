// The footprint stage's two launches (kernels/common/photon_footprint.h), run on the host with the
// scene BVH the device uses: the first pattern's launch lists the footprints it finds partly
// covered and leaves them to the edge pattern's launch. On a 2 x 2 m table top, a footprint in
// the middle covers its disc, one centred on the rim half of it and one on a corner a quarter,
// and every footprint is written once, by one of the two launches.
#include "kernels/common/compat_host.h"
#include "kernels/common/photon_footprint.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "support/host_scene.h"
#include "support/room_scenes.h"

namespace pm {
namespace {

constexpr float kRadius = 0.2f;  // the radius estimator's sphere: a disc on the table's plane

struct Hits {
  std::vector<float4> position, normal, incident, flux, dp;
  std::vector<uint> sorted;
  void add(float x, float z) {
    const float flags = PM_UINT_AS_FLOAT(PM_HIT_VALID);
    position.push_back(PM_MAKE_FLOAT4(x, 0.0f, z, flags));
    normal.push_back(PM_MAKE_FLOAT4(0.0f, 1.0f, 0.0f, flags));
    incident.push_back(PM_MAKE_FLOAT4(0.0f, 1.0f, 0.0f, 0.0f));
    flux.push_back(PM_MAKE_FLOAT4(1.0f, 1.0f, 1.0f, 0.0f));
    dp.push_back(PM_MAKE_FLOAT4(0.0f, 0.0f, 0.0f, 0.0f));
    sorted.push_back(uint(sorted.size()));
  }
};

struct FootprintStage {
  test::HostScene scene;
  LaunchParams p{};
  std::vector<float4> lo, hi, center, row_u, row_v, row_n, cut, power, incident_out;
  std::vector<uint> edges;
  uint edge_count = 0;

  FootprintStage(const Scene& s, Hits& h) : scene(s) {
    const size_t n = h.sorted.size();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (auto* v : {&lo, &hi, &center, &row_u, &row_v, &row_n, &cut, &power, &incident_out})
      v->assign(n, PM_MAKE_FLOAT4(nan, nan, nan, nan));
    edges.assign(n, 0xFFFFFFFFu);
    KernelGlobals& kg = scene.kg;
    kg.hit_position = h.position.data();
    kg.hit_normal = h.normal.data();
    kg.hit_incident = h.incident.data();
    kg.hit_flux = h.flux.data();
    kg.hit_dp_u = h.dp.data();
    kg.hit_dp_v = h.dp.data();
    kg.sorted_slots = h.sorted.data();
    kg.map_lo = lo.data();
    kg.map_hi = hi.data();
    kg.map_center = center.data();
    kg.map_row_u = row_u.data();
    kg.map_row_v = row_v.data();
    kg.map_row_n = row_n.data();
    kg.map_cut = cut.data();
    kg.map_power = power.data();
    kg.map_incident = incident_out.data();
    kg.map_edges = edges.data();
    kg.map_edge_count = &edge_count;
    p.estimator = PM_ESTIMATOR_RADIUS;
    p.gather_radius = kRadius;
    p.rmax = 1.0f;
    p.footprint_scale = 1.0f;
    p.footprint_clip = 1;
    p.footprint_coverage = 1;
    p.kernel_shape = PM_KERNEL_CONSTANT;
    p.ray_epsilon = 1e-5f;
    p.hit_slots_per_photon = 1;
    p.seed = 7;
    p.hit_count = uint(n);
  }

  // The stage as the host runs it: the first launch over every hit, then the edge launch over
  // every hit (items past the list's length do nothing).
  void run() {
    const uint n = p.hit_count;
    for (uint k = 0; k < n; ++k) kernel_photon_footprint(&scene.kg, &p, k);
    for (uint i = 0; i < n; ++i) kernel_photon_footprint_edges(&scene.kg, &p, i);
  }
};

Scene table_top() {
  Scene s;
  s.name = "table-top";
  s.source = "test";
  s.materials = {test::diffuse_material("white", {0.7f, 0.7f, 0.7f})};
  test::add_quad(s, {-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1});
  return s;
}

TEST(FootprintEdges, PartlyCoveredFootprintsAreMeasuredByTheEdgeLaunch) {
  Hits hits;
  hits.add(0.0f, 0.0f);    // 0: in the middle: its whole disc on the table
  hits.add(1.0f, 0.0f);    // 1: centred on the rim: half of it
  hits.add(1.0f, 1.0f);    // 2: on a corner: a quarter
  hits.add(-0.5f, 0.3f);   // 3: inside, a radius from every rim
  for (int i = 0; i < 24; ++i) hits.add(-1.0f + 0.09f * float(i), i % 2 ? 0.95f : -0.9f);  // along two rims
  FootprintStage stage(table_top(), hits);
  stage.run();

  // Every footprint was written, by one launch or the other.
  for (size_t k = 0; k < hits.sorted.size(); ++k) {
    ASSERT_TRUE(std::isfinite(stage.power[k].x)) << "footprint " << k << " was not written";
    ASSERT_TRUE(std::isfinite(stage.row_n[k].w)) << "footprint " << k;
  }
  // The list holds each partly covered footprint once: 1 and 2, not 0 and 3.
  std::vector<int> listed(hits.sorted.size(), 0);
  ASSERT_GT(stage.edge_count, 2u);
  ASSERT_LT(stage.edge_count, hits.sorted.size());
  for (uint i = 0; i < stage.edge_count; ++i) ++listed[stage.edges[i]];
  for (int count : listed) EXPECT_LE(count, 1);
  EXPECT_EQ(listed[0], 0);
  EXPECT_EQ(listed[1], 1);
  EXPECT_EQ(listed[2], 1);
  EXPECT_EQ(listed[3], 0);

  // Flux over the covered area: the disc's area in the middle, half of it on the rim, a quarter
  // on the corner (64 probes: a few per cent of quantisation).
  const float whole = 1.0f / (float(M_PI) * kRadius * kRadius);
  EXPECT_NEAR(stage.power[0].x, whole, 1e-4f * whole);
  EXPECT_NEAR(stage.power[3].x, whole, 1e-4f * whole);
  EXPECT_NEAR(stage.power[1].x / whole, 2.0f, 0.1f);
  EXPECT_NEAR(stage.power[2].x / whole, 4.0f, 0.3f);
}

TEST(FootprintEdges, WithoutCoverageNothingIsListed) {
  Hits hits;
  hits.add(1.0f, 0.0f);
  hits.add(0.0f, 0.0f);
  FootprintStage stage(table_top(), hits);
  stage.p.footprint_coverage = 0;
  stage.run();
  EXPECT_EQ(stage.edge_count, 0u);
  const float whole = 1.0f / (float(M_PI) * kRadius * kRadius);
  EXPECT_NEAR(stage.power[0].x, whole, 1e-4f * whole);
  EXPECT_NEAR(stage.power[1].x, whole, 1e-4f * whole);
}

}  // namespace
}  // namespace pm

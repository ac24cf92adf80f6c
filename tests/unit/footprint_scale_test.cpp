// Unit tests of the automatic smoothing (kernels/common/footprint_scale.h, render/
// footprint_scale.h): the per-tile reduction of the s = 1 footprint area against an independent
// double-precision sum, and the chosen s giving the batch's diffuse footprints a total area of
// overlap x scene area, growing as k^(3/4) when the scene grows by k.
#include "kernels/common/compat_host.h"
#include "kernels/common/footprint_scale.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "render/footprint_scale.h"

namespace pm {
namespace {

// A batch of hits held on the host, with the kernel's view of them: per slot a word of the flags
// and the index of the hit's record; the records in the reverse of slot order, as an atomic
// counter may hand them out (photon_trace.h).
struct HostHits {
  std::vector<uint32_t> slot_words;
  std::vector<float4> incident, dp_u, dp_v, records, partials;
  LaunchParams params{};
  KernelGlobals kg{};

  uint32_t record(size_t slot) const { return uint32_t(slot_words.size() - 1 - slot); }

  HostHits(uint32_t photons, uint32_t slots_per_photon, uint32_t seed, float scale) {
    const uint32_t slots = photons * slots_per_photon;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    slot_words.resize(slots);
    incident.resize(slots);
    dp_u.resize(slots);
    dp_v.resize(slots);
    for (uint32_t i = 0; i < slots; ++i) {
      uint32_t flags = i % 7 == 3 ? 0u : PM_HIT_VALID;  // some empty slots
      if (i % 11 == 5) flags |= PM_HIT_CAUSTIC;          // some caustic hits
      const uint32_t r = record(i);
      slot_words[i] = flags | (r << PM_HIT_RECORD_SHIFT);
      incident[r] = {0, 0, 1, 0.01f + 0.001f * float(i % 5)};  // w: Delta
      dp_u[r] = {scale * u(rng), scale * u(rng), 0, 0};
      dp_v[r] = {scale * u(rng), scale * u(rng), 0, 0};
    }
    // The kernel's records: five float4 side by side (PM_RECORD_*, kernels/common/types.h).
    records.resize(size_t(PM_RECORD_FLOAT4S) * slots);
    for (uint32_t r = 0; r < slots; ++r) {
      records[PM_RECORD_FLOAT4S * r + PM_RECORD_INCIDENT] = incident[r];
      records[PM_RECORD_FLOAT4S * r + PM_RECORD_DP_U] = dp_u[r];
      records[PM_RECORD_FLOAT4S * r + PM_RECORD_DP_V] = dp_v[r];
    }
    // As the photon map allocates it: two float4 per tile of the bounds reduction.
    partials.resize(2 * ((slots + PM_PHOTON_MAP_BOUNDS_TILE - 1) / PM_PHOTON_MAP_BOUNDS_TILE));
    params.photon_count = photons;
    params.hit_slots_per_photon = slots_per_photon;
    kg.hit_slots = slot_words.data();
    kg.hit_records = records.data();
    kg.map_partials = partials.data();
  }

  // The batch's s = 1 area as the host sums the kernel's tiles, which fit in the partials.
  double kernel_area() {
    const uint32_t tiles = footprint_scale_tile_count(uint32_t(slot_words.size()));
    EXPECT_LE(tiles, 4 * partials.size());
    for (uint32_t t = 0; t < tiles; ++t) kernel_photon_footprint_scale(&kg, &params, t);
    return footprint_scale_tile_sum(reinterpret_cast<const float*>(partials.data()), tiles);
  }

  // Independent: pi Delta^2 |dp_u|^(1/4) |dp_v|^(1/4) sin(angle) over valid diffuse hits, in double.
  double reference_area() const {
    double sum = 0;
    for (size_t i = 0; i < slot_words.size(); ++i) {
      const uint32_t flags = slot_words[i];
      if (!(flags & PM_HIT_VALID) || (flags & PM_HIT_CAUSTIC)) continue;
      const uint32_t r = record(i);
      const double ax = dp_u[r].x, ay = dp_u[r].y, bx = dp_v[r].x, by = dp_v[r].y;
      const double la = std::hypot(ax, ay), lb = std::hypot(bx, by);
      const double sine = std::fabs(ax * by - ay * bx) / (la * lb);
      const double delta = incident[r].w;
      sum += M_PI * delta * delta * std::pow(la, 0.25) * std::pow(lb, 0.25) * sine;
    }
    return sum;
  }

  // Total area of the batch's diffuse footprints at smoothing s, unclamped, as S3 builds them.
  double footprint_area_at(float s) const {
    double sum = 0;
    for (size_t i = 0; i < slot_words.size(); ++i) {
      const uint32_t flags = slot_words[i];
      if (!(flags & PM_HIT_VALID) || (flags & PM_HIT_CAUSTIC)) continue;
      const uint32_t r = record(i);
      Footprint f = footprint_from_differentials(vec3_from_float4(dp_u[r]), vec3_from_float4(dp_v[r]), vec3(0, 0, 1),
                                                 incident[r].w, s, 1e30f, 0);
      sum += footprint_area(f);
    }
    return sum;
  }
};

TEST(AutoSmoothing, TileReductionMatchesAnIndependentSum) {
  HostHits hits(700, 4, 1, 0.3f);  // 2800 slots: 88 tiles, the last one partial
  EXPECT_NEAR(hits.kernel_area() / hits.reference_area(), 1.0, 1e-5);
}

TEST(AutoSmoothing, FootprintsCoverTheSceneOverlapTimes) {
  const double scene_area = 37.5;
  HostHits hits(700, 4, 2, 0.3f);
  const float s = auto_smoothing(hits.kernel_area(), scene_area);
  EXPECT_NEAR(hits.footprint_area_at(s) / (kAutoSmoothingOverlap * scene_area), 1.0, 1e-4);
}

TEST(AutoSmoothing, GrowsAsTheScenesSizeToTheThreeQuarters) {
  // Positional differentials grow as k with the scene, its area as k^2: s must grow as k^(3/4),
  // so that footprint radii s Delta L^(1/4) grow as k.
  const double area1 = 37.5;
  HostHits unit(500, 4, 3, 0.3f);
  const float s1 = auto_smoothing(unit.kernel_area(), area1);
  for (float k : {1e-4f, 1e-2f, 1e2f, 1e4f, 1e6f}) {
    HostHits big(500, 4, 3, 0.3f * k);
    const float s = auto_smoothing(big.kernel_area(), area1 * double(k) * k);
    EXPECT_NEAR(s / s1 / std::pow(double(k), 0.75), 1.0, 1e-4) << k;
  }
}

TEST(AutoSmoothing, NoDiffuseAreaGivesAFiniteFactor) {
  for (double area : {0.0, -1.0, double(NAN), double(INFINITY)}) EXPECT_EQ(auto_smoothing(area, 10.0), 1.0f);
  EXPECT_EQ(auto_smoothing(1.0, 0.0), 1.0f);
}

}  // namespace
}  // namespace pm

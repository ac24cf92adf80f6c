// Coherent stratified emission (kernels/common/emission_order.h): the Hilbert curve visits every
// cell once through neighbours, each photon stays in its stratum, the photons of a pass are
// uniform over the square of emission parameters, and a warp's photons leave close together.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <vector>

// clang-format off
#include "kernels/common/compat_host.h"
#include "kernels/common/emission_order.h"
// clang-format on

namespace {

TEST(EmissionOrder, HilbertCurveVisitsEveryCellOnceThroughNeighbours) {
  for (uint levels : {1u, 3u, PM_HILBERT_LEVELS}) {
    const uint side = 1u << levels;
    std::vector<char> seen(size_t(side) * side, 0);
    uint px = 0, py = 0;
    for (uint d = 0; d < side * side; ++d) {
      uint x, y;
      hilbert_cell(d, levels, &x, &y);
      ASSERT_LT(x, side);
      ASSERT_LT(y, side);
      ASSERT_EQ(seen[size_t(y) * side + x]++, 0) << "cell visited twice, level " << levels;
      if (d > 0) {
        ASSERT_EQ(std::abs(int(x) - int(px)) + std::abs(int(y) - int(py)), 1) << "a jump at " << d;
      }
      px = x;
      py = y;
    }
  }
}

TEST(EmissionOrder, PhotonsAreUniformAndStratified) {
  std::mt19937 rng(3);
  for (uint n : {1u, 7u, 1000u, 262144u}) {
    // Uniform: counts per cell of an 8 x 8 grid over many passes (fresh random words each).
    const int grid = 8, passes = n < 1000 ? 20000 / n + 1 : 2;
    std::vector<double> counts(grid * grid, 0.0);
    double total = 0;
    for (int pass = 0; pass < passes; ++pass)
      for (uint i = 0; i < n; ++i) {
        float u, v;
        stratified_emission(i, n, rng(), rng(), rng(), &u, &v);
        ASSERT_GE(u, 0.0f);
        ASSERT_LT(u, 1.0f);
        ASSERT_GE(v, 0.0f);
        ASSERT_LT(v, 1.0f);
        counts[size_t(int(v * grid) * grid + int(u * grid))] += 1;
        total += 1;
      }
    double chi2 = 0;
    for (double c : counts) chi2 += (c - total / counts.size()) * (c - total / counts.size()) / (total / counts.size());
    EXPECT_LT(chi2, 120.0) << "n = " << n << ": 63 degrees of freedom, chi^2 " << chi2;  // p ~ 1e-5
  }
}

TEST(EmissionOrder, AWarpsPhotonsLeaveCloseTogether) {
  // 32 consecutive photons of a million: their parameters span a small patch, where independent
  // uniform photons would span most of the square.
  std::mt19937 rng(5);
  const uint n = 1u << 20;
  double spread = 0;
  int warps = 0;
  for (uint first = 0; first < n; first += 32 * 997, ++warps) {
    float lo_u = 1, hi_u = 0, lo_v = 1, hi_v = 0;
    for (uint i = first; i < first + 32 && i < n; ++i) {
      float u, v;
      stratified_emission(i, n, rng(), rng(), rng(), &u, &v);
      lo_u = std::min(lo_u, u), hi_u = std::max(hi_u, u), lo_v = std::min(lo_v, v), hi_v = std::max(hi_v, v);
    }
    spread += (hi_u - lo_u) * (hi_v - lo_v);
  }
  EXPECT_LT(spread / warps, 1e-3) << "mean area of a warp's bounding box in the unit square";
}

}  // namespace

// The levelled stop of a frame under a target error (render/progressive.h, LevelledErrorWatch):
// readings of an error estimate that keeps falling as an unbiased or a shrinking method's does
// never stop the frame; one that stands still above the target does, once two doublings of render
// time show it; one that stands still within two standard errors of the target does not.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "render/progressive.h"

namespace pm {
namespace {

// Feeds `passes` readings, a pass every 10 ms, the estimate error(t) with two standard errors of
// `spread` times it; returns the pass at which the watch said levelled (0: never).
uint32_t levelled_at(uint32_t passes, const std::function<double(double)>& error, double target,
                     double spread = 0.02) {
  LevelledErrorWatch watch;
  for (uint32_t pass = 1; pass <= passes; ++pass) {
    const double t = 0.01 * pass, e = error(t);
    if (watch.levelled(pass, t, e, e * (1 + spread), target)) return pass;
  }
  return 0;
}

TEST(LevelledError, FallingEstimatesNeverStopTheFrame) {
  // The path tracer (t^-1/2) and the slowest shrinking photon passes measured (t^-0.15), both far
  // above their target for all 100,000 passes.
  EXPECT_EQ(levelled_at(100000, [](double t) { return 0.2 / std::sqrt(t); }, 1e-4), 0u);
  EXPECT_EQ(levelled_at(100000, [](double t) { return 0.2 * std::pow(t, -0.15); }, 1e-4), 0u);
}

TEST(LevelledError, AnEstimateStandingAboveTheTargetStopsItAfterTwoDoublings) {
  // Noise falling as t^-1/2 over a bias of 5 %, asked for 1 %: it stops once the noise is small
  // beside the bias, and not before 16 passes however flat the start.
  const uint32_t pass = levelled_at(100000, [](double t) { return std::sqrt(0.05 * 0.05 + 1e-4 / t); }, 0.01);
  EXPECT_GT(pass, 16u);
  EXPECT_LT(pass, 2000u);
  EXPECT_EQ(levelled_at(100000, [](double) { return 0.05; }, 0.01), 16u) << "flat from the start";
}

TEST(LevelledError, NotWhileTheTargetIsWithinTwoStandardErrors) {
  // Flat at 1.05 % with two standard errors of 10 % of it, asked for 1 %: it may yet get there.
  EXPECT_EQ(levelled_at(10000, [](double) { return 0.0105; }, 0.01, 0.1), 0u);
  EXPECT_EQ(levelled_at(10000, [](double) { return 0.05; }, 0.0), 0u) << "no target, no stop";
}

}  // namespace
}  // namespace pm

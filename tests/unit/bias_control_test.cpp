// The error estimate's comparison with its path-traced control (render/bias_control.h), on
// synthetic controls whose truth is known: per control pixel, paths drawn from a skewed
// distribution around the true value, and a film off by a known error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "render/bias_control.h"

namespace pm {
namespace {

struct SyntheticControl {
  std::vector<float4> sums, film;
  double true_mae = 0;  // the film's relative mean absolute error
};

// `pixels` control pixels of true value 1, `paths` paths each from a gamma distribution of
// shape `shape` (mean 1: the smaller the shape, the heavier the tail), and a film off by +-error
// (signs alternating in runs of 16, so regions see a bias), plus `offset` everywhere, plus a
// normal noise of deviation `film_noise` per pixel (a film of photon or path noise).
SyntheticControl synthetic(int pixels, int paths, double shape, double error, double offset, uint32_t seed,
                           double film_noise = 0.0) {
  std::mt19937 rng(seed);
  std::gamma_distribution<double> path_value(shape, 1.0 / shape);
  std::normal_distribution<double> noise(0.0, 1.0);
  SyntheticControl c;
  double abs_sum = 0;
  for (int i = 0; i < pixels; ++i) {
    double sum = 0, squares = 0;
    for (int k = 0; k < paths; ++k) {
      const double v = path_value(rng);
      sum += v;
      squares += v * v;
    }
    c.sums.push_back({float(sum), float(sum), float(sum), float(squares)});
    const double e = ((i / 16) % 2 ? error : -error) + offset + film_noise * noise(rng);
    c.film.push_back({float(1 + e), float(1 + e), float(1 + e), 0.0f});
    abs_sum += std::fabs(e);
  }
  c.true_mae = abs_sum / pixels;
  return c;
}

ControlGrid grid_of(int side) {
  ControlGrid g;
  g.blocks_x = uint32_t(side);
  g.blocks_y = uint32_t(side);
  return g;
}

TEST(BiasControl, GridHoldsAtMostAboutItsTargetOfControlPixels) {
  for (auto [w, h] : {std::pair{96, 54}, {960, 540}, {1920, 1080}, {3840, 2160}}) {
    const ControlGrid g = control_grid(w, h);
    EXPECT_LE(g.pixels(), kControlPixelsTarget * 11 / 10) << w << "x" << h;
    EXPECT_GE(g.pixels(), kControlPixelsTarget / 2) << w << "x" << h;
  }
  EXPECT_EQ(control_grid(16, 16).stride, 1u);  // a film smaller than the target: every pixel
  EXPECT_EQ(control_grid(16, 16).pixels(), 256u);
}

TEST(BiasControl, ReadsTheFilmsErrorWhereTheControlResolvesIt) {
  // 1024 paths of a skewed distribution: the control's noise per pixel is about 4 %, under the
  // film's 10 %.
  const SyntheticControl c = synthetic(1024, 1024, 0.5, 0.10, 0.0, 1);
  const BiasEstimate e = compare_with_control(c.sums, c.film, grid_of(32), 1024, kControlRegionSide);
  ASSERT_TRUE(e.known);
  EXPECT_NEAR(e.mean_abs_error, c.true_mae, 0.15 * c.true_mae);
  EXPECT_LT(e.control_noise, 0.06);
  EXPECT_NEAR(e.signed_bias, 0.0, 3 * e.bias_error + 1e-3);
  EXPECT_GT(e.regional_bias, 0.05) << "runs of +-10 % are a regional bias";
}

TEST(BiasControl, ABiasShowsInTheSignedBiasAndTheError) {
  const SyntheticControl c = synthetic(1024, 1024, 0.5, 0.0, -0.05, 2);
  const BiasEstimate e = compare_with_control(c.sums, c.film, grid_of(32), 1024, kControlRegionSide);
  EXPECT_NEAR(e.signed_bias, -0.05, 3 * e.bias_error);
  EXPECT_GE(e.mean_abs_error, 2.0 / 3.0 * 0.05);
  EXPECT_LE(e.mean_abs_error, 1.5 * 0.05);
}

TEST(BiasControl, ReadsTheFilmsErrorThroughAControlNoisierThanIt) {
  // 256 paths: the control's noise per pixel (about 9 %) is over twice the film's error, a bias
  // of +-4 % in runs or a noise of 4 % per pixel (a mean |error| of 3.2 %). Read pixel by pixel
  // through that noise, each film read about 1.4 times its error; the regions' second moments
  // read it within 12 % (0.93-1.12 times it over these seeds), and the stopping rule's upper end
  // stays above it.
  for (uint32_t seed : {4u, 5u, 6u}) {
    const SyntheticControl biased = synthetic(1024, 256, 0.5, 0.04, 0.0, seed);
    const SyntheticControl noisy = synthetic(1024, 256, 0.5, 0.0, 0.0, seed, 0.04);
    for (const SyntheticControl* c : {&biased, &noisy}) {
      const BiasEstimate e = compare_with_control(c->sums, c->film, grid_of(32), 256, kControlRegionSide);
      ASSERT_TRUE(e.known);
      EXPECT_GT(e.control_noise, 2 * c->true_mae) << "the case: noise over twice the error";
      const char* film = c == &biased ? "bias" : "noise";
      EXPECT_NEAR(e.mean_abs_error, c->true_mae, 0.2 * c->true_mae) << film << ", seed " << seed;
      EXPECT_GE(e.mean_abs_error_upper, c->true_mae) << film << ", seed " << seed;
    }
  }
}

TEST(BiasControl, ANoisyControlSaysSoInsteadOfReadingNoiseAsAccuracy) {
  // 32 paths: the control's noise per pixel (about 25 %) dwarfs the film's 5 %. The estimate
  // then errs high, never low, and control_noise tells the renderer to add paths.
  const SyntheticControl c = synthetic(1024, 32, 0.5, 0.05, 0.0, 3);
  const BiasEstimate e = compare_with_control(c.sums, c.film, grid_of(32), 32, kControlRegionSide);
  EXPECT_GE(e.mean_abs_error, 2.0 / 3.0 * c.true_mae);
  EXPECT_GT(e.control_noise, e.mean_abs_error - e.mean_abs_error_stderr);
}

// A film of `passes` passes, half of them odd, of bias +-bias in runs of 16 control pixels and a
// noise of deviation `noise` in the mean of all passes, against a control of 1024 paths: its w
// the odd passes' mean, as the control kernel writes it.
SyntheticControl split_film(double bias, double noise, uint32_t seed) {
  SyntheticControl c = synthetic(1024, 1024, 4.0, 0.0, 0.0, seed);
  std::mt19937 rng(seed + 100);
  std::normal_distribution<double> normal(0.0, 1.0);
  double abs_sum = 0;
  for (size_t i = 0; i < c.film.size(); ++i) {
    const double b = (i / 16) % 2 ? bias : -bias;
    // Each half's mean has twice the variance of the mean of all passes.
    const double even = 1 + b + noise * std::sqrt(2.0) * normal(rng), odd = 1 + b + noise * std::sqrt(2.0) * normal(rng);
    const float all = float(0.5 * (even + odd));
    c.film[i] = {all, all, all, float(odd)};
    abs_sum += std::fabs(all - 1.0);
  }
  c.true_mae = abs_sum / double(c.film.size());
  return c;
}

TEST(BiasControl, TheFilmsOwnNoiseIsToldFromItsBias) {
  // A bias of 5 % under a noise of 5 %: the part of the error that is bias, read through the
  // film's even and odd passes, at most the bias's own mean |error| and at least 60 % of it
  // (the share of the mean absolute error that sqrt(bias^2 / error^2) gives, less a standard
  // error of the squared bias; measured 4.01-4.29 %).
  for (uint32_t seed : {7u, 8u, 9u}) {
    const SyntheticControl c = split_film(0.05, 0.05, seed);
    const BiasEstimate e = compare_with_control(c.sums, c.film, grid_of(32), 1024, kControlRegionSide, {64, 32});
    ASSERT_TRUE(e.known);
    EXPECT_GE(e.bias_floor, 0.6 * 0.05) << "seed " << seed;
    EXPECT_LE(e.bias_floor, 0.05) << "seed " << seed;
    EXPECT_LT(e.bias_floor, e.mean_abs_error);
    // Noise alone: next to nothing of it is bias.
    const SyntheticControl noise = split_film(0.0, 0.05, seed);
    const BiasEstimate n = compare_with_control(noise.sums, noise.film, grid_of(32), 1024, kControlRegionSide, {64, 32});
    EXPECT_LT(n.bias_floor, 0.2 * n.mean_abs_error) << "seed " << seed;
    std::printf("seed %u: bias 5 %% under noise 5 %%: floor %.2f %% of %.2f %%; noise alone: floor %.2f %% of %.2f %%\n", seed,
                100 * e.bias_floor, 100 * e.mean_abs_error, 100 * n.bias_floor, 100 * n.mean_abs_error);
  }
  // Without the passes behind the film (or with no odd ones), it is not known.
  const SyntheticControl c = split_film(0.05, 0.05, 7);
  EXPECT_EQ(compare_with_control(c.sums, c.film, grid_of(32), 1024, kControlRegionSide).bias_floor, -1.0);
  EXPECT_EQ(compare_with_control(c.sums, c.film, grid_of(32), 1024, kControlRegionSide, {64, 0}).bias_floor, -1.0);
}

TEST(BiasControl, APairedProbeReadsItsMethodsBiasAgainstTheControlsLight) {
  // Per control pixel, paths of the truth less a method's estimate along the same first
  // direction: the estimate 4 % of the light too dark in runs of 16 pixels and 4 % too bright in
  // the others, each path's difference with a deviation of 0.2. Read against a film of zeros,
  // relative to the control's light (control_level: 1 here), the method's absolute and signed bias.
  const SyntheticControl light = synthetic(1024, 256, 0.5, 0.0, 0.0, 11);
  SharedControl control;
  control.sums = light.sums;
  control.paths = 256;
  EXPECT_NEAR(control_level(control), 1.0, 0.02);
  SharedControl probe;
  probe.paths = 512;
  std::mt19937 rng(12);
  std::normal_distribution<double> normal(0.0, 0.2);
  for (size_t i = 0; i < 1024; ++i) {
    const double truth_less_estimate = (i / 16) % 2 ? -0.04 : 0.04;
    double sum = 0, squares = 0;
    for (uint64_t k = 0; k < probe.paths; ++k) {
      const double d = truth_less_estimate + normal(rng);
      sum += d;
      squares += d * d;
    }
    probe.sums.push_back({float(sum), float(sum), float(sum), float(squares)});
  }
  const BiasEstimate e = paired_bias(probe, grid_of(32), control_level(control));
  ASSERT_TRUE(e.known);
  EXPECT_NEAR(e.signed_bias, 0.0, 3 * e.bias_error) << "as much too bright as too dark";
  EXPECT_NEAR(e.mean_abs_error - e.mean_abs_error_stderr, 0.04, 0.006) << "4 % of the light at every pixel";
  // Too bright throughout: the signed bias is the method's, its estimate less the truth.
  for (float4& s : probe.sums) s = {s.x - 0.04f * 512, s.y - 0.04f * 512, s.z - 0.04f * 512, s.w};
  EXPECT_NEAR(paired_bias(probe, grid_of(32), control_level(control)).signed_bias, 0.04, 0.005);
}

}  // namespace
}  // namespace pm

// --method auto's forecasts (render/error_forecast.h): how a candidate's error is carried forward
// from its readings, per kind of method, and where the forecast says "never".
#include <gtest/gtest.h>

#include <cmath>

#include "render/method_race.h"

namespace pm {
namespace {

TEST(MethodRaceForecast, MonteCarloFallsAsOneOverRootTimeUntilMeasured) {
  const ErrorForecast f = forecast_error({{1.0, 0.2, 4}}, ErrorDecay::monte_carlo);
  EXPECT_DOUBLE_EQ(f.rate, 0.5);
  EXPECT_NEAR(f.seconds_to(0.1), 4.0, 1e-12) << "half the error: four times the time";
  EXPECT_NEAR(f.error_at(16.0), 0.05, 1e-12);
  EXPECT_DOUBLE_EQ(f.error_at(0.5), 0.2) << "no forecast backwards";
  EXPECT_DOUBLE_EQ(f.seconds_to(0.3), 1.0) << "already there";
}

TEST(MethodRaceForecast, RatesAreMeasuredFromReadingsFarEnoughApart) {
  // 0.4 at 1 s, 0.2 at 8 s: rate log 2 / log 8 = 1/3.
  const ErrorForecast shrink = forecast_error({{1.0, 0.4, 2}, {8.0, 0.2, 16}}, ErrorDecay::measured);
  EXPECT_NEAR(shrink.rate, 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(shrink.seconds_to(0.1), 64.0, 1e-9);
  // Too close in time to tell (1.2x): the assumed rate.
  const ErrorForecast close = forecast_error({{1.0, 0.4, 2}, {1.2, 0.1, 3}}, ErrorDecay::measured);
  EXPECT_DOUBLE_EQ(close.rate, kAssumedShrinkRate);
  // The last reading against the latest one far enough before it, not the first.
  const ErrorForecast latest = forecast_error({{1.0, 1.0, 1}, {2.0, 0.4, 2}, {8.0, 0.2, 8}}, ErrorDecay::measured);
  EXPECT_NEAR(latest.rate, 0.5, 1e-12);
}

TEST(MethodRaceForecast, RatesAreClampedToWhatMethodsCanDo) {
  // Faster than Monte Carlo is noise in the readings: 1/2 at most.
  EXPECT_DOUBLE_EQ(forecast_error({{1.0, 0.4, 2}, {4.0, 0.05, 8}}, ErrorDecay::measured).rate, 0.5);
  // A biased method whose error stalls (or grows) never reaches a lower target.
  const ErrorForecast stalled = forecast_error({{1.0, 0.1, 2}, {4.0, 0.12, 8}}, ErrorDecay::measured);
  EXPECT_DOUBLE_EQ(stalled.rate, 0.0);
  EXPECT_TRUE(std::isinf(stalled.seconds_to(0.05)));
  // An unbiased method converges: a slow early reading keeps at least kLeastMonteCarloRate.
  EXPECT_DOUBLE_EQ(forecast_error({{1.0, 0.1, 2}, {4.0, 0.1, 8}}, ErrorDecay::monte_carlo).rate, kLeastMonteCarloRate);
}

TEST(MethodRaceForecast, TheFramesStartIsNotPartOfTheDecay) {
  // 1 s beginning the frame (radiosity's solve), then 0.2 at 1.25 s and 0.1 at 2 s: four times
  // the passes' time, half the error. Measured against the whole time the rate would read 0.74
  // (clamped to 1/2) and the forecast would miss where the time goes.
  const ErrorForecast f = forecast_error({{1.25, 0.2, 1}, {2.0, 0.1, 4}}, ErrorDecay::sampled, 1.0);
  EXPECT_NEAR(f.rate, 0.5, 1e-12);
  EXPECT_NEAR(f.seconds_to(0.05), 1.0 + 4.0, 1e-9) << "the passes' second quadruples; the start is paid once";
  EXPECT_NEAR(f.error_at(17.0), 0.025, 1e-12);
  // Until two readings are far enough apart in the passes' time, passes that are samples of one
  // estimate fall as 1/sqrt(t), biased or not; photon passes (measured) more slowly.
  const ErrorForecast first = forecast_error({{1.25, 0.2, 1}, {1.3, 0.19, 2}}, ErrorDecay::sampled, 1.0);
  EXPECT_DOUBLE_EQ(first.rate, 0.5);
  EXPECT_NEAR(first.seconds_to(0.095), 1.0 + 0.3 * 4.0, 1e-9);
  EXPECT_DOUBLE_EQ(forecast_error({{1.25, 0.2, 1}}, ErrorDecay::measured, 1.0).rate, kAssumedShrinkRate);
  // And a sampled estimate whose error does not fall is all bias: it stays where it is.
  const ErrorForecast stalled = forecast_error({{1.5, 0.1, 2}, {4.0, 0.1, 8}}, ErrorDecay::sampled, 1.0);
  EXPECT_DOUBLE_EQ(stalled.floor, 0.1);
  EXPECT_TRUE(std::isinf(stalled.seconds_to(0.09)));
}

TEST(MethodRaceForecast, ASampledEstimatesBiasIsAFloorUnderItsNoise) {
  // error^2 = 0.0004 / p + 0.01^2: 2.236 % after 1 s of passes, 1.414 % after 4 s.
  const ErrorForecast f =
      forecast_error({{1.0, std::sqrt(0.0005), 4}, {4.0, std::sqrt(0.0002), 16}}, ErrorDecay::sampled);
  EXPECT_NEAR(f.floor, 0.01, 1e-12);
  EXPECT_NEAR(f.seconds_to(0.012), 0.0004 / (0.012 * 0.012 - 0.0001), 1e-9)
      << "9.1 s, where the power law through the same readings (rate 0.33) says 6.5 s";
  EXPECT_NEAR(f.error_at(400.0), std::sqrt(0.0004 / 400 + 0.0001), 1e-12);
  EXPECT_TRUE(std::isinf(f.seconds_to(0.0099))) << "never under its bias";
  // Noise alone, falling as 1/sqrt(t): no floor, the forecast of an unbiased method.
  const ErrorForecast noise = forecast_error({{1.0, 0.02, 4}, {4.0, 0.01, 16}}, ErrorDecay::sampled);
  EXPECT_DOUBLE_EQ(noise.floor, 0.0);
  EXPECT_NEAR(noise.seconds_to(0.005), 16.0, 1e-9);
  // Falling faster than that is the readings' noise: no floor either.
  EXPECT_DOUBLE_EQ(forecast_error({{1.0, 0.04, 4}, {4.0, 0.01, 16}}, ErrorDecay::sampled).floor, 0.0);
}

TEST(MethodRaceForecast, TheTimeToProveATargetCountsTheReadingsStandardError) {
  // The stopping rule wants the estimate plus two standard errors under the target: with a
  // standard error of 5 % of the error, the error must reach target / 1.1.
  ErrorReading last{1.0, 0.02, 16, 0.001};
  const ErrorForecast noise = forecast_error({last}, ErrorDecay::monte_carlo);
  EXPECT_NEAR(noise.seconds_to_proof(0.01), 4.0 * 1.1 * 1.1, 1e-9);
  // Over a floor the proof costs more than the noise's share: 0.8 % under a target of 1 %.
  ErrorForecast biased = noise;
  biased.floor = 0.008;
  const double to_target = biased.seconds_to(0.01), to_proof = biased.seconds_to_proof(0.01);
  EXPECT_NEAR(to_proof / to_target, (0.01 * 0.01 - 0.008 * 0.008) / (0.01 * 0.01 / 1.21 - 0.008 * 0.008), 1e-9);
  EXPECT_GT(to_proof / to_target, 1.9) << "the noise alone: 1.21";
  // A reading without a standard error: the target itself.
  last.error_stderr = 0;
  EXPECT_DOUBLE_EQ(forecast_error({last}, ErrorDecay::monte_carlo).seconds_to_proof(0.01), 4.0);
}

// Readings at 0.4, 0.8, ... 6.4 s of passes (80 passes a second) of an estimate whose mean squared
// error is a t^-exponent + floor^2, its relative mean absolute error mae_share times the RMS
// error, its standard error stderr_share of that.
std::vector<ErrorReading> doubling_readings(double a, double exponent, double floor, double mae_share,
                                            double stderr_share) {
  std::vector<ErrorReading> readings;
  for (double t : {0.4, 0.8, 1.6, 3.2, 6.4}) {
    ErrorReading r;
    r.seconds = t;
    r.passes = uint32_t(80 * t);
    r.mean_square = a * std::pow(t, -exponent) + floor * floor;
    r.error = mae_share * std::sqrt(r.mean_square);
    r.error_stderr = stderr_share * r.error;
    readings.push_back(r);
  }
  return readings;
}

TEST(MethodRaceForecast, ASampledEstimatesFloorIsFittedThroughItsReadingsMeanSquares) {
  // Final gathering over radiosity on Sponza: MSE = a / p + b^2 with b = 0.8 %, the relative mean
  // absolute error 0.8 times the RMS error; each reading's standard error 7 % of its error.
  const double a = 0.0001, b = 0.008;
  std::vector<ErrorReading> readings = doubling_readings(a, 1.0, b, 0.8, 0.07);
  const ErrorForecast f = forecast_error(readings, ErrorDecay::sampled);
  EXPECT_NEAR(f.floor, 0.8 * b, 1e-9);
  EXPECT_DOUBLE_EQ(f.rate, 0.5);
  // Readings of few passes are left out of the fit, and three within the span are needed: with
  // two, the two-reading fit, each a standard error apart (lower).
  for (ErrorReading& r : readings) r.passes = kFloorFitLeastPasses - 1;
  readings.back().passes = 600;
  const ErrorForecast two = forecast_error({readings[3], readings[4]}, ErrorDecay::sampled);
  EXPECT_DOUBLE_EQ(forecast_error(readings, ErrorDecay::sampled).floor, two.floor);
  EXPECT_LT(two.floor, f.floor);
  // An error that does not fall over the fitted readings is all floor.
  std::vector<ErrorReading> stalled(3, readings.back());
  for (int i = 0; i < 3; ++i) stalled[size_t(i)].seconds = std::pow(2.0, i);
  const ErrorForecast flat = forecast_error(stalled, ErrorDecay::sampled);
  EXPECT_DOUBLE_EQ(flat.floor, stalled.back().error);
  EXPECT_TRUE(std::isinf(flat.seconds_to(0.5 * flat.floor)));
}

TEST(MethodRaceForecast, FinalGatheringsNoiseFallsAsAScrambledNetsOverItsFloor) {
  // Final gathering's rays are scrambled nets' points: noise as p^-3/4 (MSE as p^-3/2) over the
  // solution's bias. Sponza's readings at 1 % (H200): 2.22 % at 1.35 s, 1.57 % at 2.71 s, 1.24 %
  // at 5.42 s. This model through the first two (no standard errors taken off) has a floor of
  // 1.06 % and 1.26 % at 5.42 s; the independent samples' 1 / p model a floor of 0.14 % and 1.11 %.
  const double a = 0.0001, b = 0.008;
  const std::vector<ErrorReading> readings = doubling_readings(a, 1.5, b, 1.0, 0.0);
  const ErrorForecast f = forecast_error(readings, ErrorDecay::sampled, 0, kScrambledNetRate);
  EXPECT_NEAR(f.floor, b, 1e-9);
  EXPECT_DOUBLE_EQ(f.rate, kScrambledNetRate);
  EXPECT_NEAR(f.error_at(12.8), std::sqrt(a * std::pow(12.8, -1.5) + b * b), 1e-12);
  const ErrorForecast two = forecast_error({readings[0], readings[1]}, ErrorDecay::sampled, 0, kScrambledNetRate);
  EXPECT_NEAR(two.floor, b, 1e-9);
  // Readings of few passes fall as independent samples': through them, the 1 / p model.
  std::vector<ErrorReading> early = {readings[0], readings[1]};
  early[0].passes = kFloorFitLeastPasses - 1;
  const ErrorForecast few = forecast_error(early, ErrorDecay::sampled, 0, kScrambledNetRate);
  EXPECT_DOUBLE_EQ(few.rate, kIndependentNoiseRate);
  EXPECT_DOUBLE_EQ(few.floor, forecast_error(early, ErrorDecay::sampled).floor);
  const ErrorForecast as_independent = forecast_error(readings, ErrorDecay::sampled);
  EXPECT_LT(as_independent.floor, 0.9 * b) << "the 1 / p model takes the net's fast fall for noise";
  // Over photons (measured) the rate may read up to 1 (a net's smooth integrand), 1/2 assumed
  // until measured; independent samples' is clamped to 1/2.
  const std::vector<ErrorReading> fast = {{1.0, 0.04, 4}, {4.0, 0.01, 16}};
  EXPECT_DOUBLE_EQ(forecast_error(fast, ErrorDecay::measured, 0, kScrambledNetRate).rate, 1.0);
  EXPECT_DOUBLE_EQ(forecast_error(fast, ErrorDecay::measured).rate, 0.5);
  EXPECT_DOUBLE_EQ(forecast_error({fast[1]}, ErrorDecay::measured, 0, kScrambledNetRate).rate, 0.5);
  const std::vector<ErrorReading> sponza = {{0.877, 0.0364, 40}, {1.56, 0.0233, 70}};
  EXPECT_NEAR(forecast_error(sponza, ErrorDecay::measured, 0, kScrambledNetRate).rate, 0.774, 0.001)
      << "final gathering over photons on Sponza, 3.64 % to 2.33 % as its passes' time grew 1.78 times";
}

TEST(MethodRaceForecast, ASampledEstimatesMeasuredBiasIsItsFloor) {
  // Sibenik's final gathering over radiosity: its noise fell as 1/sqrt(p) over a bias of about
  // 0.6 %. Through readings of that fall the net's assumed p^-3/4 reads a floor near twice the bias;
  // the bias measured along the control's paths is the floor, and the rate over it is measured.
  const double a = 0.0004, b = 0.006;
  std::vector<ErrorReading> readings = doubling_readings(a, 1.0, b, 1.0, 0.0);
  const std::vector<ErrorReading> two = {readings[1], readings[2]};
  EXPECT_GT(forecast_error(two, ErrorDecay::sampled, 0, kScrambledNetRate).floor, 1.5 * b) << "read from the fall";
  for (ErrorReading& r : readings) {
    r.measured_floor = b;
    r.measured_floor_stderr = 0.0005;
  }
  const ErrorForecast f = forecast_error({readings[1], readings[2]}, ErrorDecay::sampled, 0, kScrambledNetRate);
  EXPECT_DOUBLE_EQ(f.floor, b);
  EXPECT_NEAR(f.rate, 0.5, 1e-9);
  const double t = 4 * readings[2].seconds;
  EXPECT_NEAR(f.error_at(t), std::sqrt(a / t + b * b), 1e-12);
  // Before a second reading the rate is the method's assumed one over the measured floor.
  const ErrorForecast one = forecast_error({readings[1]}, ErrorDecay::sampled, 0, kScrambledNetRate);
  EXPECT_DOUBLE_EQ(one.floor, b);
  EXPECT_DOUBLE_EQ(one.rate, kScrambledNetRate);
  // A measured bias of nothing leaves no floor where the readings' fall would have read one, and
  // the best case stands on the measured bias less two standard errors.
  for (ErrorReading& r : readings) r.measured_floor = 0;
  EXPECT_DOUBLE_EQ(forecast_error(readings, ErrorDecay::sampled, 0, kScrambledNetRate).floor, 0.0);
  for (ErrorReading& r : readings) r.measured_floor = b;
  EXPECT_NEAR(best_case_forecast(readings, ErrorDecay::sampled, 0, kScrambledNetRate).floor, b - 0.001, 1e-12);
  // The part of the error the film's even and odd passes say is bias at least still counts where
  // it is the higher.
  readings.back().floor = 1.5 * b;
  EXPECT_DOUBLE_EQ(forecast_error(readings, ErrorDecay::sampled, 0, kScrambledNetRate).floor, 1.5 * b);
}

TEST(MethodRaceForecast, TheBestCaseFallsAtTheFastestRateItsSamplesAllow) {
  // One reading, as after the race's first round: independent samples (the path tracer, photon
  // passes) at best 1/2, a scrambled net's passes at best 1, whatever the assumed rates.
  const std::vector<ErrorReading> one = {{0.1, 0.2, 2}};
  EXPECT_NEAR(best_case_forecast(one, ErrorDecay::monte_carlo).seconds_to(0.1), 0.4, 1e-12);
  EXPECT_NEAR(best_case_forecast(one, ErrorDecay::measured).seconds_to(0.1), 0.4, 1e-12);
  EXPECT_NEAR(best_case_forecast(one, ErrorDecay::measured, 0, kScrambledNetRate).seconds_to(0.1), 0.2, 1e-12);
  EXPECT_LT(best_case_forecast(one, ErrorDecay::measured).seconds_to(0.1),
            forecast_error(one, ErrorDecay::measured).seconds_to(0.1))
      << "never slower than the forecast on an assumed rate";
  // Over radiosity the bias its reading shows at least stays under it: it cannot go below it.
  std::vector<ErrorReading> biased = {{1.0, 0.05, 8}};
  biased[0].floor = 0.02;
  const ErrorForecast over_floor = best_case_forecast(biased, ErrorDecay::sampled, 0.5, kScrambledNetRate);
  EXPECT_TRUE(std::isinf(over_floor.seconds_to(0.015)));
  EXPECT_NEAR(over_floor.error_at(1.5), std::sqrt(0.02 * 0.02 + (0.05 * 0.05 - 0.02 * 0.02) / 4), 1e-12)
      << "its noise halves as its passes' time doubles";
  EXPECT_TRUE(std::isinf(best_case_forecast(one, ErrorDecay::fixed).seconds_to(0.1))) << "its passes are done";
}

TEST(MethodRaceForecast, AProbeReadingUnderHalfTheTargetAsksForNoMorePaths) {
  // The probe grows ahead of the control while the bias it reads, less a standard error, is half
  // the target or more (kProbeResolveShare): Conference's first readings, 0.96 % (+-0.04) under a
  // target of 1 %, ask for more; under 2 %, not; nor does a probe that saw no light.
  BiasEstimate probe;
  probe.known = true;
  probe.mean_abs_error = 0.0096;
  probe.mean_abs_error_stderr = 0.0004;
  EXPECT_TRUE(probe_reads_near_target(probe, 0.01));
  EXPECT_FALSE(probe_reads_near_target(probe, 0.02));
  probe.mean_abs_error_stderr = 0.0005;  // 0.91 % less a standard error: under 0.5 x 2 %
  EXPECT_FALSE(probe_reads_near_target(probe, 0.0184));
  EXPECT_TRUE(probe_reads_near_target(probe, 0.018));
  probe.known = false;
  EXPECT_FALSE(probe_reads_near_target(probe, 0.01));
}

TEST(MethodRaceForecast, AFinishedMethodStaysWhereItIs) {
  const ErrorForecast radiosity = forecast_error({{0.5, 0.02, 1}}, ErrorDecay::fixed);
  EXPECT_DOUBLE_EQ(radiosity.error_at(100.0), 0.02);
  EXPECT_DOUBLE_EQ(radiosity.seconds_to(0.03), 0.5);
  EXPECT_TRUE(std::isinf(radiosity.seconds_to(0.01)));
}

}  // namespace
}  // namespace pm

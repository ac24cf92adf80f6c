// How --method auto carries a candidate's error forward from its readings (method_race.h): the
// kinds of decay a method's error has over its passes, and the forecast of when it reaches a
// target or what it reaches by a time. Tested in tests/unit/method_race_forecast_test.cpp.
#pragma once

#include <cstdint>
#include <vector>

namespace pm {

// One reading of a candidate's error estimate after `seconds` of its own render time.
struct ErrorReading {
  double seconds = 0;
  double error = -1;  // Renderer::estimate_error: the relative mean absolute error of the indirect light
  uint32_t passes = 0;
  double error_stderr = 0;  // the standard error of that estimate
  double floor = -1;        // the part of it that is bias, at least (BiasEstimate::bias_floor); -1: not known
  double floor_upper = -1;  // and at most (BiasEstimate::bias_ceiling); -1: not known
  double mean_square = -1;  // the relative mean squared error, unbiased (BiasEstimate::mean_square); -1: not known
  // The bias itself measured along the control's paths (paired_bias, render/bias_control.h): its
  // relative mean absolute error and that figure's standard error; -1: not measured.
  double measured_floor = -1;
  double measured_floor_stderr = 0;
};

// How a candidate's error falls with its render time t (its own; start is what it spent
// beginning the frame before its first pass, radiosity's solve: passes lower the error, the start
// does not), with p = t - start its time in passes:
//   error(t)^2 = floor^2 + (last.error^2 - floor^2) * (p_last / p)^(2 rate)
// With no floor that is error(t) = last.error * (p_last / p)^rate. The rate is measured from the
// last reading and the latest one far enough before it in pass time (kRateSpan), clamped to at
// most the method's noise can fall: 1/2 for independent samples (Monte Carlo's 1/sqrt(t)), 1 for
// final gathering, whose rays over the frame are points of scrambled (0,2)-sequences
// (kernels/common/low_discrepancy.h; noise_rate, below):
// - monte_carlo (unbiased: the path tracer): assumed 1/2 until measured, kept at least 1/4 (its
//   relative mean absolute error falls slower than 1/sqrt(t) only while most pixels have seen few
//   paths); no floor.
// - sampled (passes are samples of one biased estimate: final gathering over a radiosity
//   solution): noise falling as p^-noise_rate over a constant bias, the floor, fitted from
//   the same two readings (error^2 = a p^(-2 noise_rate) + floor^2), each a standard error towards the lower
//   floor: a floor is a difference of squares, and the readings' noise alone would make one (for
//   readings twice apart in time whose ratio is 7 % low, about half the last error), which would
//   count a converging candidate out. Over those readings a floor shows where it is a large part of the error: in
//   the spot-lit box's coarse solution (levelling at 3.2-3.7 %, read at 4.7-4.9 %) it read
//   2.5-2.9 %; on Sponza, about 0.8 % under 1.2-1.5 %, it read 0.26-0.36 % (docs/method-auto.md,
//   "The duel"). A power law instead takes the bias's slowing for a slower rate that never stops.
//   From readings of fewer than kFloorFitLeastPasses passes the noise is taken to fall as
//   independent samples' (1/2): a net's faster fall shows only once its pixels have many rays.
//   With three readings or more spanning 3.5 times in pass time, the floor is fitted instead
//   through their mean squared errors by least squares (fitted_floor, error_forecast.cpp).
//   Where the bias itself is measured (ErrorReading::measured_floor: final gathering over
//   radiosity, whose solution's bias the control's paths measure along their first directions,
//   kernels/common/radiosity_bias_probe.h), that is the floor, and the noise's rate is measured
//   over it from the same two readings (within kIndependentNoiseRate and the fastest the method
//   allows): neither fit reads a floor from how the error falls (on the benchmark scenes they
//   read 1.0-1.5 % where the error went on falling to 0.6-0.9 %, docs/method-auto.md).
//   Where the last reading knows the part of its error that the film's own noise does not explain
//   (ErrorReading::floor, from the film's even and odd passes at the control pixels), that is the
//   floor if it is the higher: it needs no second reading and no fit across time.
// - measured (passes also shrink a bias: photon passes shrinking): assumed kAssumedShrinkRate until
//   measured (1/2 with final gathering, whose rays' noise is most of its error), may measure 0;
//   no floor (the bias shrinks with the passes).
// - fixed (its passes are done): stays where it is.
struct ErrorForecast {
  ErrorReading last;
  double rate = 0;
  double floor = 0;  // the error it cannot go below (sampled)
  double start = 0;  // own seconds before the first pass
  // Render time at which the error reaches `target` (its own time, the time spent included);
  // infinity if never.
  double seconds_to(double target) const;
  // Render time at which the stopping rule proves the error under `target` (the estimate plus two
  // standard errors under it, render/progressive.h), the standard error the same share of the
  // error as at the last reading (5-8 % on the benchmark scenes). Not seconds_to(target): near a
  // floor the last stretch to the proof is the longest (final gathering over radiosity on
  // Conference, forecast 2 s more to 1.07 -> 1 %, needed 12 s more to prove 1 %).
  double seconds_to_proof(double target) const;
  double error_at(double seconds) const;
};

enum class ErrorDecay { monte_carlo, sampled, measured, fixed };
// Photon passes that shrink measured 0.15 to 0.27 on Sponza, Sibenik and Conference at 960 x 540
// (docs/method-auto.md); progressive photon mapping's error falls at best as t^-1/3.
constexpr double kAssumedShrinkRate = 0.2;
constexpr double kLeastMonteCarloRate = 0.25;
// How a pixel's noise falls with its passes, as p^-rate (IndirectMethod::noise_rate): 1/2 for
// independent samples; final gathering's rays over the frame are points of scrambled
// (0,2)-sequences, whose error falls as about n^-3/4 where the integrand has edges, as
// visibility gives it (He & Wang 2015: the variance of scrambled nets for a discontinuity along
// a smooth curve in d = 2 is O(n^-3/2)), and as n^-1 where it is smooth (Owen 1997). Measured on
// Sponza, Sibenik and Conference at 960 x 540 (H200): rates of 0.52-0.77 between readings, final
// gathering over photons (docs/final-gathering.md, "Directions from a scrambled sequence").
constexpr double kIndependentNoiseRate = 0.5;
constexpr double kScrambledNetRate = 0.75;
constexpr double kScrambledNetMostRate = 1.0;
// Readings this far apart in pass time (a factor) measure a rate; closer ones are mostly the
// estimate's own noise.
constexpr double kRateSpan = 1.5;
// The floor of a sampled estimate is fitted over its readings within kFloorFitSpan of the last
// in pass time and of kFloorFitLeastPasses passes or more, once there are kFloorFitReadings of
// them spanning kFloorFitLeastSpan (three rounds of doubling): readings of few passes, while
// pixels have few rays, fall more slowly than 1/sqrt(t) and read a floor that is not there
// (docs/method-auto.md, "The duel"). The rules lower that risk, not remove it: on Sibenik the
// fit read 1.44 % from readings at 0.36-1.43 s of passes, where its later readings show about
// 0.6 % ("A floor fitted across readings").
constexpr double kFloorFitSpan = 8.0;
constexpr int kFloorFitReadings = 3;
constexpr double kFloorFitLeastSpan = 3.5;
constexpr uint32_t kFloorFitLeastPasses = 16;
ErrorForecast forecast_error(const std::vector<ErrorReading>& readings, ErrorDecay decay, double start_seconds = 0,
                             double noise_rate = kIndependentNoiseRate);
// The fastest its error could fall from its last reading: at the most rate its decay allows (1/2
// for independent samples, kScrambledNetMostRate for scrambled nets' passes), over no floor but
// the bias its last reading shows at least (sampled). Before a rate is measured, a candidate
// even this forecast puts far behind the best is out (race_referee.h, RaceStanding::best_case).
ErrorForecast best_case_forecast(const std::vector<ErrorReading>& readings, ErrorDecay decay, double start_seconds = 0,
                                 double noise_rate = kIndependentNoiseRate);

}  // namespace pm

// The error forecasts of --method auto (error_forecast.h).
#include "render/error_forecast.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pm {

double ErrorForecast::seconds_to(double target) const {
  if (last.error <= target) return last.seconds;
  const double passes = last.seconds - start;
  if (rate <= 0 || passes <= 0 || target <= floor) return std::numeric_limits<double>::infinity();
  const double above = last.error * last.error - floor * floor, wanted = target * target - floor * floor;
  return start + passes * std::pow(above / wanted, 0.5 / rate);
}

double ErrorForecast::seconds_to_proof(double target) const {
  const double share = last.error > 0 ? std::max(0.0, last.error_stderr) / last.error : 0.0;
  return seconds_to(target / (1.0 + 2.0 * share));
}

double ErrorForecast::error_at(double seconds) const {
  const double passes = last.seconds - start;
  if (seconds <= last.seconds || passes <= 0) return last.error;
  const double above = last.error * last.error - floor * floor;
  return std::sqrt(floor * floor + above * std::pow(passes / (seconds - start), 2 * rate));
}

namespace {

// The floor of a sampled estimate from its recent readings' mean squared errors, fitted as
// MSE = a p^(-2 noise_rate) + floor^2 by least squares (p: the passes' time) over the readings within
// kFloorFitSpan of the last in time and of kFloorFitLeastPasses passes or more, when there are
// kFloorFitReadings of them spanning at least kFloorFitLeastSpan; as a share of the last
// reading's error. The mean squares are unbiased and all of a candidate's readings are measured
// against the same control, so the fit sees how the error falls, not the control's noise, which
// shifts every reading alike (the relative mean absolute errors moved a standard error apart, as
// the two-reading fit must, read Sponza's floor of about 0.8 % as 0.26-0.36 %). -1: too few
// readings.
double fitted_floor(const std::vector<ErrorReading>& readings, double start_seconds, double noise_rate) {
  const ErrorReading& last = readings.back();
  const double last_passes = last.seconds - start_seconds;
  if (!(last_passes > 0) || !(last.mean_square > 0) || !(last.error > 0)) return -1;
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, earliest = last_passes;
  for (const ErrorReading& r : readings) {
    const double passes = r.seconds - start_seconds;
    if (!(passes > 0) || r.mean_square < 0 || r.passes < kFloorFitLeastPasses || passes * kFloorFitSpan < last_passes)
      continue;
    const double x = std::pow(passes, -2.0 * noise_rate);
    n += 1;
    sx += x;
    sy += r.mean_square;
    sxx += x * x;
    sxy += x * r.mean_square;
    earliest = std::min(earliest, passes);
  }
  if (n < kFloorFitReadings || last_passes < kFloorFitLeastSpan * earliest) return -1;
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  if (!(slope > 0)) return last.error;  // the error does not fall: all of it is floor
  const double floor_square = (sy - slope * sx) / n;
  return last.error * std::sqrt(std::clamp(floor_square / last.mean_square, 0.0, 1.0));
}

// A forecast from the last reading, at rate 0 (where a finished method stays).
ErrorForecast from_last_reading(const std::vector<ErrorReading>& readings, double start_seconds) {
  ErrorForecast f;
  f.start = start_seconds;
  if (!readings.empty()) f.last = readings.back();
  return f;
}

// The fastest a method's error can fall: as independent samples' or as scrambled nets'.
double fastest_rate(double noise_rate) {
  return noise_rate > kIndependentNoiseRate ? kScrambledNetMostRate : kIndependentNoiseRate;
}

// The rate at which the part of the error above a known floor falls, from the last reading and
// the latest one kRateSpan or more before it in pass time: error^2 - floor^2 as p^(-2 rate),
// within kIndependentNoiseRate and the fastest the method's noise allows; noise_rate where no
// reading is far enough back or the error is already at the floor.
double noise_rate_over(const std::vector<ErrorReading>& readings, double start_seconds, double floor,
                       double noise_rate) {
  const ErrorReading& last = readings.back();
  const double last_passes = last.seconds - start_seconds, above_last = last.error * last.error - floor * floor;
  for (size_t i = readings.size() - 1; i-- > 0;) {
    const ErrorReading& a = readings[i];
    const double passes = a.seconds - start_seconds;
    if (passes <= 0 || a.error <= 0 || last_passes < kRateSpan * passes) continue;
    const double above = a.error * a.error - floor * floor;
    if (!(above > 0) || !(above_last > 0)) return noise_rate;
    const double measured = 0.5 * std::log(above / above_last) / std::log(last_passes / passes);
    return std::clamp(measured, kIndependentNoiseRate, fastest_rate(noise_rate));
  }
  return noise_rate;
}

}  // namespace

ErrorForecast forecast_error(const std::vector<ErrorReading>& readings, ErrorDecay decay, double start_seconds,
                             double noise_rate) {
  ErrorForecast f = from_last_reading(readings, start_seconds);
  if (readings.empty() || decay == ErrorDecay::fixed) return f;
  const bool scrambled = noise_rate > kIndependentNoiseRate;
  const double most_rate = fastest_rate(noise_rate);
  if (decay == ErrorDecay::measured)
    f.rate = scrambled ? kIndependentNoiseRate : kAssumedShrinkRate;
  else
    f.rate = decay == ErrorDecay::sampled ? noise_rate : kIndependentNoiseRate;
  // The latest reading against the latest one far enough before it, in the passes' time.
  const double last_passes = f.last.seconds - start_seconds;
  for (size_t i = readings.size() - 1; i-- > 0;) {
    const ErrorReading& a = readings[i];
    const double passes = a.seconds - start_seconds;
    if (passes <= 0 || a.error <= 0 || f.last.error <= 0 || last_passes < kRateSpan * passes) continue;
    if (decay == ErrorDecay::sampled) {
      // error^2 = noise p^(-2 noise_rate) + floor^2 through both readings, the earlier a
      // standard error higher and the later one lower; an error that did not fall even so is all floor.
      const double high = a.error + a.error_stderr, low = std::max(0.0, f.last.error - f.last.error_stderr);
      const double e0 = high * high, e1 = low * low;
      // A net's error falls faster than independent samples' only once its pixels have many
      // rays: from readings of fewer passes than the fits' least, as independent samples (the
      // net's rate through Sponza's first readings, of 1 and 9 passes, read a floor of 3.8 %).
      const double fit_rate = a.passes >= kFloorFitLeastPasses ? noise_rate : kIndependentNoiseRate;
      const double x0 = std::pow(passes, -2.0 * fit_rate), x1 = std::pow(last_passes, -2.0 * fit_rate);
      const double noise = (e0 - e1) / (x0 - x1);
      f.floor = noise > 0 ? std::sqrt(std::max(0.0, e1 - noise * x1)) : low;
      f.rate = noise > 0 ? fit_rate : 0.0;
      break;
    }
    const double measured = std::log(a.error / f.last.error) / std::log(last_passes / passes);
    f.rate = std::clamp(measured, decay == ErrorDecay::monte_carlo ? kLeastMonteCarloRate : 0.0, most_rate);
    break;
  }
  // Over enough readings, their mean squares' fit instead of the two readings' (whose standard
  // errors are mostly the control's, which all readings share).
  if (decay == ErrorDecay::sampled) {
    const double fitted = fitted_floor(readings, start_seconds, noise_rate);
    if (fitted >= 0) {
      f.floor = std::min(fitted, f.last.error);
      f.rate = f.floor < f.last.error ? noise_rate : 0.0;
    }
  }
  // The bias measured along the control's paths: the floor, and the noise's rate over it.
  if (decay == ErrorDecay::sampled && f.last.measured_floor >= 0) {
    f.floor = std::min(f.last.measured_floor, f.last.error);
    f.rate = noise_rate_over(readings, start_seconds, f.floor, noise_rate);
  }
  // The bias the last reading itself shows beside the film's own noise, where it says more.
  if (decay == ErrorDecay::sampled && f.last.floor > f.floor) {
    f.floor = std::min(f.last.floor, f.last.error);
    if (f.floor >= f.last.error) f.rate = 0;
  }
  return f;
}

ErrorForecast best_case_forecast(const std::vector<ErrorReading>& readings, ErrorDecay decay, double start_seconds,
                                 double noise_rate) {
  ErrorForecast f = from_last_reading(readings, start_seconds);
  if (readings.empty() || decay == ErrorDecay::fixed) return f;
  f.rate = fastest_rate(noise_rate);
  if (decay == ErrorDecay::sampled) {
    // At least the bias its reading shows, or the measured bias less two standard errors.
    const double measured = f.last.measured_floor >= 0 ? f.last.measured_floor - 2.0 * f.last.measured_floor_stderr : 0.0;
    f.floor = std::clamp(std::max(f.last.floor, measured), 0.0, f.last.error);
  }
  return f;
}

}  // namespace pm

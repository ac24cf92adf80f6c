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
// MSE = a / p + floor^2 by least squares (p: the passes' time) over the readings within
// kFloorFitSpan of the last in time and of kFloorFitLeastPasses passes or more, when there are
// kFloorFitReadings of them spanning at least kFloorFitLeastSpan; as a share of the last
// reading's error. The mean squares are unbiased and all of a candidate's readings are measured
// against the same control, so the fit sees how the error falls, not the control's noise, which
// shifts every reading alike (the relative mean absolute errors moved a standard error apart, as
// the two-reading fit must, read Sponza's floor of about 0.8 % as 0.26-0.36 %). -1: too few
// readings.
double fitted_floor(const std::vector<ErrorReading>& readings, double start_seconds) {
  const ErrorReading& last = readings.back();
  const double last_passes = last.seconds - start_seconds;
  if (!(last_passes > 0) || !(last.mean_square > 0) || !(last.error > 0)) return -1;
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, earliest = last_passes;
  for (const ErrorReading& r : readings) {
    const double passes = r.seconds - start_seconds;
    if (!(passes > 0) || r.mean_square < 0 || r.passes < kFloorFitLeastPasses || passes * kFloorFitSpan < last_passes)
      continue;
    const double x = 1.0 / passes;
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

}  // namespace

ErrorForecast forecast_error(const std::vector<ErrorReading>& readings, ErrorDecay decay, double start_seconds,
                             double noise_rate) {
  ErrorForecast f;
  f.start = start_seconds;
  if (readings.empty()) return f;
  f.last = readings.back();
  if (decay == ErrorDecay::fixed) return f;
  const bool scrambled = noise_rate > kIndependentNoiseRate;
  const double most_rate = scrambled ? kScrambledNetMostRate : kIndependentNoiseRate;
  f.rate = decay == ErrorDecay::measured && !scrambled ? kAssumedShrinkRate : kIndependentNoiseRate;
  // The latest reading against the latest one far enough before it, in the passes' time.
  const double last_passes = f.last.seconds - start_seconds;
  const ErrorReading* earlier = nullptr;
  for (size_t i = readings.size() - 1; i-- > 0;) {
    const ErrorReading& a = readings[i];
    const double passes = a.seconds - start_seconds;
    if (passes <= 0 || a.error <= 0 || f.last.error <= 0 || last_passes < kRateSpan * passes) continue;
    earlier = &a;
    if (decay == ErrorDecay::sampled) {
      // error^2 = noise / p + floor^2 through both readings, the earlier a standard error higher
      // and the later one lower; an error that did not fall even so is all floor.
      const double high = a.error + a.error_stderr, low = std::max(0.0, f.last.error - f.last.error_stderr);
      const double e0 = high * high, e1 = low * low;
      const double noise = (e0 - e1) / (1.0 / passes - 1.0 / last_passes);
      f.floor = noise > 0 ? std::sqrt(std::max(0.0, e1 - noise / last_passes)) : low;
      f.rate = noise > 0 ? kIndependentNoiseRate : 0.0;
      break;
    }
    const double measured = std::log(a.error / f.last.error) / std::log(last_passes / passes);
    f.rate = std::clamp(measured, decay == ErrorDecay::monte_carlo ? kLeastMonteCarloRate : 0.0, most_rate);
    break;
  }
  if (decay != ErrorDecay::sampled) return f;
  // Over enough readings, their mean squares' fit instead of the two readings' (whose standard
  // errors are mostly the control's, which all readings share).
  const double fitted = fitted_floor(readings, start_seconds);
  if (fitted >= 0) {
    f.floor = std::min(fitted, f.last.error);
    f.rate = f.floor < f.last.error ? kIndependentNoiseRate : 0.0;
  }
  // The bias the last reading itself shows beside the film's own noise, where it says more.
  if (f.last.floor > f.floor) {
    f.floor = std::min(f.last.floor, f.last.error);
    if (f.floor >= f.last.error) f.rate = 0;
  }
  // A net's noise falls faster than independent samples' (noise_rate): above the floor, its rate
  // measured between the same two readings, the floor taken off both. The floor itself is fitted
  // as independent samples' noise would fall: a net's fall is not steady (about p^-1/2 while its
  // pixels have few rays, towards p^-3/4 and faster later), and a steeper model read as a floor
  // what was only its slower start (Sibenik's final gathering over radiosity, counted out as
  // "never" at 1.83 % where alone it reached 1 % in 7.9 s; docs/method-auto.md).
  if (scrambled && earlier && f.rate > 0 && f.floor < f.last.error) {
    const double floor2 = f.floor * f.floor;
    const double above0 = earlier->error * earlier->error - floor2, above1 = f.last.error * f.last.error - floor2;
    const double span = last_passes / (earlier->seconds - start_seconds);
    if (above1 > 0 && above0 > above1)
      f.rate = std::clamp(0.5 * std::log(above0 / above1) / std::log(span), kIndependentNoiseRate, most_rate);
  }
  return f;
}

}  // namespace pm

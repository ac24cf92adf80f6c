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

ErrorForecast forecast_error(const std::vector<ErrorReading>& readings, ErrorDecay decay, double start_seconds) {
  ErrorForecast f;
  f.start = start_seconds;
  if (readings.empty()) return f;
  f.last = readings.back();
  if (decay == ErrorDecay::fixed) return f;
  f.rate = decay == ErrorDecay::measured ? kAssumedShrinkRate : 0.5;
  // The latest reading against the latest one far enough before it, in the passes' time.
  const double last_passes = f.last.seconds - start_seconds;
  for (size_t i = readings.size() - 1; i-- > 0;) {
    const ErrorReading& a = readings[i];
    const double passes = a.seconds - start_seconds;
    if (passes <= 0 || a.error <= 0 || f.last.error <= 0 || last_passes < kRateSpan * passes) continue;
    if (decay == ErrorDecay::sampled) {
      // error^2 = noise / p + floor^2 through both readings, the earlier a standard error higher
      // and the later one lower; an error that did not fall even so is all floor.
      const double high = a.error + a.error_stderr, low = std::max(0.0, f.last.error - f.last.error_stderr);
      const double e0 = high * high, e1 = low * low;
      const double noise = (e0 - e1) / (1.0 / passes - 1.0 / last_passes);
      f.floor = noise > 0 ? std::sqrt(std::max(0.0, e1 - noise / last_passes)) : low;
      f.rate = noise > 0 ? 0.5 : 0.0;
      break;
    }
    const double measured = std::log(a.error / f.last.error) / std::log(last_passes / passes);
    f.rate = std::clamp(measured, decay == ErrorDecay::monte_carlo ? kLeastMonteCarloRate : 0.0, 0.5);
    break;
  }
  // The bias the last reading itself shows beside the film's own noise, where it says more.
  if (decay == ErrorDecay::sampled && f.last.floor > f.floor) {
    f.floor = std::min(f.last.floor, f.last.error);
    if (f.floor >= f.last.error) f.rate = 0;
  }
  return f;
}

}  // namespace pm

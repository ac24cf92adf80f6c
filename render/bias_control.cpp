// The bias control's grid, its launch and the comparison of its paths with the film.
#include "render/bias_control.h"

#include <algorithm>
#include <cmath>

#include "render/buffer_table.h"
#include "render/device.h"
#include "render/errors.h"

namespace pm {

namespace {

// E|e + eta| for eta ~ N(0, sigma^2): the expected absolute difference between the film and a
// control whose own noise is sigma, when the film is off by e >= 0.
double expected_abs_difference(double e, double sigma) {
  if (!(sigma > 0)) return e;
  const double z = e / (sigma * std::sqrt(2.0));
  return e * std::erf(z) + sigma * std::sqrt(2.0 / M_PI) * std::exp(-z * z);
}

// The film's |error| at one control pixel from the observed |difference|: the e >= 0 whose
// expected absolute difference is |d| (0 where |d| is within the control's own noise). Monotone
// in e, so bisection.
double absolute_error_from(double d, double sigma) {
  d = std::fabs(d);
  if (!(sigma > 0)) return d;
  if (d <= expected_abs_difference(0.0, sigma)) return 0.0;
  double lo = 0.0, hi = d;
  for (int i = 0; i < 40; ++i) {
    const double mid = 0.5 * (lo + hi);
    (expected_abs_difference(mid, sigma) < d ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

ControlGrid control_grid(int width, int height) {
  ControlGrid g;
  const double pixels = double(std::max(width, 1)) * std::max(height, 1);
  g.stride = uint32_t(std::max(1.0, std::ceil(std::sqrt(pixels / kControlPixelsTarget))));
  g.blocks_x = (uint32_t(std::max(width, 1)) + g.stride - 1) / g.stride;
  g.blocks_y = (uint32_t(std::max(height, 1)) + g.stride - 1) / g.stride;
  return g;
}

// One region's film error from its control pixels (sums over them, in radiance units), as the
// film's |error| summed over its pixels. Where the control's noise per pixel is within the
// film's RMS error there, each pixel's |error| is read through the control's noise at that pixel
// (absolute_error_from). Where the noise exceeds it, that reading errs high (a film off by e read
// through noise 2e reads about 1.5 e, through 4e 2.7 e: each pixel's |difference| is mostly the
// control's), so the region's unbiased second moments are used instead: the mean of d^2 - v is
// the film's mean squared error there and the squared mean of d less its variance the square of
// its mean error, and the film's |error| is taken as that of a normal spread of errors with this
// mean and the rest of the mean square (photon or path noise about a bias; a two-valued error
// reads 0.8 of itself). On synthetic controls whose noise was 2.2 times the film's error, readings
// of 1.28-1.67 times the truth became 0.93-1.12 times it (tests/unit/bias_control_test.cpp).
namespace {

struct RegionSums {
  double pixels = 0, difference = 0, squared_difference = 0, variance = 0, abs_error = 0;
};

double region_abs_error(const RegionSums& r) {
  if (!(r.pixels > 0)) return 0.0;
  const double mse = (r.squared_difference - r.variance) / r.pixels;
  if (r.variance / r.pixels <= mse) return r.abs_error;  // the control resolves each pixel
  const double mean_difference = r.difference / r.pixels;
  const double bias2 = std::max(0.0, mean_difference * mean_difference - r.variance / (r.pixels * r.pixels));
  const double spread2 = std::max(0.0, mse - bias2);
  return r.pixels * expected_abs_difference(std::sqrt(bias2), std::sqrt(spread2));
}

}  // namespace

BiasEstimate compare_with_control(const std::vector<float4>& control_sums, const std::vector<float4>& control_film,
                                  const ControlGrid& grid, uint64_t paths, uint32_t region_side,
                                  ControlFilmPasses film_passes, double level_of) {
  BiasEstimate e;
  e.paths = paths;
  if (paths < 2 || control_sums.size() < grid.pixels() || control_film.size() < grid.pixels()) return e;
  const double n = double(paths);
  const uint32_t side = std::max(region_side, 1u);
  const uint32_t regions_x = (grid.blocks_x + side - 1) / side, regions_y = (grid.blocks_y + side - 1) / side;
  std::vector<RegionSums> regions(size_t(regions_x) * regions_y);
  double control_total = 0, difference_total = 0, variance_total = 0;
  double squared_error_sum = 0, squared_error_squares = 0, counted = 0, noise_sum = 0;
  double squared_bias_sum = 0, squared_bias_squares = 0;
  const double all_passes = film_passes.passes, odd_passes = film_passes.odd, even_passes = all_passes - odd_passes;
  for (uint32_t by = 0; by < grid.blocks_y; ++by)
    for (uint32_t bx = 0; bx < grid.blocks_x; ++bx) {
      const size_t c = size_t(by) * grid.blocks_x + bx;
      const float4 s = control_sums[c];
      const double mean = (double(s.x) + s.y + s.z) / 3.0 / n;
      // The sample variance of one path's channel mean, and so of the control's mean here.
      const double path_variance = std::max(0.0, (double(s.w) / n - mean * mean) * n / (n - 1.0));
      const double variance = path_variance / n;
      const float4 f = control_film[c];
      const double film = (double(f.x) + f.y + f.z) / 3.0;
      if (!std::isfinite(mean) || !std::isfinite(film) || !std::isfinite(variance)) continue;
      const double d = film - mean;
      RegionSums& r = regions[size_t(by / side) * regions_x + bx / side];
      r.pixels += 1;
      r.difference += d;
      r.squared_difference += d * d;
      r.variance += variance;
      r.abs_error += absolute_error_from(d, std::sqrt(variance));
      control_total += mean;
      difference_total += d;
      variance_total += variance;
      const double squared_error = d * d - variance;  // unbiased for the MSE
      squared_error_sum += squared_error;
      squared_error_squares += squared_error * squared_error;
      if (film_passes.split()) {
        // The even and the odd passes' means are two independent estimates; their difference
        // squared, times P_even P_odd / P^2, is unbiased for the variance of the mean of all P.
        const double odd = f.w, even = (film * all_passes - odd * odd_passes) / even_passes;
        const double film_variance = (even - odd) * (even - odd) * even_passes * odd_passes / (all_passes * all_passes);
        const double squared_bias = squared_error - film_variance;
        squared_bias_sum += squared_bias;
        squared_bias_squares += squared_bias * squared_bias;
      }
      noise_sum += std::sqrt(variance);
      counted += 1;
    }
  if (!(control_total > 0) && !(level_of > 0)) return e;
  // The light the relative errors are of: the control's own, or level_of's per pixel.
  const double light_total = level_of > 0 ? level_of * counted : control_total;
  // The regions' |errors|, and their spread per pixel, from which the mean's standard error.
  double regional = 0, abs_error_sum = 0, per_pixel_sum = 0, per_pixel_squares = 0, region_count = 0;
  for (const RegionSums& r : regions) {
    if (!(r.pixels > 0)) continue;
    regional += std::sqrt(std::max(0.0, r.difference * r.difference - r.variance));
    const double abs_error = region_abs_error(r);
    abs_error_sum += abs_error;
    per_pixel_sum += abs_error / r.pixels;
    per_pixel_squares += (abs_error / r.pixels) * (abs_error / r.pixels);
    region_count += 1;
  }
  const double level = light_total / counted;
  const double mse = squared_error_sum / counted;
  const double mse_spread = counted > 1 ? std::sqrt(std::max(0.0, (squared_error_squares / counted - mse * mse) /
                                                                      (counted - 1)))
                                        : 0.0;
  // The point estimate with the control's own resolution folded in (one standard error of the
  // mean squared error): an imprecise control never reports an error of zero.
  e.mean_square = mse / (level * level);
  e.rms_error = std::sqrt(std::max(0.0, mse) + mse_spread) / level;
  const double mae = abs_error_sum / counted;
  const double per_pixel_mean = per_pixel_sum / region_count;
  const double mae_spread =
      region_count > 1 ? std::sqrt(std::max(0.0, (per_pixel_squares / region_count - per_pixel_mean * per_pixel_mean) /
                                                     (region_count - 1)))
                       : 0.0;
  // The relative mean absolute error (the tradeoff's and `compare --metric relmae`'s measure),
  // with the control's resolution folded in: one standard error, so an imprecise control never
  // reports zero; the stopping rule's upper end adds two.
  e.mean_abs_error = (mae + mae_spread) / level;
  e.mean_abs_error_upper = (mae + 2.0 * mae_spread) / level;
  e.mean_abs_error_stderr = mae_spread / level;
  e.signed_bias = difference_total / light_total;
  e.bias_error = std::sqrt(variance_total) / light_total;
  e.regional_bias = regional / light_total;
  e.control_noise = noise_sum / light_total;
  if (film_passes.split() && mse > 0 && counted > 1) {
    const double squared_bias = squared_bias_sum / counted;
    const double spread =
        std::sqrt(std::max(0.0, (squared_bias_squares / counted - squared_bias * squared_bias) / (counted - 1)));
    e.bias_floor = mae / level * std::sqrt(std::clamp((squared_bias - 2.0 * spread) / mse, 0.0, 1.0));
    e.bias_ceiling = mae / level * std::sqrt(std::clamp((squared_bias + 2.0 * spread) / mse, 0.0, 1.0));
  }
  e.known = true;
  return e;
}

double control_level(const SharedControl& control) {
  if (control.paths == 0 || control.sums.empty()) return 0;
  double total = 0;
  for (const float4& s : control.sums) total += (double(s.x) + s.y + s.z) / 3.0;
  return total / double(control.paths) / double(control.sums.size());
}

BiasEstimate paired_bias(const SharedControl& probe, const ControlGrid& grid, double level) {
  // Each control pixel's mean delta is the truth less the method's expectation there, read
  // through the deltas' own noise as compare_with_control reads a film through a control's: a
  // film of zeros against "paths" that are the deltas, 0 - mean delta its error (signed_bias:
  // the method's signed bias).
  const std::vector<float4> zeros(probe.sums.size(), float4{0, 0, 0, 0});
  return compare_with_control(probe.sums, zeros, grid, probe.paths, kControlRegionSide, {}, level);
}

BiasControl::BiasControl(Device& device, BufferTable& buffers, int width, int height)
    : device_(device), buffers_(buffers), grid_(control_grid(width, height)) {}

void BiasControl::launch(LaunchParams params, uint32_t samples, uint64_t first_sample, const PathsLaunch& paths) {
  const uint64_t items = grid_.pixels();
  params.control_stride = grid_.stride;
  params.control_samples = samples;
  params.control_first_sample = uint32_t(first_sample);
  params.control_lanes = std::min<uint32_t>(PM_CONTROL_LANES, std::max<uint32_t>(samples, 1));
  if (samples > 0) {
    if (paths) paths(params, items * params.control_lanes);
    else device_.launch(KernelId::bias_control, items * params.control_lanes, params);
  }
  device_.launch(KernelId::bias_control_sum, items, params);
}

BiasEstimate BiasControl::add_and_compare(LaunchParams params, uint32_t samples, ControlFilmPasses film_passes) {
  const uint64_t items = grid_.pixels();
  if (!cleared_) {
    device_.fill_zero(buffers_[BufferSlot::control_sums], buffers_[BufferSlot::control_sums].bytes());
    cleared_ = true;
  }
  launch(params, samples, paths_);
  paths_ += samples;
  std::vector<float4> sums(items), film(items);
  device_.download(buffers_[BufferSlot::control_sums], sums.data(), items * sizeof(float4));
  device_.download(buffers_[BufferSlot::control_film], film.data(), items * sizeof(float4));
  return compare_with_control(sums, film, grid_, paths_, kControlRegionSide, film_passes);
}

void BiasControl::grow_shared(LaunchParams params, SharedControl& shared, uint32_t samples, const PathsLaunch& paths) {
  const uint64_t items = grid_.pixels();
  DeviceBuffer& sums = buffers_[BufferSlot::control_sums];
  if (shared.sums.size() == items) device_.upload(sums, shared.sums.data(), items * sizeof(float4));
  else device_.fill_zero(sums, sums.bytes());
  launch(params, samples, shared.paths, paths);
  shared.sums.resize(items);
  device_.download(sums, shared.sums.data(), items * sizeof(float4));
  shared.paths += samples;
  cleared_ = false;  // this renderer's own control starts again when next asked
  paths_ = 0;
}

void BiasControl::adopt(const SharedControl& shared) {
  const uint64_t items = grid_.pixels();
  if (shared.sums.size() != items) throw DeviceError("error control: shared sums of another size than the control grid");
  device_.upload(buffers_[BufferSlot::control_sums], shared.sums.data(), items * sizeof(float4));
  paths_ = shared.paths;
  cleared_ = true;
}

std::vector<float4> BiasControl::film_at_control(LaunchParams params) {
  const uint64_t items = grid_.pixels();
  launch(params, 0, 0);  // reads the film at the control pixels, adds no path
  std::vector<float4> film(items);
  device_.download(buffers_[BufferSlot::control_film], film.data(), items * sizeof(float4));
  return film;
}

}  // namespace pm

// The automatic preview exposure (preview_exposure.h): luminance percentile to display white.
#include "render/preview_exposure.h"

#include <algorithm>
#include <cmath>

namespace pm {

namespace {

const double kWhitePercentile = 0.99;

double clamped_stops(double ev) {
  return std::clamp(std::round(ev * 100.0) / 100.0, -kMaxExposureStops, kMaxExposureStops);
}

}  // namespace

double automatic_exposure_ev(const std::vector<float>& rgb) {
  std::vector<double> luminance(rgb.size() / 3);
  for (size_t i = 0; i < luminance.size(); ++i) {
    const double y = 0.2126 * rgb[3 * i] + 0.7152 * rgb[3 * i + 1] + 0.0722 * rgb[3 * i + 2];
    luminance[i] = std::isfinite(y) && y > 0 ? y : 0.0;
  }
  if (luminance.empty()) return 0;
  // Nearest rank: the smallest value at or above which lie no more than 1 % of the pixels.
  const size_t rank = size_t(std::ceil(kWhitePercentile * double(luminance.size()))) - 1;
  std::nth_element(luminance.begin(), luminance.begin() + rank, luminance.end());
  double white = luminance[rank];
  if (white <= 0) white = *std::max_element(luminance.begin() + rank, luminance.end());
  if (white <= 0) return 0;
  return clamped_stops(-std::log2(white));
}

}  // namespace pm

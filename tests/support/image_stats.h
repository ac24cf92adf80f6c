// Small image statistics for render tests: finiteness, mean, and the relative difference of
// two renders of the same scene.
#pragma once

#include <cmath>
#include <vector>

namespace pm::test {

struct ImageDifference {
  double mean_relative = 0;  // sum |a - b| / sum |b| over all channels
  double max_absolute = 0;
  double mean_value = 0;     // mean of b, for scale
};

inline ImageDifference compare_rgb(const std::vector<float>& a, const std::vector<float>& b) {
  ImageDifference d;
  double diff = 0, sum = 0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i) {
    double e = std::fabs(double(a[i]) - double(b[i]));
    diff += e;
    sum += std::fabs(double(b[i]));
    d.max_absolute = std::max(d.max_absolute, e);
  }
  d.mean_relative = sum > 0 ? diff / sum : diff;
  d.mean_value = b.empty() ? 0 : sum / double(b.size());
  return d;
}

inline double mean(const std::vector<float>& v) {
  double sum = 0;
  for (float x : v) sum += x;
  return v.empty() ? 0 : sum / double(v.size());
}

inline bool all_finite(const std::vector<float>& v) {
  for (float x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

}  // namespace pm::test

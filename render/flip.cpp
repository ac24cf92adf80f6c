// LDR-FLIP and HDR-FLIP from the equations of Andersson et al. 2020 and 2021; see flip.h for the
// pipeline and the constants' roles.
#include "render/flip.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace pm::flip {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Colour pipeline constants (FLIP 2020, section 4.1).
constexpr float kQc = 0.7f;   // exponent of the HyAB distance
constexpr float kPc = 0.4f;   // fraction of c_max^q_c ...
constexpr float kPt = 0.95f;  // ... that maps to this error
// Feature pipeline constants (section 4.2).
constexpr float kQf = 0.5f;         // exponent of the feature difference
constexpr double kFeatureWidth = 0.082;  // w, degrees; the detectors' Gaussian has sigma = 0.5 w ppd
// HDR-FLIP: exposures put the chosen luminance at this tone-mapped value.
constexpr float kExposureTarget = 0.85f;
// HDR-FLIP evaluates its exposures on at most this many threads, each holding several full-size
// float images while it works (`pmrender compare` of two 1920 x 1080 frames peaks at 619 MB with
// two threads).
constexpr unsigned kMaxThreads = 8;

// Contrast sensitivity functions as sums of two Gaussians (FLIP 2020, Table 1): spatial kernel
// S(x) = sum_i a_i sqrt(pi / b_i) exp(-pi^2 x^2 / b_i), x in degrees.
struct CsfParams {
  double a1, b1, a2, b2;
};
constexpr CsfParams kCsf[3] = {
    {1.0, 0.0047, 0.0, 1e-5},     // achromatic (Yy)
    {1.0, 0.0053, 0.0, 1e-5},     // red-green (Cx)
    {34.1, 0.04, 13.5, 0.025},    // blue-yellow (Cz)
};
constexpr double kCsfMaxB = 0.04;

// Linear sRGB primaries with a D65 white (IEC 61966-2-1).
constexpr float kRgbToXyz[3][3] = {{0.4124564f, 0.3575761f, 0.1804375f},
                                   {0.2126729f, 0.7151522f, 0.0721750f},
                                   {0.0193339f, 0.1191920f, 0.9503041f}};
constexpr float kXyzToRgb[3][3] = {{3.2404542f, -1.5371385f, -0.4985314f},
                                   {-0.9692660f, 1.8760108f, 0.0415560f},
                                   {0.0556434f, -0.2040259f, 1.0572252f}};

Color mul(const float m[3][3], Color c) {
  return {m[0][0] * c.x + m[0][1] * c.y + m[0][2] * c.z, m[1][0] * c.x + m[1][1] * c.y + m[1][2] * c.z,
          m[2][0] * c.x + m[2][1] * c.y + m[2][2] * c.z};
}

// The reference white: XYZ of linear RGB (1, 1, 1).
Color white() {
  static const Color w = mul(kRgbToXyz, {1.0f, 1.0f, 1.0f});
  return w;
}

float clamp01(float v) { return std::min(std::max(v, 0.0f), 1.0f); }

float lab_f(float t) {
  const float delta = 6.0f / 29.0f;
  return t > delta * delta * delta ? std::cbrt(t) : t / (3.0f * delta * delta) + 4.0f / 29.0f;
}

std::vector<float> gaussian_taps(int radius, double sigma_or_b, bool csf, double ppd) {
  std::vector<float> taps(2 * radius + 1);
  for (int i = -radius; i <= radius; ++i) {
    double x = i;
    double v = csf ? std::exp(-kPi * kPi * (x / ppd) * (x / ppd) / sigma_or_b)
                   : std::exp(-x * x / (2.0 * sigma_or_b * sigma_or_b));
    taps[i + radius] = float(v);
  }
  return taps;
}

double sum(const std::vector<float>& v) {
  double s = 0;
  for (float x : v) s += x;
  return s;
}

int feature_radius(double ppd) { return int(std::ceil(3.0 * 0.5 * kFeatureWidth * ppd)); }
double feature_sigma(double ppd) { return 0.5 * kFeatureWidth * ppd; }

// A derivative factor normalised so that its positive taps sum to 1 and its negative taps to -1.
void normalise_signed(std::vector<float>& taps) {
  double positive = 0, negative = 0;
  for (float t : taps) (t > 0 ? positive : negative) += t;
  for (float& t : taps) {
    if (t > 0) t = float(t / positive);
    else if (t < 0) t = float(t / -negative);
  }
}

SeparableKernel derivative_kernel(double ppd, bool along_x, int order) {
  const int r = feature_radius(ppd);
  const double sigma = feature_sigma(ppd);
  std::vector<float> g = gaussian_taps(r, sigma, false, ppd);
  std::vector<float> d(g.size());
  for (int i = -r; i <= r; ++i) {
    double x = i;
    d[i + r] = order == 1 ? float(-x * g[i + r]) : float((x * x / (sigma * sigma) - 1.0) * g[i + r]);
  }
  normalise_signed(d);
  const double gs = sum(g);
  for (float& t : g) t = float(t / gs);
  SeparableTerm term;
  term.weight = 1.0f;
  term.x_taps = along_x ? d : g;
  term.y_taps = along_x ? g : d;
  return {term};
}

}  // namespace

double pixels_per_degree(double distance_m, double width_px, double width_m) {
  return distance_m * (width_px / width_m) * (kPi / 180.0);
}

double default_pixels_per_degree() { return pixels_per_degree(0.7, 3840.0, 0.7); }

Color linear_rgb_to_xyz(Color rgb) { return mul(kRgbToXyz, rgb); }
Color xyz_to_linear_rgb(Color xyz) { return mul(kXyzToRgb, xyz); }

Color xyz_to_ycxcz(Color xyz) {
  const Color w = white();
  const float x = xyz.x / w.x, y = xyz.y / w.y, z = xyz.z / w.z;
  return {116.0f * y - 16.0f, 500.0f * (x - y), 200.0f * (y - z)};
}

Color ycxcz_to_xyz(Color c) {
  const Color w = white();
  const float y = (c.x + 16.0f) / 116.0f;
  const float x = y + c.y / 500.0f;
  const float z = y - c.z / 200.0f;
  return {x * w.x, y * w.y, z * w.z};
}

Color xyz_to_lab(Color xyz) {
  const Color w = white();
  const float fx = lab_f(xyz.x / w.x), fy = lab_f(xyz.y / w.y), fz = lab_f(xyz.z / w.z);
  return {116.0f * fy - 16.0f, 500.0f * (fx - fy), 200.0f * (fy - fz)};
}

Color hunt_adjust(Color lab) { return {lab.x, 0.01f * lab.x * lab.y, 0.01f * lab.x * lab.z}; }

float hyab(Color a, Color b) {
  const float da = a.y - b.y, db = a.z - b.z;
  return std::fabs(a.x - b.x) + std::sqrt(da * da + db * db);
}

float max_color_distance() {
  static const float cmax = hyab(hunt_adjust(xyz_to_lab(linear_rgb_to_xyz({0, 1, 0}))),
                                 hunt_adjust(xyz_to_lab(linear_rgb_to_xyz({0, 0, 1}))));
  return cmax;
}

float remap_color_error(float distance) {
  const float cmax = std::pow(max_color_distance(), kQc);
  const float e = std::pow(std::max(distance, 0.0f), kQc);
  const float knee = kPc * cmax;
  if (e < knee) return kPt * e / knee;
  return std::min(1.0f, kPt + (e - knee) / (cmax - knee) * (1.0f - kPt));
}

float feature_error(float edge_reference, float edge_test, float point_reference, float point_test) {
  const float d = std::max(std::fabs(edge_reference - edge_test), std::fabs(point_reference - point_test));
  return std::pow(std::min(d / std::sqrt(2.0f), 1.0f), kQf);
}

float combine_errors(float color_error, float feature_error) {
  return std::pow(clamp01(color_error), 1.0f - clamp01(feature_error));
}

SeparableKernel csf_kernel(int channel, double ppd) {
  if (channel < 0 || channel > 2) throw std::invalid_argument("csf_kernel: channel must be 0, 1 or 2");
  if (!(ppd > 0) || !std::isfinite(ppd)) throw std::invalid_argument("csf_kernel: pixels per degree must be positive");
  const int r = int(std::ceil(3.0 * std::sqrt(kCsfMaxB / (2.0 * kPi * kPi)) * ppd));
  const CsfParams& p = kCsf[channel];
  SeparableKernel kernel;
  double total = 0;
  for (int i = 0; i < 2; ++i) {
    const double a = i == 0 ? p.a1 : p.a2, b = i == 0 ? p.b1 : p.b2;
    if (a == 0) continue;
    SeparableTerm term;
    term.x_taps = gaussian_taps(r, b, true, ppd);
    term.y_taps = term.x_taps;
    const double s = sum(term.x_taps);
    term.weight = float(a * std::sqrt(kPi / b));
    total += term.weight * s * s;
    kernel.push_back(std::move(term));
  }
  for (SeparableTerm& term : kernel) term.weight = float(term.weight / total);
  return kernel;
}

SeparableKernel edge_kernel(double ppd, bool along_x) { return derivative_kernel(ppd, along_x, 1); }
SeparableKernel point_kernel(double ppd, bool along_x) { return derivative_kernel(ppd, along_x, 2); }

// Edge pixels repeat (clamp to the border). Each output sums its taps in the same order whatever
// the loop structure, so the result does not depend on it: the horizontal pass reads a padded copy
// of the line (no clamp per tap), the vertical pass runs tap by tap over whole rows (sequential
// reads) into a row of double accumulators.
std::vector<float> convolve(const std::vector<float>& image, int width, int height, const SeparableKernel& kernel) {
  std::vector<float> out(image.size(), 0.0f), rows(image.size());
  std::vector<float> padded;
  std::vector<double> acc(static_cast<size_t>(width));
  for (const SeparableTerm& term : kernel) {
    const int rx = int(term.x_taps.size() / 2), ry = int(term.y_taps.size() / 2);
    padded.resize(size_t(width) + 2 * size_t(rx));
    for (int y = 0; y < height; ++y) {
      const float* line = &image[size_t(y) * width];
      for (int i = 0; i < width + 2 * rx; ++i) padded[i] = line[std::min(std::max(i - rx, 0), width - 1)];
      for (int x = 0; x < width; ++x) {
        double sum = 0;
        const float* window = &padded[size_t(x)];  // window[k + rx] is pixel x + k
        for (int k = 0; k <= 2 * rx; ++k) sum += term.x_taps[k] * window[k];
        rows[size_t(y) * width + x] = float(sum);
      }
    }
    for (int y = 0; y < height; ++y) {
      std::fill(acc.begin(), acc.end(), 0.0);
      for (int k = -ry; k <= ry; ++k) {
        const float tap = term.y_taps[k + ry];  // float products, as before: bit for bit the same sums
        const float* row = &rows[size_t(std::min(std::max(y + k, 0), height - 1)) * width];
        for (int x = 0; x < width; ++x) acc[x] += tap * row[x];
      }
      float* line = &out[size_t(y) * width];
      for (int x = 0; x < width; ++x) line[x] += float(term.weight * acc[x]);
    }
  }
  return out;
}

namespace {

struct Prepared {
  std::vector<Color> lab;     // Hunt-adjusted L*a*b* of the CSF-filtered image
  std::vector<float> edge;    // gradient magnitude of the edge detector
  std::vector<float> point;   // gradient magnitude of the point detector
};

Prepared prepare(const std::vector<float>& rgb, int width, int height, double ppd) {
  const size_t n = size_t(width) * height;
  std::vector<float> channel[3];
  for (auto& c : channel) c.resize(n);
  std::vector<float> luminance(n);
  for (size_t i = 0; i < n; ++i) {
    Color c = xyz_to_ycxcz(linear_rgb_to_xyz({clamp01(rgb[3 * i]), clamp01(rgb[3 * i + 1]), clamp01(rgb[3 * i + 2])}));
    channel[0][i] = c.x;
    channel[1][i] = c.y;
    channel[2][i] = c.z;
    luminance[i] = (c.x + 16.0f) / 116.0f;
  }
  for (int k = 0; k < 3; ++k) channel[k] = convolve(channel[k], width, height, csf_kernel(k, ppd));
  Prepared p;
  p.lab.resize(n);
  for (size_t i = 0; i < n; ++i) {
    Color rgb_filtered = xyz_to_linear_rgb(ycxcz_to_xyz({channel[0][i], channel[1][i], channel[2][i]}));
    rgb_filtered = {clamp01(rgb_filtered.x), clamp01(rgb_filtered.y), clamp01(rgb_filtered.z)};
    p.lab[i] = hunt_adjust(xyz_to_lab(linear_rgb_to_xyz(rgb_filtered)));
  }
  const std::vector<float> ex = convolve(luminance, width, height, edge_kernel(ppd, true));
  const std::vector<float> ey = convolve(luminance, width, height, edge_kernel(ppd, false));
  const std::vector<float> px = convolve(luminance, width, height, point_kernel(ppd, true));
  const std::vector<float> py = convolve(luminance, width, height, point_kernel(ppd, false));
  p.edge.resize(n);
  p.point.resize(n);
  for (size_t i = 0; i < n; ++i) {
    p.edge[i] = std::sqrt(ex[i] * ex[i] + ey[i] * ey[i]);
    p.point[i] = std::sqrt(px[i] * px[i] + py[i] * py[i]);
  }
  return p;
}

void check_sizes(const std::vector<float>& a, const std::vector<float>& b, int width, int height) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("flip: image size must be positive");
  const size_t n = size_t(width) * height * 3;
  if (a.size() != n || b.size() != n) throw std::invalid_argument("flip: images must hold width*height*3 floats");
}

}  // namespace

std::vector<float> ldr_flip(const std::vector<float>& reference, const std::vector<float>& test, int width,
                            int height, double ppd) {
  check_sizes(reference, test, width, height);
  const Prepared r = prepare(reference, width, height, ppd);
  const Prepared t = prepare(test, width, height, ppd);
  std::vector<float> error(size_t(width) * height);
  for (size_t i = 0; i < error.size(); ++i) {
    const float color = remap_color_error(hyab(r.lab[i], t.lab[i]));
    const float feature = feature_error(r.edge[i], t.edge[i], r.point[i], t.point[i]);
    error[i] = combine_errors(color, feature);
  }
  return error;
}

float tone_map(float x) {
  const double a = 0.6 * 0.6 * 2.51, b = 0.6 * 0.03, c = 0.6 * 0.6 * 2.43, d = 0.6 * 0.59, e = 0.14;
  const double v = std::max(double(x), 0.0);
  return clamp01(float((a * v * v + b * v) / (c * v * v + d * v + e)));
}

float inverse_tone_map(float y) {
  const double a = 0.6 * 0.6 * 2.51, b = 0.6 * 0.03, c = 0.6 * 0.6 * 2.43, d = 0.6 * 0.59, e = 0.14;
  if (!(y > 0)) return 0.0f;
  // y (c x^2 + d x + e) = a x^2 + b x  ->  (a - y c) x^2 + (b - y d) x - y e = 0, positive root.
  const double qa = a - y * c, qb = b - y * d, qc = -y * e;
  if (std::fabs(qa) < 1e-12) return float(-qc / qb);
  return float((-qb + std::sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa));
}

ExposureRange exposure_range(const std::vector<float>& rgb) {
  std::vector<float> luminance;
  luminance.reserve(rgb.size() / 3);
  float max_l = 0;
  for (size_t i = 0; i + 2 < rgb.size(); i += 3) {
    const float l = 0.2126f * rgb[i] + 0.7152f * rgb[i + 1] + 0.0722f * rgb[i + 2];
    luminance.push_back(l);
    max_l = std::max(max_l, l);
  }
  ExposureRange range;
  if (!(max_l > 0)) return range;  // all black: exposure 0 only
  auto median_of = [](std::vector<float> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  float median = median_of(luminance);
  if (!(median > 0)) {
    std::vector<float> positive;
    for (float l : luminance)
      if (l > 0) positive.push_back(l);
    median = median_of(positive);
  }
  const double x_max = inverse_tone_map(kExposureTarget);
  range.start = std::log2(x_max / max_l);
  range.stop = std::log2(x_max / median);
  range.count = std::max(2, int(std::ceil(range.stop - range.start)));
  return range;
}

HdrFlipResult hdr_flip(const std::vector<float>& reference, const std::vector<float>& test, int width, int height,
                       double ppd) {
  check_sizes(reference, test, width, height);
  HdrFlipResult result;
  result.exposures = exposure_range(reference);
  const size_t pixels = size_t(width) * height;
  // The exposures are independent LDR-FLIP evaluations: thread w takes exposures w, w + workers,
  // ..., keeping the maximum of its own; the maximum of those is the same whatever the order
  // (1080p takes seconds per exposure, and a tradeoff sweep compares every setting).
  const int count = result.exposures.count;
  const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
  const unsigned workers = std::min({unsigned(count), hardware, kMaxThreads});
  std::vector<std::vector<float>> maxima(workers, std::vector<float>(pixels, 0.0f));
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto work = [&](unsigned w) {
    try {
      std::vector<float> r(reference.size()), t(test.size());
      for (int k = int(w); k < count; k += int(workers)) {
        const double c = result.exposures.start + k * (result.exposures.stop - result.exposures.start) / double(count - 1);
        const float scale = float(std::exp2(c));
        for (size_t i = 0; i < reference.size(); ++i) {
          r[i] = tone_map(scale * reference[i]);
          t[i] = tone_map(scale * test[i]);
        }
        const std::vector<float> e = ldr_flip(r, t, width, height, ppd);
        for (size_t i = 0; i < pixels; ++i) maxima[w][i] = std::max(maxima[w][i], e[i]);
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = std::current_exception();
    }
  };
  std::vector<std::thread> threads;
  try {
    for (unsigned w = 1; w < workers; ++w) threads.emplace_back(work, w);
  } catch (...) {  // no thread to be had: let the started ones finish, then report
    for (std::thread& thread : threads) thread.join();
    throw;
  }
  work(0);
  for (std::thread& thread : threads) thread.join();
  if (failure) std::rethrow_exception(failure);
  result.error = std::move(maxima[0]);
  for (unsigned w = 1; w < workers; ++w)
    for (size_t i = 0; i < pixels; ++i) result.error[i] = std::max(result.error[i], maxima[w][i]);
  double total = 0;
  for (float e : result.error) total += e;
  result.mean = total / double(result.error.size());
  return result;
}

}  // namespace pm::flip

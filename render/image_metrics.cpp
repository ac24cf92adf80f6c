// Image differences for `pmrender compare` and the golden-image tests.
#include "render/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "render/errors.h"

namespace pm {

namespace {

constexpr double kRelMseEpsilon = 0.01;  // keeps relmse finite where the reference is black

std::string layer_label(const std::string& layer) { return layer.empty() ? "combined" : layer; }

}  // namespace

ImageMetric parse_image_metric(const std::string& name) {
  if (name == "flip") return ImageMetric::flip;
  if (name == "rmse") return ImageMetric::rmse;
  if (name == "relmse") return ImageMetric::relmse;
  if (name == "mean") return ImageMetric::mean;
  if (name == "relmae") return ImageMetric::relmae;
  throw SettingError("metric", "expected flip, rmse, relmse, mean or relmae, got '" + name + "'");
}

const char* image_metric_name(ImageMetric metric) {
  switch (metric) {
    case ImageMetric::flip: return "flip";
    case ImageMetric::rmse: return "rmse";
    case ImageMetric::relmse: return "relmse";
    case ImageMetric::mean: return "mean";
    case ImageMetric::relmae: return "relmae";
  }
  return "?";
}

double ImageComparison::value(ImageMetric metric) const {
  switch (metric) {
    case ImageMetric::flip: return flip;
    case ImageMetric::rmse: return rmse;
    case ImageMetric::relmse: return relmse;
    case ImageMetric::mean: return mean;
    case ImageMetric::relmae: return relmae;
  }
  return 0;
}

const std::vector<float>& ImageComparison::map(ImageMetric metric) const {
  switch (metric) {
    case ImageMetric::flip: return flip_map;
    case ImageMetric::rmse: return rmse_map;
    case ImageMetric::relmse: return relmse_map;
    case ImageMetric::mean:
    case ImageMetric::relmae: return mean_map;
  }
  return flip_map;
}

ImageComparison compare_images(const std::vector<float>& reference, const std::vector<float>& test, int width,
                               int height, double ppd) {
  const size_t pixels = size_t(width) * size_t(height);
  if (width <= 0 || height <= 0 || reference.size() != 3 * pixels || test.size() != 3 * pixels)
    throw InputError("compare: images of different sizes");
  ImageComparison c;
  c.width = width;
  c.height = height;
  c.ppd = ppd;
  flip::HdrFlipResult flip = flip::hdr_flip(reference, test, width, height, ppd);
  c.flip = flip.mean;
  c.flip_map = std::move(flip.error);
  c.exposures = flip.exposures;

  double sum_ref = 0, sum_test = 0, sq = 0, rel = 0, abs_sum = 0;
  for (size_t i = 0; i < 3 * pixels; ++i) {
    sum_ref += reference[i];
    sum_test += test[i];
  }
  const double mean_ref = sum_ref / double(3 * pixels);
  const double mean_scale = std::fabs(mean_ref) > 0 ? 1.0 / std::fabs(mean_ref) : 1.0;
  c.rmse_map.resize(pixels);
  c.relmse_map.resize(pixels);
  c.mean_map.resize(pixels);
  for (size_t p = 0; p < pixels; ++p) {
    double psq = 0, prel = 0, pabs = 0;
    for (int k = 0; k < 3; ++k) {
      const double r = reference[3 * p + k], d = double(test[3 * p + k]) - r;
      psq += d * d;
      prel += d * d / (r * r + kRelMseEpsilon);
      pabs += std::fabs(d);
    }
    sq += psq;
    rel += prel;
    abs_sum += pabs;
    c.rmse_map[p] = float(std::sqrt(psq / 3.0));
    c.relmse_map[p] = float(prel / 3.0);
    c.mean_map[p] = float(pabs / 3.0 * mean_scale);
  }
  c.rmse = std::sqrt(sq / double(3 * pixels));
  c.relmse = rel / double(3 * pixels);
  c.mean = std::fabs(sum_test - sum_ref) / double(3 * pixels) * mean_scale;
  c.relmae = abs_sum / double(3 * pixels) * mean_scale;
  return c;
}

namespace {
double sum(const std::vector<float>& v) {
  double s = 0;
  for (float x : v) s += x;
  return s;
}
}  // namespace

LightBias light_bias(const FrameImage& reference, const FrameImage& test) {
  LightBias b;
  const ImageLayer* ref_combined = reference.find("");
  const ImageLayer* test_combined = test.find("");
  if (!ref_combined || !test_combined) return b;
  const double ref_sum = sum(ref_combined->rgb), test_sum = sum(test_combined->rgb);
  b.mean = ref_sum > 0 ? test_sum / ref_sum - 1.0 : 0.0;
  const ImageLayer* test_direct_layer = test.find("direct");
  if (!test_direct_layer) return b;
  const double test_direct = sum(test_direct_layer->rgb);
  const ImageLayer* ref_direct_layer = reference.find("direct");
  const double ref_direct = ref_direct_layer ? sum(ref_direct_layer->rgb) : test_direct;
  const double test_ratio = test_direct > 0 ? (test_sum - test_direct) / test_direct : 0.0;
  const double ref_ratio = ref_direct > 0 ? (ref_sum - ref_direct) / ref_direct : 0.0;
  b.indirect = ref_ratio > 0 ? test_ratio / ref_ratio - 1.0 : 0.0;
  return b;
}

const ImageLayer& require_layer(const FrameImage& image, const std::string& layer, const std::string& file) {
  const std::string name = layer == "combined" ? "" : layer;
  if (const ImageLayer* found = image.find(name)) return *found;
  std::ostringstream have;
  for (size_t i = 0; i < image.layers.size(); ++i) have << (i ? ", " : "") << layer_label(image.layers[i].name);
  throw InputError(file + ": no layer '" + layer_label(name) + "' (the file has: " + have.str() + ")");
}

void require_finite(const std::vector<float>& rgb, int width, const std::string& file, const std::string& layer) {
  static const char* kChannels = "RGB";
  for (size_t i = 0; i < rgb.size(); ++i) {
    if (std::isfinite(rgb[i])) continue;
    const size_t pixel = i / 3;
    std::ostringstream s;
    s << file << ": layer " << layer_label(layer == "combined" ? "" : layer) << ": pixel (" << pixel % size_t(width)
      << ", " << pixel / size_t(width) << ") channel " << kChannels[i % 3] << " is "
      << (std::isnan(rgb[i]) ? "NaN" : rgb[i] > 0 ? "+Inf" : "-Inf");
    throw InputError(s.str());
  }
}

FrameImage error_map_image(const std::vector<float>& map, int width, int height) {
  FrameImage image;
  image.width = width;
  image.height = height;
  ImageLayer layer;
  layer.rgb.resize(map.size() * 3);
  for (size_t i = 0; i < map.size(); ++i) layer.rgb[3 * i] = layer.rgb[3 * i + 1] = layer.rgb[3 * i + 2] = map[i];
  image.layers.push_back(std::move(layer));
  return image;
}

FlickerStats sequence_flicker(const std::vector<std::vector<float>>& frames) {
  FlickerStats stats;
  if (frames.size() < 2) return stats;
  double total = 0;
  for (size_t f = 1; f < frames.size(); ++f) {
    const std::vector<float>& a = frames[f - 1];
    const std::vector<float>& b = frames[f];
    double diff = 0, level = 0;
    for (size_t i = 0; i < a.size() && i < b.size(); ++i) {
      diff += std::fabs(double(b[i]) - double(a[i]));
      level += 0.5 * (std::fabs(double(a[i])) + std::fabs(double(b[i])));
    }
    const double relative = level > 0 ? diff / level : 0.0;
    total += relative;
    stats.max = std::max(stats.max, relative);
  }
  stats.mean = total / double(frames.size() - 1);
  return stats;
}

}  // namespace pm

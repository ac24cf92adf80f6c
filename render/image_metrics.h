// Differences of two renders of the same frame, as `pmrender compare`, `pmrender tradeoff` and the
// golden-image tests compute them: the perceptual HDR-FLIP (render/flip.h) and four plain
// statistics, each with a per-pixel error map, and the signed biases of the light. Bad input
// (different sizes, a missing layer, NaN or Inf) is a pm::InputError naming the file and, for
// non-finite values, the pixel.
#pragma once

#include <string>
#include <vector>

#include "render/flip.h"
#include "render/image.h"

namespace pm {

enum class ImageMetric {
  flip,    // mean HDR-FLIP over the image, in [0, 1]
  rmse,    // sqrt(mean over pixels and channels of (test - reference)^2), radiance units
  relmse,  // mean over pixels and channels of (test - reference)^2 / (reference^2 + 0.01)
  mean,    // |mean(test) - mean(reference)| / mean(reference), means over pixels and channels
  relmae,  // sum |test - reference| / sum reference over pixels and channels (relative mean abs. error)
};

// "flip", "rmse", "relmse", "mean", "relmae"; SettingError for the setting "metric" otherwise.
ImageMetric parse_image_metric(const std::string& name);
const char* image_metric_name(ImageMetric metric);

struct ImageComparison {
  int width = 0, height = 0;
  double flip = 0, rmse = 0, relmse = 0, mean = 0, relmae = 0;
  flip::ExposureRange exposures;  // HDR-FLIP's exposures
  double ppd = 0;                 // HDR-FLIP's viewing conditions

  // Per-pixel error maps, width*height each: HDR-FLIP; sqrt of the channel-mean squared
  // difference; channel-mean relative squared difference; channel-mean |difference| divided by
  // mean(reference). Each map's mean is its metric, except rmse (root of the mean of squares);
  // mean_map's mean is relmae (mean's own value is the difference of the means).
  std::vector<float> flip_map, rmse_map, relmse_map, mean_map;

  double value(ImageMetric metric) const;
  const std::vector<float>& map(ImageMetric metric) const;
};

// Both images are linear RGB, width*height*3 floats, already checked finite.
ImageComparison compare_images(const std::vector<float>& reference, const std::vector<float>& test, int width,
                               int height, double ppd = flip::default_pixels_per_degree());

// Signed biases of a render's light against a reference render of the same frame (the
// combined layers, and the direct layers where the files have them).
struct LightBias {
  double mean = 0;  // mean(test) / mean(reference) - 1
  // (indirect / direct of the test) / (indirect / direct of the reference) - 1, indirect being
  // everything but the direct layer: the bias of the indirect light once the direct light, the
  // same in both when the camera pass is, is matched. The reference's direct layer is the test's
  // when the reference has none; 0 when the test has none.
  double indirect = 0;
};
LightBias light_bias(const FrameImage& reference, const FrameImage& test);

// The named layer ("" or "combined": the combined image) of an image read from file; InputError
// naming the file, the layer and the layers the file has when it is missing.
const ImageLayer& require_layer(const FrameImage& image, const std::string& layer, const std::string& file);

// InputError "<file>: layer <name>: pixel (x, y) channel G is NaN" at the first non-finite value.
void require_finite(const std::vector<float>& rgb, int width, const std::string& file, const std::string& layer);

// The error map as an image to write: the combined layer holds the map as grey (R = G = B).
FrameImage error_map_image(const std::vector<float>& map, int width, int height);

// Mean absolute frame-to-frame difference of a sequence of images, relative to their mean:
// for each consecutive pair, sum |b - a| / sum (|a| + |b|) / 2 over all pixels and channels,
// then the mean and the largest value over the pairs. Fewer than two frames give zeros.
struct FlickerStats {
  double mean = 0;
  double max = 0;
};
FlickerStats sequence_flicker(const std::vector<std::vector<float>>& frames);

}  // namespace pm

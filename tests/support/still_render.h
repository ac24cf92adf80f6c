// One still frame of a scene on a device at a small resolution, with its statistics, and the
// per-layer figures the end-to-end tests compare.
#pragma once

#include <cmath>
#include <string>

#include "render/renderer.h"

namespace pm::test {

struct StillRender {
  FrameImage image;
  FrameStats stats;
};

inline StillRender render_still(Device& device, const Scene& scene, RenderSettings settings, int width, int height) {
  settings.width = width;
  settings.height = height;
  Renderer renderer(device, scene, settings);
  StillRender r;
  r.image = renderer.render_frame(0, &r.stats);
  return r;
}

// Mean over pixels and channels of a layer ("" = combined); NaN when the layer is missing.
inline double layer_mean(const FrameImage& image, const std::string& name) {
  const ImageLayer* layer = image.find(name);
  if (!layer || layer->rgb.empty()) return std::nan("");
  double sum = 0;
  for (float v : layer->rgb) sum += v;
  return sum / double(layer->rgb.size());
}

// Fraction of the pixels whose layer is exactly black (all three channels zero).
inline double black_fraction(const FrameImage& image, const std::string& name) {
  const ImageLayer* layer = image.find(name);
  if (!layer || layer->rgb.empty()) return std::nan("");
  size_t black = 0, pixels = layer->rgb.size() / 3;
  for (size_t i = 0; i < pixels; ++i)
    black += layer->rgb[3 * i] == 0.0f && layer->rgb[3 * i + 1] == 0.0f && layer->rgb[3 * i + 2] == 0.0f;
  return double(black) / double(pixels);
}

}  // namespace pm::test

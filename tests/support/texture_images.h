// Small images for the texture tests: PNG bytes encoded with stb_image_write (the library the
// previews use), written by the tests themselves, so no image file is committed.
#pragma once

#include <stb_image_write.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace pm::test {

// A PNG of width x height texels, `channels` bytes each (1 grey, 2 grey + alpha, 3 RGB, 4 RGBA),
// rows top first.
inline std::string png_bytes(int width, int height, int channels, const std::vector<uint8_t>& texels) {
  if (texels.size() != size_t(width) * size_t(height) * size_t(channels)) throw std::invalid_argument("png_bytes: size");
  std::string png;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
  };
  if (!stbi_write_png_to_func(append, &png, width, height, channels, texels.data(), width * channels))
    throw std::runtime_error("png_bytes: stbi_write_png_to_func failed");
  return png;
}

// An RGB image of one colour.
inline std::string uniform_png(int width, int height, uint8_t r, uint8_t g, uint8_t b) {
  std::vector<uint8_t> texels;
  for (int i = 0; i < width * height; ++i) texels.insert(texels.end(), {r, g, b});
  return png_bytes(width, height, 3, texels);
}

// The linear value of an 8-bit sRGB code (IEC 61966-2-1), in double, for expectations.
inline double srgb_to_linear(int code) {
  const double c = code / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

}  // namespace pm::test

// PNG previews: the tone map (preview_png.h), the encoding through stb_image_write into memory,
// the exposure's text chunks, and the write through an AtomicFile.
#include "render/preview_png.h"

#include <stb_image_write.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "render/atomic_file.h"
#include "render/errors.h"
#include "render/interruption.h"
#include "render/png_text_chunk.h"
#include "render/preview_exposure.h"

namespace pm {

const char kPreviewExposureKeyword[] = "pmrender/exposure_ev";
const char kPreviewExposureSourceKeyword[] = "pmrender/exposure_from";

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw DeviceError("cannot write preview PNG '" + path + "': " + why);
}

// stb hands the encoded PNG to this callback in one piece or several.
void append_to_string(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
}

// The shortest text that reads back as exactly this value ("2.47", "-0.5").
std::string shortest_text(double value) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof(text), value);
  return std::string(text, result.ptr);
}

}  // namespace

uint8_t preview_tone_map(float linear, float scale) {
  const float v = std::clamp(linear * scale, 0.0f, 1.0f);  // NaN never reaches here: images are finite
  const float encoded = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
  return uint8_t(std::lround(encoded * 255.0f));
}

double write_preview_png(const std::string& path, const FrameImage& image, std::optional<double> exposure_ev) {
  const ImageLayer* combined = image.find("");
  if (!combined) fail(path, "the image has no combined layer");
  const size_t values = size_t(std::max(image.width, 0)) * size_t(std::max(image.height, 0)) * 3;
  if (values == 0 || combined->rgb.size() != values) fail(path, "the combined layer is malformed");
  if (exposure_ev && !(std::abs(*exposure_ev) <= kMaxExposureStops))
    fail(path, "exposure " + shortest_text(*exposure_ev) + " is outside +-" + shortest_text(kMaxExposureStops) + " stops");

  const double ev = exposure_ev ? *exposure_ev : automatic_exposure_ev(combined->rgb);
  const float scale = float(std::exp2(ev));
  std::vector<uint8_t> pixels(values);
  std::transform(combined->rgb.begin(), combined->rgb.end(), pixels.begin(),
                 [scale](float linear) { return preview_tone_map(linear, scale); });
  try {
    std::string png;
    if (!stbi_write_png_to_func(append_to_string, &png, image.width, image.height, 3, pixels.data(), image.width * 3))
      throw std::runtime_error("the PNG encoder failed");
    add_png_text(png, {{kPreviewExposureKeyword, shortest_text(ev)},
                       {kPreviewExposureSourceKeyword,
                        exposure_ev ? "--exposure" : "automatic: the 99th percentile of luminance as white"}});
    // The temporary keeps a .png ending so nothing looking at the folder mistakes it for a frame.
    AtomicFile file(path, ".png");
    file.write(png.data(), png.size());
    file.commit();
  } catch (const std::exception& e) {
    if (interruption_signal() != 0) throw Interrupted();
    fail(path, e.what());
  }
  return ev;
}

}  // namespace pm

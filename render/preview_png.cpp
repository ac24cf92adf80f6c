// PNG previews: the tone map (preview_png.h) and the encoding through stb_image_write into an
// AtomicFile.
#include "render/preview_png.h"

#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "render/atomic_file.h"
#include "render/errors.h"
#include "render/interruption.h"

namespace pm {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw DeviceError("cannot write preview PNG '" + path + "': " + why);
}

// stb hands the encoded PNG to this callback (in one piece or several); errors are kept for later
// because the callback cannot throw through stb's C code.
struct PngSink {
  AtomicFile* file;
  std::string error;
};

void write_to_sink(void* context, void* data, int size) {
  PngSink& sink = *static_cast<PngSink*>(context);
  if (!sink.error.empty()) return;
  try {
    sink.file->write(data, size_t(size));
  } catch (const std::exception& e) {
    sink.error = e.what();
  }
}

}  // namespace

uint8_t preview_tone_map(float linear) {
  const float v = std::clamp(linear, 0.0f, 1.0f);  // NaN never reaches here: images are finite
  const float encoded = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
  return uint8_t(std::lround(encoded * 255.0f));
}

void write_preview_png(const std::string& path, const FrameImage& image) {
  const ImageLayer* combined = image.find("");
  if (!combined) fail(path, "the image has no combined layer");
  const size_t values = size_t(std::max(image.width, 0)) * size_t(std::max(image.height, 0)) * 3;
  if (values == 0 || combined->rgb.size() != values) fail(path, "the combined layer is malformed");

  std::vector<uint8_t> pixels(values);
  std::transform(combined->rgb.begin(), combined->rgb.end(), pixels.begin(), preview_tone_map);
  try {
    // The temporary keeps a .png ending so nothing looking at the folder mistakes it for a frame.
    AtomicFile file(path, ".png");
    PngSink sink{&file, ""};
    if (!stbi_write_png_to_func(write_to_sink, &sink, image.width, image.height, 3, pixels.data(), image.width * 3))
      throw std::runtime_error(sink.error.empty() ? "the PNG encoder failed" : sink.error);
    if (!sink.error.empty()) throw std::runtime_error(sink.error);
    file.commit();
  } catch (const std::exception& e) {
    if (interruption_signal() != 0) throw Interrupted();
    fail(path, e.what());
  }
}

}  // namespace pm

// PNG previews through OpenImageIO, which is optional: without PMRENDER_HAVE_OIIO this file only
// reports that previews are unavailable.
#include "render/preview_png.h"

#include "render/errors.h"

#ifdef PMRENDER_HAVE_OIIO
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>
#endif

namespace pm {

#ifdef PMRENDER_HAVE_OIIO

namespace {

// Linear radiance to an 8-bit sRGB code value: exposure 1, clamp, then the sRGB transfer curve.
uint8_t to_srgb8(float linear) {
  const float v = std::clamp(linear, 0.0f, 1.0f);  // negatives become black
  const float encoded = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
  return uint8_t(std::lround(encoded * 255.0f));
}

[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw DeviceError("cannot write preview PNG '" + path + "': " + why);
}

}  // namespace

bool preview_available() { return true; }

void write_preview_png(const std::string& path, const FrameImage& image) {
  namespace fs = std::filesystem;
  const ImageLayer* combined = image.find("");
  if (!combined) fail(path, "the image has no combined layer");
  const size_t values = size_t(std::max(image.width, 0)) * size_t(std::max(image.height, 0)) * 3;
  if (values == 0 || combined->rgb.size() != values) fail(path, "the combined layer is malformed");

  std::vector<uint8_t> pixels(values);
  std::transform(combined->rgb.begin(), combined->rgb.end(), pixels.begin(), to_srgb8);

  const fs::path target(path);
  if (!target.parent_path().empty()) {
    std::error_code error;
    fs::create_directories(target.parent_path(), error);
    if (error) fail(path, "cannot create its folder: " + error.message());
  }
  // Same atomic scheme as write_exr; the temporary keeps a .png ending so that nothing looking
  // at the folder mistakes it for a finished preview, and OpenImageIO still knows the format.
  static std::atomic<unsigned> counter{0};
  const fs::path temporary = target.parent_path() /
      ("." + target.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
       std::to_string(counter++) + ".png");
  auto remove_temporary = [&] {
    std::error_code ignored;
    fs::remove(temporary, ignored);
  };

  std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create("png");
  if (!output) fail(path, "OpenImageIO has no PNG writer: " + OIIO::geterror());
  const OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
  if (!output->open(temporary.string(), spec)) {
    const std::string why = output->geterror();
    remove_temporary();
    fail(path, why);
  }
  const bool written = output->write_image(OIIO::TypeDesc::UINT8, pixels.data());
  const bool closed = output->close();
  if (!written || !closed) {
    const std::string why = output->geterror();
    remove_temporary();
    fail(path, why);
  }
  if (std::rename(temporary.c_str(), target.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    remove_temporary();
    fail(path, "cannot rename the temporary file onto it: " + why);
  }
}

#else  // !PMRENDER_HAVE_OIIO

bool preview_available() { return false; }

void write_preview_png(const std::string& /*path*/, const FrameImage& /*image*/) {
  throw InputError("--preview needs OpenImageIO, which this build does not have");
}

#endif

}  // namespace pm

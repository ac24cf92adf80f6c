// libFuzzer target for the EXR reader `pmrender compare` uses (render/exr_io.h: read_exr) and
// the completeness check of --resume (exr_is_complete), on the input written as a file. The
// contract checked: read_exr throws nothing but pm::InputError, and an image it returns has a
// positive size and width x height x 3 values in every layer; exr_is_complete never throws.
// Inputs whose header declares more than 2^16 pixels are skipped: reading them allocates much more
// than the seeds need and would slow the search down (read_exr itself refuses images beyond 16384x16384).
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "render/errors.h"
#include "render/exr_header_check.h"
#include "render/exr_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = pm::fuzz::write("image.exr", data, size);
  try {
    pm::check_exr_header(path);  // OpenEXR would allocate what a header attribute declares
    const Imath::Box2i window = Imf::InputFile(path.c_str()).header().dataWindow();
    const int64_t width = int64_t(window.max.x) - window.min.x + 1, height = int64_t(window.max.y) - window.min.y + 1;
    if (width > 0 && height > 0 && width * height > (int64_t(1) << 16)) return 0;
  } catch (...) {
    // Not even a header: read_exr must say so as an InputError.
  }
  pm::exr_is_complete(path);
  try {
    const pm::FrameImage image = pm::read_exr(path);
    pm::fuzz::require(image.width > 0 && image.height > 0, "positive size");
    pm::fuzz::require(!image.layers.empty(), "at least one layer");
    for (const pm::ImageLayer& layer : image.layers)
      pm::fuzz::require(layer.rgb.size() == size_t(image.width) * size_t(image.height) * 3, "layer size");
  } catch (const pm::InputError&) {
  }
  return 0;
}

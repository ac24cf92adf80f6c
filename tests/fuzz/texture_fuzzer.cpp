// libFuzzer target for the texture decoder both scene loaders use (scene_io/texture_files.h:
// decode_texture_image, stb_image from Debian's libstb behind the project's size limits) on the
// input's bytes as an image file (PNG, JPEG, BMP, or TGA by name). The contract checked: it throws
// nothing but pm::InputError; an image it returns has a positive size within kMaxTextureSide and
// kMaxTextureTexels, 1 to 4 channels in the file, and width x height x 4 bytes of RGBA.
#include <cstdint>

#include "fuzz_support.h"
#include "render/errors.h"
#include "scene_io/texture_files.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    // TGA has no signature: the decoder takes it by the file's name, so half the inputs are named so.
    const char* name = size > 0 && (data[0] & 1u) ? "fuzz.tga" : "fuzz.png";
    const pm::TextureImage image = pm::decode_texture_image(data, size, name, "map_Kd");
    pm::fuzz::require(image.width > 0 && image.height > 0, "positive size");
    pm::fuzz::require(image.width <= pm::kMaxTextureSide && image.height <= pm::kMaxTextureSide, "side limit");
    pm::fuzz::require(uint64_t(image.width) * uint64_t(image.height) <= pm::kMaxTextureTexels, "texel limit");
    pm::fuzz::require(image.file_channels >= 1 && image.file_channels <= 4, "channels");
    pm::fuzz::require(image.rgba.size() == size_t(image.width) * size_t(image.height) * 4, "RGBA size");
  } catch (const pm::InputError&) {
  }
  return 0;
}

// Texture images for the loaders (texture_files.h): stb_image decoding with size checks first,
// regular files only, and the deduplicating table of images and textures.
#include "scene_io/texture_files.h"

#include <stb_image.h>

#include <cctype>
#include <cstring>
#include <filesystem>
#include <memory>
#include <vector>

#include "scene_io/load_error.h"
#include "scene_io/regular_files.h"

namespace pm {

namespace {

// A name from a scene file as quoted in a message: at most 80 characters.
std::string quoted(const std::string& name) { return "'" + (name.size() > 80 ? name.substr(0, 77) + "..." : name) + "'"; }

// Whether the bytes are an image of a format textures are read in: PNG, JPEG and BMP by their
// leading bytes, TGA (which has none) by the file name. stb_image reads more (GIF, PSD, HDR, PNM,
// PIC), but Debian 12's libstb reads past the end of a PNM whose header promises more texels than
// the file holds (found by tests/fuzz/texture_fuzzer.cpp; the input is kept in its corpus), and
// scenes do not use those formats for textures: they are refused before stb_image sees them.
bool is_texture_format(const unsigned char* bytes, size_t size, const std::string& source) {
  static const unsigned char png[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (size >= sizeof(png) && std::memcmp(bytes, png, sizeof(png)) == 0) return true;
  if (size >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff) return true;
  if (size >= 2 && bytes[0] == 'B' && bytes[1] == 'M') return true;
  std::string extension = std::filesystem::path(source).extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".tga";
}

std::string decoder_reason() {
  const char* reason = stbi_failure_reason();
  return reason ? reason : "no reason given";
}

}  // namespace

TextureImage decode_texture_image(const unsigned char* bytes, size_t size, const std::string& source,
                                  const std::string& where) {
  if (size == 0) throw_input_error(where, quoted(source) + " is empty, not an image");
  if (size > size_t(INT32_MAX)) throw_input_error(where, quoted(source) + " is larger than 2 GiB");
  if (!is_texture_format(bytes, size, source))
    throw_input_error(where, quoted(source) + " is not an image stb_image can decode (textures are read from PNG, "
                                              "JPEG, BMP and .tga files only)");
  int width = 0, height = 0, channels = 0;
  // The header first: a corrupt or hostile size must not reach the allocation of the texels.
  if (!stbi_info_from_memory(bytes, int(size), &width, &height, &channels))
    throw_input_error(where, quoted(source) + " is not an image stb_image can decode (" + decoder_reason() + ")");
  if (width < 1 || height < 1 || width > kMaxTextureSide || height > kMaxTextureSide ||
      uint64_t(width) * uint64_t(height) > kMaxTextureTexels)
    throw_input_error(where, quoted(source) + " is " + std::to_string(width) + "x" + std::to_string(height) +
                                 " texels; at most " + std::to_string(kMaxTextureSide) + " a side and " +
                                 std::to_string(kMaxTextureTexels) + " texels are supported");
  int decoded_width = 0, decoded_height = 0, file_channels = 0;
  std::unique_ptr<stbi_uc, void (*)(void*)> texels(
      stbi_load_from_memory(bytes, int(size), &decoded_width, &decoded_height, &file_channels, 4), stbi_image_free);
  if (!texels)
    throw_input_error(where, quoted(source) + " is not an image stb_image can decode (" + decoder_reason() + ")");
  TextureImage image;
  image.source = source;
  image.width = decoded_width;
  image.height = decoded_height;
  image.file_channels = file_channels;
  image.rgba.assign(texels.get(), texels.get() + size_t(decoded_width) * size_t(decoded_height) * 4);
  return image;
}

int SceneTextures::file_texture(const std::string& path, const std::string& shown, const std::string& where,
                                TextureWrap wrap_u, TextureWrap wrap_v) {
  std::error_code ec;
  std::string key = std::filesystem::weakly_canonical(path, ec).string();
  if (ec || key.empty()) key = path;
  auto it = image_by_path_.find(key);
  uint32_t image;
  if (it != image_by_path_.end()) {
    image = it->second;
  } else {
    std::vector<unsigned char> bytes;
    const std::string problem = read_regular_file(path, &bytes);
    if (!problem.empty())
      throw_input_error(where, "cannot open " + quoted(shown) + " (" + problem +
                                   (shown != path ? "; looked for " + quoted(path) : "") + ")");
    TextureImage decoded = decode_texture_image(bytes.data(), bytes.size(), shown, where);
    decoded.source = path;
    image = add_image(std::move(decoded));
    image_by_path_[key] = image;
  }
  return image_texture(image, wrap_u, wrap_v);
}

uint32_t SceneTextures::add_image(TextureImage image) {
  scene_->images.push_back(std::move(image));
  return uint32_t(scene_->images.size() - 1);
}

int SceneTextures::image_texture(uint32_t image, TextureWrap wrap_u, TextureWrap wrap_v) {
  const std::pair<uint32_t, int> key{image, int(wrap_u) | int(wrap_v) << 4};
  auto it = texture_by_image_and_wrap_.find(key);
  if (it != texture_by_image_and_wrap_.end()) return it->second;
  TextureRef ref;
  ref.image = image;
  ref.wrap_u = wrap_u;
  ref.wrap_v = wrap_v;
  scene_->textures.push_back(ref);
  const int index = int(scene_->textures.size() - 1);
  texture_by_image_and_wrap_[key] = index;
  return index;
}

}  // namespace pm

// Owns turning the images a scene names into Scene::images and Scene::textures for both loaders
// (MTL map_Kd / map_d, glTF images): decoding with stb_image (Debian's libstb, the decoder
// tinygltf is built with too), the size limits, one-line messages naming the file and field,
// and one decoded copy per image file however many materials and wrap modes use it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <utility>

#include "render/scene.h"

namespace pm {

// Images wider or taller than this are refused (the camera's own limit), as are images of more
// than kMaxTextureTexels texels (1 GiB of RGBA8), before any texel is decoded.
constexpr int kMaxTextureSide = 16384;
constexpr uint64_t kMaxTextureTexels = uint64_t(1) << 28;

// Decodes an encoded image (PNG, JPEG, BMP, or TGA when `source` ends in .tga; other formats are
// refused) into RGBA8, colour as stored (sRGB), alpha 255 where the file has none.
// `source` names the image in messages and in TextureImage::source. Throws InputError
// "<where>: <source> is not an image stb_image can decode (<why>)" or names a size limit.
TextureImage decode_texture_image(const unsigned char* bytes, size_t size, const std::string& source,
                                  const std::string& where);

// The scene's textures as the loaders add them: each image decoded once, each (image, wraps)
// pair one Scene::textures entry.
class SceneTextures {
 public:
  explicit SceneTextures(Scene* scene) : scene_(scene) {}

  // The texture of the image file at `path` (decoded on first use). `shown` is the name as the
  // scene wrote it, `where` the field naming it, for "<where>: cannot open '<shown>' (...)".
  int file_texture(const std::string& path, const std::string& shown, const std::string& where, TextureWrap wrap_u,
                   TextureWrap wrap_v);
  // A decoded image added to Scene::images; returns its index.
  uint32_t add_image(TextureImage image);
  // The texture of an image already added.
  int image_texture(uint32_t image, TextureWrap wrap_u, TextureWrap wrap_v);
  // The image a texture samples.
  const TextureImage& image_of(int texture) const { return scene_->images[scene_->textures[size_t(texture)].image]; }

 private:
  Scene* scene_;
  std::map<std::string, uint32_t> image_by_path_;
  std::map<std::pair<uint32_t, int>, int> texture_by_image_and_wrap_;
};

}  // namespace pm

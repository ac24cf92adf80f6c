// Packing of a scene's textures for the device (render/scene_textures.h).
#include "render/scene_textures.h"

#include <cmath>
#include <limits>
#include <string>

#include "render/errors.h"

namespace pm {

namespace {

uint32_t wrap_bits(TextureWrap wrap) {
  switch (wrap) {
    case TextureWrap::clamp_to_edge: return PM_WRAP_CLAMP;
    case TextureWrap::mirrored_repeat: return PM_WRAP_MIRROR;
    case TextureWrap::repeat: break;
  }
  return PM_WRAP_REPEAT;
}

}  // namespace

float srgb_code_to_linear(int code) {
  const double c = code / 255.0;
  return float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

void pack_texture_images(const Scene& scene, DeviceTextures* out) {
  out->srgb_table.resize(256);
  for (int code = 0; code < 256; ++code) out->srgb_table[size_t(code)] = srgb_code_to_linear(code);
  std::vector<uint64_t> first_texel;
  uint64_t total = 0;
  for (const TextureImage& image : scene.images) {
    const uint64_t texels = uint64_t(image.width) * uint64_t(image.height);
    if (image.width <= 0 || image.height <= 0 || image.rgba.size() != 4 * texels)
      throw InputError(image.source + ": decoded image holds " + std::to_string(image.rgba.size()) + " bytes for " +
                       std::to_string(image.width) + "x" + std::to_string(image.height) + " texels");
    first_texel.push_back(total);
    total += texels;
  }
  if (total > std::numeric_limits<uint32_t>::max())
    throw InputError("scene '" + scene.name + "': the textures hold " + std::to_string(total) +
                     " texels, more than 32-bit texel offsets reach");
  out->texels.resize(size_t(total));
  for (size_t i = 0; i < scene.images.size(); ++i) {
    const std::vector<uint8_t>& rgba = scene.images[i].rgba;
    uint32_t* word = out->texels.data() + first_texel[i];
    for (size_t t = 0; t < rgba.size() / 4; ++t)
      word[t] = uint32_t(rgba[4 * t]) | uint32_t(rgba[4 * t + 1]) << 8 | uint32_t(rgba[4 * t + 2]) << 16 |
                uint32_t(rgba[4 * t + 3]) << 24;
  }
  out->info.clear();
  for (size_t i = 0; i < scene.textures.size(); ++i) {
    const TextureRef& ref = scene.textures[i];
    if (ref.image >= scene.images.size())
      throw InputError("scene '" + scene.name + "': texture " + std::to_string(i) + " names image " +
                       std::to_string(ref.image) + " of " + std::to_string(scene.images.size()));
    const TextureImage& image = scene.images[ref.image];
    out->info.push_back(uint4{uint32_t(first_texel[ref.image]), uint32_t(image.width), uint32_t(image.height),
                              wrap_bits(ref.wrap_u) | wrap_bits(ref.wrap_v) << 8});
  }
}

DeviceTextures pack_scene_textures(const Scene& scene, const SceneBvh& bvh) {
  DeviceTextures out;
  if (!scene.has_textures()) return out;
  for (const MaterialDesc& m : scene.materials) {
    for (int texture : {m.base_color_texture, m.alpha_texture})
      if (texture >= 0 && size_t(texture) >= scene.textures.size())
        throw InputError("scene '" + scene.name + "': material '" + m.name + "' names texture " +
                         std::to_string(texture) + " of " + std::to_string(scene.textures.size()));
  }
  pack_texture_images(scene, &out);
  const size_t n = bvh.triangle_count();
  out.uvs.assign(2 * n, float4{0, 0, 0, 0});
  for (size_t i = 0; i < n; ++i) {
    const size_t tri = bvh.original_index[i];
    if (3 * tri + 2 >= scene.triangle_uvs.size()) continue;  // no coordinates: (0, 0) at every corner
    const Float2* uv = &scene.triangle_uvs[3 * tri];
    out.uvs[2 * i] = float4{uv[0].u, uv[0].v, uv[1].u, uv[1].v};
    out.uvs[2 * i + 1] = float4{uv[2].u, uv[2].v, 0, 0};
  }
  return out;
}

void set_material_textures(const MaterialDesc& desc, Material* out) {
  uint32_t flags = 0;
  if (desc.texture_tints_specular) flags |= PM_MATERIAL_TINT_SPECULAR;
  if (desc.alpha_mask) flags |= PM_MATERIAL_MASKED | (uint32_t(desc.alpha_channel) & 3u) << PM_MATERIAL_ALPHA_CHANNEL_SHIFT;
  out->diffuse.w = PM_UINT_AS_FLOAT(flags);
  // Without a mask nothing reads the alpha fields; factor 1 and cutoff 0 would pass anyway.
  out->texture = float4{PM_UINT_AS_FLOAT(uint32_t(desc.base_color_texture + 1)),
                        PM_UINT_AS_FLOAT(desc.alpha_mask ? uint32_t(desc.alpha_texture + 1) : 0u),
                        desc.alpha_mask ? desc.alpha_factor : 1.0f, desc.alpha_mask ? desc.alpha_cutoff : 0.0f};
}

}  // namespace pm

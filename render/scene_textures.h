// A scene's textures in the device layout kernels/common/texture.h reads: one packed buffer of
// RGBA8 texels for every image, one descriptor per texture (first texel, size, wrap modes), two
// float4 of texture coordinates per triangle in BVH leaf order, and the texture fields of the
// device materials. Built once per scene, on the host; the renderer uploads it once, and the
// radiosity method samples the same arrays on the host (radiosity_texture_tint.h).
#pragma once

#include <cstdint>
#include <vector>

#if defined(__CUDACC__)
#include "kernels/cuda/compat.h"
#else
#include "kernels/common/compat_host.h"
#endif
#include "kernels/common/types.h"
#include "render/scene.h"
#include "render/scene_bvh.h"

namespace pm {

struct DeviceTextures {
  std::vector<uint4> info;      // texture_info: one per Scene::textures entry
  std::vector<uint32_t> texels;  // texels: every Scene::images entry once, in order
  std::vector<float4> uvs;       // triangle_uvs: 2 per triangle, leaf order
  std::vector<float> srgb_table;  // texture_srgb_table: 256 entries

  // Device bytes of the four buffers (what the memory report counts for textures).
  uint64_t bytes() const {
    return info.size() * sizeof(uint4) + texels.size() * sizeof(uint32_t) + uvs.size() * sizeof(float4) +
           srgb_table.size() * sizeof(float);
  }
};

// The linear value of an 8-bit sRGB code (IEC 61966-2-1), computed in double and rounded once.
float srgb_code_to_linear(int code);

// Texel words, descriptors and the sRGB table of the scene's images and textures. Throws InputError when an
// image's texels do not match its size or a texture names no image, or the texels of all images
// together exceed 2^32 (32-bit offsets).
void pack_texture_images(const Scene& scene, DeviceTextures* out);

// All four arrays for a scene and its BVH (empty when Scene::has_textures() is false).
DeviceTextures pack_scene_textures(const Scene& scene, const SceneBvh& bvh);

// The texture fields of a device material (Material::texture, the flags in diffuse.w).
void set_material_textures(const MaterialDesc& desc, Material* out);

}  // namespace pm

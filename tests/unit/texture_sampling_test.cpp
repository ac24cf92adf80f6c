// The device's texture lookup (kernels/common/texture.h) called on the host: sRGB decoding,
// bilinear filtering in linear space, the three wrap modes at and beyond the edges, linear alpha,
// texture coordinates across a triangle, the tint a texel applies to a material and the alpha
// test of masked materials; and the packing of Scene images into the device layout.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "kernels/common/compat_host.h"
#include "kernels/common/texture.h"
#include "render/errors.h"
#include "render/kernel_abi.h"
#include "render/renderer.h"
#include "render/scene_bvh.h"
#include "render/scene_textures.h"
#include "support/texture_images.h"

namespace pm {
namespace {

uint32_t rgba(int r, int g, int b, int a) { return uint32_t(r) | uint32_t(g) << 8 | uint32_t(b) << 16 | uint32_t(a) << 24; }

// One image of width x height texels, sampled with the given wrap modes.
struct HostTexture {
  std::vector<uint4> info;
  std::vector<uint32_t> texels;
  std::vector<float> srgb_table;
  HostTexture(int width, int height, std::vector<uint32_t> words, uint32_t wrap_u, uint32_t wrap_v)
      : texels(std::move(words)) {
    info.push_back(uint4{0, uint32_t(width), uint32_t(height), wrap_u | wrap_v << 8});
    for (int code = 0; code < 256; ++code) srgb_table.push_back(srgb_code_to_linear(code));
  }
  float4 sample(float u, float v, int srgb = 1) const {
    return texture_sample(info.data(), texels.data(), srgb_table.data(), 0, u, v, srgb);
  }
};

TEST(TextureSampling, SrgbTableMatchesTheStandard) {
  Scene scene;
  DeviceTextures packed;
  pack_texture_images(scene, &packed);  // the table the device gets, even without images
  ASSERT_EQ(packed.srgb_table.size(), 256u);
  EXPECT_EQ(packed.srgb_table[0], 0.0f);
  EXPECT_EQ(packed.srgb_table[255], 1.0f);
  for (int code = 0; code < 256; ++code) {
    EXPECT_FLOAT_EQ(packed.srgb_table[size_t(code)], float(test::srgb_to_linear(code))) << code;
    if (code > 0) {
      EXPECT_GT(packed.srgb_table[size_t(code)], packed.srgb_table[size_t(code - 1)]) << code;
    }
  }
  // Code 10 lies on the linear piece (10 / 255 < 0.04045), 11 on the power piece.
  EXPECT_NEAR(packed.srgb_table[10], 10.0 / 255.0 / 12.92, 1e-9);
  EXPECT_NEAR(packed.srgb_table[11], std::pow((11.0 / 255.0 + 0.055) / 1.055, 2.4), 1e-9);
}

TEST(TextureSampling, TexelCentresAreExactAndTheFilterBlendsLinearValues) {
  // Black and white side by side: at texel centres each colour exactly; half way between them
  // half the light (0.5), not the linear value of the encoded midpoint 128 (0.216).
  const HostTexture t(2, 1, {rgba(0, 0, 0, 255), rgba(255, 255, 255, 255)}, PM_WRAP_CLAMP, PM_WRAP_CLAMP);
  EXPECT_EQ(t.sample(0.25f, 0.5f).x, 0.0f);
  EXPECT_NEAR(t.sample(0.75f, 0.5f).x, 1.0f, 1e-6);
  EXPECT_NEAR(t.sample(0.5f, 0.5f).x, 0.5f, 1e-6);
  EXPECT_NEAR(t.sample(0.375f, 0.5f).y, 0.25f, 1e-6);
  // Unfiltered channels (srgb = 0) come back as stored, over 255.
  const HostTexture grey(1, 1, {rgba(128, 64, 32, 255)}, PM_WRAP_REPEAT, PM_WRAP_REPEAT);
  EXPECT_NEAR(grey.sample(0.3f, 0.6f, 0).x, 128.0f / 255.0f, 1e-6);
  EXPECT_NEAR(grey.sample(0.3f, 0.6f, 1).x, test::srgb_to_linear(128), 2e-6);
}

TEST(TextureSampling, RowsRunTopFirstAndColumnsLeftFirst) {
  // 1 x 2: red on top (v = 0.25), blue below (v = 0.75).
  const HostTexture t(1, 2, {rgba(255, 0, 0, 255), rgba(0, 0, 255, 255)}, PM_WRAP_CLAMP, PM_WRAP_CLAMP);
  EXPECT_NEAR(t.sample(0.5f, 0.25f).x, 1.0f, 1e-6);
  EXPECT_EQ(t.sample(0.5f, 0.25f).z, 0.0f);
  EXPECT_NEAR(t.sample(0.5f, 0.75f).z, 1.0f, 1e-6);
}

TEST(TextureSampling, WrapModesAtAndBeyondTheEdges) {
  const std::vector<uint32_t> dark_light = {rgba(0, 0, 0, 255), rgba(255, 255, 255, 255)};
  const HostTexture repeat(2, 1, dark_light, PM_WRAP_REPEAT, PM_WRAP_REPEAT);
  const HostTexture clamp(2, 1, dark_light, PM_WRAP_CLAMP, PM_WRAP_CLAMP);
  const HostTexture mirror(2, 1, dark_light, PM_WRAP_MIRROR, PM_WRAP_MIRROR);
  // u = 0 lies between texel 0 and the texel before it: the last (repeat), texel 0 itself
  // (clamp, and mirror, whose period reflects at the edge).
  EXPECT_NEAR(repeat.sample(0.0f, 0.5f).x, 0.5f, 1e-6);
  EXPECT_EQ(clamp.sample(0.0f, 0.5f).x, 0.0f);
  EXPECT_EQ(mirror.sample(0.0f, 0.5f).x, 0.0f);
  // One period further: repeat starts over, mirror runs backwards, clamp holds the edge texel.
  EXPECT_EQ(repeat.sample(1.25f, 0.5f).x, 0.0f);
  EXPECT_NEAR(repeat.sample(-0.25f, 0.5f).x, 1.0f, 1e-6);
  EXPECT_NEAR(mirror.sample(1.25f, 0.5f).x, 1.0f, 1e-6);
  EXPECT_EQ(mirror.sample(1.75f, 0.5f).x, 0.0f);
  EXPECT_NEAR(clamp.sample(7.0f, 0.5f).x, 1.0f, 1e-6);
  EXPECT_EQ(clamp.sample(-7.0f, 0.5f).x, 0.0f);
  // Far and broken coordinates stay inside the image.
  for (float u : {1e9f, -1e9f, 1e30f, INFINITY, NAN}) {
    for (const HostTexture* t : {&repeat, &clamp, &mirror}) {
      const float4 s = t->sample(u, u);
      EXPECT_TRUE(s.x >= 0.0f && s.x <= 1.0f) << u;
    }
  }
}

TEST(TextureSampling, AlphaIsLinear) {
  const HostTexture t(1, 1, {rgba(255, 255, 255, 128)}, PM_WRAP_REPEAT, PM_WRAP_REPEAT);
  EXPECT_NEAR(t.sample(0.5f, 0.5f).w, 128.0f / 255.0f, 1e-6);
}

// Two triangles of a unit square in z = 0, with texture coordinates (0, 0) .. (1, 1), and the
// device arrays a stage reads for them.
struct TexturedSquare {
  Scene scene;
  SceneBvh bvh;
  std::vector<Material> materials;
  DeviceTextures textures;
  KernelGlobals kg{};
  explicit TexturedSquare(MaterialDesc material, std::vector<TextureImage> images) {
    scene.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    scene.indices = {0, 1, 2, 0, 2, 3};
    scene.triangle_material = {0, 0};
    scene.triangle_uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}};
    scene.images = std::move(images);
    for (size_t i = 0; i < scene.images.size(); ++i) scene.textures.push_back(TextureRef{uint32_t(i)});
    scene.materials = {material};
    bvh = build_scene_bvh(scene);
    materials = to_device_materials(scene);
    textures = pack_scene_textures(scene, bvh);
    kg.triangles = bvh.triangles.data();
    kg.materials = materials.data();
    kg.triangle_uvs = textures.uvs.data();
    kg.texture_info = textures.info.data();
    kg.texels = textures.texels.data();
    kg.texture_srgb_table = textures.srgb_table.data();
  }
  int leaf_of(uint32_t original) const {
    for (size_t i = 0; i < bvh.triangle_count(); ++i)
      if (bvh.original_index[i] == original) return int(i);
    return -1;
  }
};

TextureImage image(int width, int height, std::vector<uint8_t> rgba_bytes, int file_channels = 4) {
  TextureImage i;
  i.source = "test";
  i.width = width;
  i.height = height;
  i.file_channels = file_channels;
  i.rgba = std::move(rgba_bytes);
  return i;
}

TEST(TextureSampling, SurfaceMaterialTintsDiffuseAndWithGltfBaseColourTheSpecularToo) {
  // 2 x 2: left column red, right column green (rows alike).
  const TextureImage checker = image(2, 2, {255, 0, 0, 255, 0, 255, 0, 255, 255, 0, 0, 255, 0, 255, 0, 255});
  MaterialDesc m;
  m.diffuse = {0.5f, 0.5f, 0.5f};
  m.glossy = {0.25f, 0.25f, 0.25f};
  m.base_color_texture = 0;
  TexturedSquare square(m, {checker});
  const int leaf = square.leaf_of(0);
  // (0.25, 0.1) on triangle 0: texture coordinates (0.25, 0.1), the red column's centre.
  Material at = surface_material(&square.kg, 0, leaf, vec3(0.25f, 0.1f, 0.0f));
  EXPECT_NEAR(at.diffuse.x, 0.5f, 1e-6);
  EXPECT_EQ(at.diffuse.y, 0.0f);
  EXPECT_EQ(at.glossy.x, 0.25f);  // an MTL texture colours the diffuse term alone
  at = surface_material(&square.kg, 0, leaf, vec3(0.75f, 0.05f, 0.0f));
  EXPECT_EQ(at.diffuse.x, 0.0f);
  EXPECT_NEAR(at.diffuse.y, 0.5f, 1e-6);

  m.texture_tints_specular = true;
  TexturedSquare gltf(m, {checker});
  at = surface_material(&gltf.kg, 0, gltf.leaf_of(0), vec3(0.25f, 0.1f, 0.0f));
  EXPECT_NEAR(at.glossy.x, 0.25f, 1e-6);
  EXPECT_EQ(at.glossy.y, 0.0f);
}

TEST(TextureSampling, AlphaTestFollowsTheCutoffTheFactorAndTheChannel) {
  // Alpha 0 in the left column, 255 in the right; red the other way round.
  const TextureImage mask = image(2, 1, {255, 0, 0, 0, 0, 0, 0, 255});
  MaterialDesc m;
  m.alpha_mask = true;
  m.alpha_texture = 0;
  m.alpha_channel = 3;
  m.alpha_cutoff = 0.5f;
  TexturedSquare square(m, {mask});
  const int leaf = square.leaf_of(0);
  EXPECT_FALSE(surface_alpha_visible(&square.kg, 0, leaf, vec3(0.2f, 0.1f, 0.0f)));
  EXPECT_TRUE(surface_alpha_visible(&square.kg, 0, leaf, vec3(0.8f, 0.1f, 0.0f)));
  // The triangle record carries the mask flag; the material index reads back without it.
  EXPECT_NE(PM_AS_UINT(square.bvh.triangles[0].w) & PM_TRIANGLE_MASKED, 0u);
  EXPECT_EQ(scene_triangle_material(square.bvh.triangles.data(), 0), 0);

  m.alpha_channel = 0;  // the red channel instead: the holes swap sides
  TexturedSquare red(m, {mask});
  EXPECT_TRUE(surface_alpha_visible(&red.kg, 0, red.leaf_of(0), vec3(0.2f, 0.1f, 0.0f)));
  EXPECT_FALSE(surface_alpha_visible(&red.kg, 0, red.leaf_of(0), vec3(0.8f, 0.1f, 0.0f)));

  m.alpha_channel = 3;
  m.alpha_factor = 0.4f;  // glTF's baseColorFactor alpha times the texel's: 0.4 < 0.5 everywhere
  TexturedSquare faint(m, {mask});
  EXPECT_FALSE(surface_alpha_visible(&faint.kg, 0, faint.leaf_of(0), vec3(0.8f, 0.1f, 0.0f)));

  MaterialDesc constant;  // a mask without a texture: the factor alone decides
  constant.alpha_mask = true;
  constant.alpha_factor = 0.5f;
  TexturedSquare opaque(constant, {});
  EXPECT_TRUE(surface_alpha_visible(&opaque.kg, 0, opaque.leaf_of(0), vec3(0.5f, 0.2f, 0.0f)));
}

TEST(TextureSampling, TextureCoordinatesFollowTheTriangleInLeafOrder) {
  MaterialDesc m;
  m.base_color_texture = 0;
  TexturedSquare square(m, {image(1, 1, {255, 255, 255, 255})});
  for (uint32_t original : {0u, 1u}) {
    const int leaf = square.leaf_of(original);
    float b1, b2, u, v;
    const Vec3 p = original == 0 ? vec3(0.7f, 0.2f, 0.0f) : vec3(0.3f, 0.6f, 0.0f);
    scene_triangle_barycentrics(square.kg.triangles, leaf, p, &b1, &b2);
    triangle_uv_at(square.kg.triangle_uvs, leaf, b1, b2, &u, &v);
    EXPECT_NEAR(u, p.x, 1e-6) << original;  // this square's coordinates equal its positions
    EXPECT_NEAR(v, p.y, 1e-6) << original;
  }
}

TEST(TextureSampling, PackingPlacesEveryImageOnceAndChecksSizes) {
  Scene scene;
  scene.name = "packed";
  scene.images = {image(2, 1, std::vector<uint8_t>(8, 7)), image(1, 3, std::vector<uint8_t>(12, 9))};
  scene.textures = {TextureRef{1, TextureWrap::clamp_to_edge, TextureWrap::mirrored_repeat}, TextureRef{0}};
  DeviceTextures out;
  pack_texture_images(scene, &out);
  ASSERT_EQ(out.texels.size(), 5u);
  ASSERT_EQ(out.info.size(), 2u);
  EXPECT_EQ(out.info[0].x, 2u);  // image 1 starts after image 0's two texels
  EXPECT_EQ(out.info[0].y, 1u);
  EXPECT_EQ(out.info[0].z, 3u);
  EXPECT_EQ(out.info[0].w, PM_WRAP_CLAMP | PM_WRAP_MIRROR << 8);
  EXPECT_EQ(out.info[1].x, 0u);
  EXPECT_EQ(out.texels[2], 0x09090909u);
  scene.images[1].rgba.pop_back();
  EXPECT_THROW(pack_texture_images(scene, &out), InputError);
}

}  // namespace
}  // namespace pm

// Textures through the glTF path: baseColorTexture with its sampler's wrap modes and texCoord
// set, images from a file, a data URI and a bufferView, alphaMode MASK with alphaCutoff and the
// base colour's alpha factor, and bad input (a missing or undecodable image, a missing TEXCOORD_n,
// a bufferView past its buffer), each one line naming the file and the field.
#include <string>

#include "gltf_test_support.h"
#include "support/texture_images.h"

namespace pm {
namespace {

// A unit square (two triangles) with TEXCOORD_0 and TEXCOORD_1 and the given material.
int textured_square(GltfBuilder& b, int material) {
  json primitive = {{"attributes",
                     {{"POSITION", b.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3")},
                      {"TEXCOORD_0", b.floats({0, 0, 1, 0, 1, 1, 0, 1}, "VEC2")},
                      {"TEXCOORD_1", b.floats({0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.25f}, "VEC2")}}},
                    {"indices", b.accessor(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, 5123, "SCALAR")},
                    {"material", material}};
  return b.mesh(json::array({primitive}));
}

class GltfTextures : public Gltf {};

TEST_F(GltfTextures, BaseColorTextureWithSamplerTexCoordAndMask) {
  write("red.png", test::uniform_png(2, 2, 255, 0, 0));
  GltfBuilder b;
  b.doc()["materials"] = {{{"name", "tiles"},
                           {"pbrMetallicRoughness",
                            {{"baseColorFactor", {0.5, 0.5, 0.5, 0.8}},
                             {"metallicFactor", 0.0},
                             {"baseColorTexture", {{"index", 0}, {"texCoord", 1}}}}},
                           {"alphaMode", "MASK"},
                           {"alphaCutoff", 0.3}},
                          {{"name", "plain"}, {"pbrMetallicRoughness", {{"metallicFactor", 0.0}}}}};
  b.doc()["samplers"] = {{{"wrapS", 33071}, {"wrapT", 33648}}};
  b.doc()["textures"] = {{{"source", 0}, {"sampler", 0}}};
  b.doc()["images"] = {{{"uri", "red.png"}}};
  b.node({{"mesh", b.triangle_mesh({{"material", 1}})}});  // an untextured triangle first
  b.node({{"mesh", textured_square(b, 0)}});
  b.add_camera_and_light();
  SceneLoadReport report;
  const Scene scene = load(b, &report);
  ASSERT_EQ(scene.materials.size(), 2u);
  const MaterialDesc& tiles = scene.materials[1];
  ASSERT_EQ(tiles.base_color_texture, 0);
  EXPECT_TRUE(tiles.texture_tints_specular);
  EXPECT_TRUE(tiles.alpha_mask);
  EXPECT_EQ(tiles.alpha_texture, 0);
  EXPECT_EQ(tiles.alpha_channel, 3);
  EXPECT_FLOAT_EQ(tiles.alpha_factor, 0.8f);
  EXPECT_FLOAT_EQ(tiles.alpha_cutoff, 0.3f);
  EXPECT_FALSE(scene.materials[0].alpha_mask);
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_EQ(scene.textures[0].wrap_u, TextureWrap::clamp_to_edge);
  EXPECT_EQ(scene.textures[0].wrap_v, TextureWrap::mirrored_repeat);
  ASSERT_EQ(scene.images.size(), 1u);
  EXPECT_EQ(scene.images[0].rgba[0], 255);
  EXPECT_EQ(scene.images[0].rgba[1], 0);
  // The untextured triangle's corners read (0, 0); the square's read TEXCOORD_1 (texCoord 1) as
  // stored, glTF's v already counting from the top.
  ASSERT_EQ(scene.triangle_uvs.size(), 9u);
  EXPECT_EQ(scene.triangle_uvs[0].u, 0.0f);
  EXPECT_EQ(scene.triangle_uvs[3].u, 0.5f);
  EXPECT_EQ(scene.triangle_uvs[8].v, 0.25f);  // vertex 3 of the second triangle (0 2 3)
  EXPECT_FALSE(has_warning(report, "ignored"));
}

TEST_F(GltfTextures, DataUriAndBufferViewImagesAndBlendStaysIgnored) {
  GltfBuilder b;
  const std::string green = test::uniform_png(1, 1, 0, 255, 0);
  // The image in a bufferView of the builder's buffer.
  const int view_accessor = b.accessor(std::vector<uint8_t>(green.begin(), green.end()), 5121, "SCALAR");
  const int view = b.doc()["accessors"][size_t(view_accessor)]["bufferView"].get<int>();
  b.doc()["materials"] = {
      {{"pbrMetallicRoughness", {{"metallicFactor", 0.0}, {"baseColorTexture", {{"index", 0}}}}}, {"alphaMode", "BLEND"}},
      {{"pbrMetallicRoughness", {{"metallicFactor", 0.0}, {"baseColorTexture", {{"index", 1}}}}}}};
  b.doc()["textures"] = {{{"source", 0}}, {{"source", 1}}};
  b.doc()["images"] = {{{"uri", "data:image/png;base64," + base64(test::uniform_png(1, 1, 0, 0, 255))}},
                       {{"bufferView", view}, {"mimeType", "image/png"}}};
  b.node({{"mesh", textured_square(b, 0)}});
  b.node({{"mesh", textured_square(b, 1)}});
  b.add_camera_and_light();
  SceneLoadReport report;
  const Scene scene = load(b, &report);
  ASSERT_EQ(scene.images.size(), 2u);
  EXPECT_EQ(scene.images[0].rgba[2], 255);  // blue, from the data URI
  EXPECT_EQ(scene.images[1].rgba[1], 255);  // green, from the bufferView
  EXPECT_EQ(scene.textures[0].wrap_u, TextureWrap::repeat);  // no sampler: repeat
  EXPECT_FALSE(scene.materials[0].alpha_mask);
  EXPECT_TRUE(has_warning(report, "materials[0]: ignored: alphaMode BLEND (rendered opaque)"));
}

TEST_F(GltfTextures, MissingImageFileNamesTheImagesUri) {
  GltfBuilder b;
  b.doc()["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  b.doc()["textures"] = {{{"source", 0}}};
  b.doc()["images"] = {{{"uri", "textures/gone.png"}}};
  b.node({{"mesh", textured_square(b, 0)}});
  b.add_camera_and_light();
  expect_error(b, "images[0].uri: 'textures/gone.png' not found (looked for '");
}

TEST_F(GltfTextures, UndecodableImageNamesTheImagesUri) {
  write("fake.png", "plain text, not an image");
  GltfBuilder b;
  b.doc()["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  b.doc()["textures"] = {{{"source", 0}}};
  b.doc()["images"] = {{{"uri", "fake.png"}}};
  b.node({{"mesh", textured_square(b, 0)}});
  b.add_camera_and_light();
  expect_error(b, "images[0].uri: 'fake.png' is not an image stb_image can decode (");
}

TEST_F(GltfTextures, TexCoordSetThePrimitiveLacksIsAnError) {
  write("red.png", test::uniform_png(1, 1, 255, 0, 0));
  GltfBuilder b;
  b.doc()["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"texCoord", 2}}}}}}};
  b.doc()["textures"] = {{{"source", 0}}};
  b.doc()["images"] = {{{"uri", "red.png"}}};
  b.node({{"mesh", textured_square(b, 0)}});
  b.add_camera_and_light();
  expect_error(b, "meshes[0].primitives[0].attributes: no TEXCOORD_2, which materials[0]'s texture reads");
}

TEST_F(GltfTextures, UnknownWrapModeIsAnError) {
  write("red.png", test::uniform_png(1, 1, 255, 0, 0));
  GltfBuilder b;
  b.doc()["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  b.doc()["samplers"] = {{{"wrapS", 10}}};
  b.doc()["textures"] = {{{"source", 0}, {"sampler", 0}}};
  b.doc()["images"] = {{{"uri", "red.png"}}};
  b.node({{"mesh", textured_square(b, 0)}});
  b.add_camera_and_light();
  expect_error(b, "samplers[0].wrapS: unknown wrap mode 10");
}

TEST_F(GltfTextures, ImageBufferViewPastItsBufferIsAnError) {
  GltfBuilder b;
  b.doc()["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  b.doc()["textures"] = {{{"source", 0}}};
  const int square = textured_square(b, 0);
  b.doc()["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 4}, {"byteLength", 1 << 20}});
  b.doc()["images"] = {{{"bufferView", b.doc()["bufferViews"].size() - 1}, {"mimeType", "image/png"}}};
  b.node({{"mesh", square}});
  b.add_camera_and_light();
  expect_error(b, "images[0].bufferView: the bufferView reaches past the end of its buffer");
}

}  // namespace
}  // namespace pm

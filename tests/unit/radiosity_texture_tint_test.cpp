// The texture colour of radiosity elements (render/radiosity/radiosity_texture_tint.h): a uniform
// texture gives every element of its material that colour exactly; a texture split into a red
// and a green half gives elements well inside a half that half's colour, elements on the seam a
// hat-weighted mix (r + g = 1 everywhere; r = g where the one-ring is symmetric, 1/3 and 2/3 at
// the edge where it is not); untextured materials' elements read (1, 1, 1).
#include <gtest/gtest.h>

#include <cmath>

#include "render/radiosity/mesh_refinement.h"
#include "render/radiosity/radiosity_elements.h"
#include "render/radiosity/radiosity_texture_tint.h"
#include "support/texture_images.h"

namespace pm {
namespace {

// The unit square in y = 0 (normal +y) with texture coordinates u = x, v = z, textured with a
// width x 1 image of the given RGB texels, next to an untextured square at x in [2, 3].
Scene textured_floor(int width, const std::vector<uint8_t>& rgb) {
  Scene s;
  s.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}, {2, 0, 0}, {3, 0, 0}, {3, 0, 1}, {2, 0, 1}};
  s.indices = {0, 3, 2, 0, 2, 1, 4, 7, 6, 4, 6, 5};
  s.triangle_material = {0, 0, 1, 1};
  s.triangle_uvs = {{0, 0}, {0, 1}, {1, 1}, {0, 0}, {1, 1}, {1, 0}};
  TextureImage image;
  image.source = "test";
  image.width = width;
  image.height = 1;
  image.file_channels = 3;
  for (size_t i = 0; i < rgb.size(); i += 3) image.rgba.insert(image.rgba.end(), {rgb[i], rgb[i + 1], rgb[i + 2], 255});
  s.images = {image};
  s.textures = {TextureRef{0, TextureWrap::clamp_to_edge, TextureWrap::clamp_to_edge}};
  MaterialDesc textured, plain;
  textured.diffuse = {1, 1, 1};
  textured.base_color_texture = 0;
  s.materials = {textured, plain};
  return s;
}

std::vector<float4> tints_of(const Scene& scene, double max_edge, RadiosityElements* elements) {
  const RefinedMesh mesh = refine_mesh(scene, max_edge);
  *elements = build_radiosity_elements(scene, mesh, 40.0f, false);
  DeviceTextures textures;
  pack_texture_images(scene, &textures);
  return radiosity_texture_tints(scene, mesh, *elements, textures);
}

int element_material(const RadiosityElements& el, size_t e) { return PM_AS_INT(el.data[2 * e].w); }

TEST(RadiosityTextureTint, UniformTextureGivesItsColourExactly) {
  const Scene scene = textured_floor(3, {200, 100, 50, 200, 100, 50, 200, 100, 50});
  RadiosityElements el;
  const std::vector<float4> tints = tints_of(scene, 0.3, &el);
  ASSERT_EQ(tints.size(), el.count());
  size_t textured = 0;
  for (size_t e = 0; e < el.count(); ++e) {
    if (element_material(el, e) == 1) {
      EXPECT_EQ(tints[e].x, 1.0f);
      continue;
    }
    ++textured;
    EXPECT_NEAR(tints[e].x, test::srgb_to_linear(200), 1e-6);
    EXPECT_NEAR(tints[e].y, test::srgb_to_linear(100), 1e-6);
    EXPECT_NEAR(tints[e].z, test::srgb_to_linear(50), 1e-6);
  }
  EXPECT_GT(textured, 9u);  // the square was refined into more than its four corners
}

TEST(RadiosityTextureTint, HalvesGiveTheirColoursAndTheSeamAHatWeightedMix) {
  std::vector<uint8_t> rgb;
  for (int i = 0; i < 64; ++i) rgb.insert(rgb.end(), {uint8_t(i < 32 ? 255 : 0), uint8_t(i < 32 ? 0 : 255), 0});
  const Scene scene = textured_floor(64, rgb);
  RadiosityElements el;
  const std::vector<float4> tints = tints_of(scene, 0.1, &el);
  size_t inside = 0, seam = 0;
  for (size_t e = 0; e < el.count(); ++e) {
    if (element_material(el, e) != 0) continue;
    const float x = el.position(e).x;
    EXPECT_NEAR(tints[e].x + tints[e].y, 1.0f, 1e-5) << x;
    if (x < 0.35f) {
      EXPECT_NEAR(tints[e].x, 1.0f, 1e-6) << x;
      ++inside;
    } else if (x > 0.65f) {
      EXPECT_NEAR(tints[e].y, 1.0f, 1e-6) << x;
      ++inside;
    } else if (std::fabs(x - 0.5f) < 1e-6f) {
      // An inner vertex's one-ring is point-symmetric about it, so half of its hat lies on each
      // side: half and half. At the square's edge the ring is one triangle on one side and two
      // on the other: a third and two thirds.
      const float z = el.position(e).z;
      if (z > 0.05f && z < 0.95f) EXPECT_NEAR(tints[e].x, 0.5f, 1e-4) << z;
      else EXPECT_NEAR(std::fabs(tints[e].x - 0.5f), 1.0f / 6.0f, 1e-4) << z;
      ++seam;
    }
  }
  EXPECT_GT(inside, 20u);
  EXPECT_GT(seam, 3u);
}

}  // namespace
}  // namespace pm

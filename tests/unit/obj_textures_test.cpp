// Textures through the OBJ path: images decoded with stb_image (what a PNG holds, where the file
// has no alpha, the size limits, one decoded copy per file), vt coordinates per corner (v flipped,
// fanned large faces too), MTL map_Kd and map_d with their options, the warning per ignored MTL
// statement, and bad input: a missing or undecodable image and a broken vt line, each one line
// naming the file and the field or line. Images are written by the tests (tests/support).
#include <gtest/gtest.h>

#include <string>

#include "render/errors.h"
#include "scene_io/scene_file.h"
#include "scene_io/texture_files.h"
#include "support/test_folder.h"
#include "support/texture_images.h"

namespace pm {
namespace {

const char kScene[] = R"({
  "format": "pmrender-scene", "version": 1,
  "meshes": [ { "file": "quad.obj" } ],
  "lights": [ { "position": [0, 2, 0], "power": [1, 1, 1] } ],
  "camera": { "position": [0, 0, -5], "look_at": [0, 0, 0] }
})";

// A unit quad in z = 0 with texture coordinates on its corners, material `m` from quad.mtl.
const char kQuad[] =
    "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 0.75\nusemtl m\nf 1/1 2/2 3/3 4/4\n";

class ObjTextures : public test::FolderTest {
 protected:
  ObjTextures() : FolderTest("pm_obj_textures_") {}

  Scene load(const std::string& mtl, SceneLoadReport* report = nullptr, const std::string& obj = kQuad) {
    write("quad.obj", obj);
    write("quad.mtl", mtl);
    return load_scene_file(write("scene.json", kScene), report);
  }
  std::string error(const std::string& mtl, const std::string& obj = kQuad) {
    try {
      load(mtl, nullptr, obj);
    } catch (const InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "loaded without an InputError";
    return "";
  }
};

TEST_F(ObjTextures, DecodingKeepsColourAsStoredAndAddsOpaqueAlpha) {
  const std::string png = test::png_bytes(2, 1, 3, {10, 20, 30, 200, 100, 0});
  const TextureImage image =
      decode_texture_image(reinterpret_cast<const unsigned char*>(png.data()), png.size(), "a.png", "here");
  EXPECT_EQ(image.width, 2);
  EXPECT_EQ(image.height, 1);
  EXPECT_EQ(image.file_channels, 3);
  const std::vector<uint8_t> expected = {10, 20, 30, 255, 200, 100, 0, 255};
  EXPECT_EQ(image.rgba, expected);
  const std::string grey_alpha = test::png_bytes(1, 1, 2, {90, 40});
  const TextureImage ga =
      decode_texture_image(reinterpret_cast<const unsigned char*>(grey_alpha.data()), grey_alpha.size(), "b.png", "here");
  EXPECT_EQ(ga.file_channels, 2);
  EXPECT_EQ(ga.rgba, (std::vector<uint8_t>{90, 90, 90, 40}));
}

TEST_F(ObjTextures, UndecodableAndOversizedImagesAreRefusedBeforeDecoding) {
  const std::string junk = "this is not an image";
  try {
    decode_texture_image(reinterpret_cast<const unsigned char*>(junk.data()), junk.size(), "x.png", "f.mtl: map_Kd");
    ADD_FAILURE() << "decoded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("f.mtl: map_Kd: 'x.png' is not an image stb_image can decode ("), std::string::npos)
        << e.what();
  }
  // A PNG whose header claims 20000 x 1 texels (stb_image does not check the header's CRC).
  std::string png = test::png_bytes(1, 1, 3, {1, 2, 3});
  png[16] = 0, png[17] = 0, png[18] = char(0x4e), png[19] = char(0x20);
  try {
    decode_texture_image(reinterpret_cast<const unsigned char*>(png.data()), png.size(), "wide.png", "f.mtl: map_Kd");
    ADD_FAILURE() << "decoded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'wide.png' is 20000x1 texels; at most 16384 a side"), std::string::npos) << e.what();
  }
}

TEST_F(ObjTextures, MapKdAndMapDBecomeTheMaterialsTexturesWithFlippedCoordinates) {
  write("checker.png", test::png_bytes(2, 2, 3, {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255}));
  write("mask.png", test::png_bytes(2, 1, 1, {0, 255}));
  SceneLoadReport report;
  const Scene scene = load("newmtl m\nKd 0.5 0.6 0.7\nmap_Kd checker.png\nmap_d -clamp on mask.png\n", &report);
  ASSERT_EQ(scene.materials.size(), 1u);
  const MaterialDesc& m = scene.materials[0];
  EXPECT_EQ(m.diffuse.y, 0.6f);  // Kd stays: the texture multiplies it
  ASSERT_GE(m.base_color_texture, 0);
  EXPECT_FALSE(m.texture_tints_specular);
  EXPECT_TRUE(m.alpha_mask);
  EXPECT_EQ(m.alpha_channel, 0);  // a grey mask image: its grey channel
  EXPECT_EQ(m.alpha_cutoff, 0.5f);
  ASSERT_EQ(scene.images.size(), 2u);
  ASSERT_EQ(scene.textures.size(), 2u);
  const TextureRef& base = scene.textures[size_t(m.base_color_texture)];
  EXPECT_EQ(scene.images[base.image].width, 2);
  EXPECT_EQ(base.wrap_u, TextureWrap::repeat);
  EXPECT_EQ(scene.textures[size_t(m.alpha_texture)].wrap_v, TextureWrap::clamp_to_edge);
  EXPECT_EQ(scene.images[scene.textures[size_t(m.alpha_texture)].image].file_channels, 1);
  // Every corner of both triangles carries its vertex's vt, v counted from the image's top:
  // vt 1 0 is the bottom-right corner (1, 1), vt 0 0.75 is (0, 0.25).
  const Float2 expected[4] = {{0, 1}, {1, 1}, {1, 0}, {0, 0.25f}};
  ASSERT_EQ(scene.triangle_uvs.size(), 6u);
  for (size_t c = 0; c < 6; ++c) {
    EXPECT_EQ(scene.triangle_uvs[c].u, expected[scene.indices[c]].u) << c;
    EXPECT_EQ(scene.triangle_uvs[c].v, expected[scene.indices[c]].v) << c;
  }
  EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
}

TEST_F(ObjTextures, OneImageFileIsDecodedOnceAndMapDReadsAlphaWhereThereIsOne) {
  write("rgba.png", test::png_bytes(1, 1, 4, {1, 2, 3, 4}));
  const std::string obj = std::string(kQuad) + "usemtl n\nf 1/1 2/2 3/3\n";
  write("quad.obj", obj);
  write("quad.mtl", "newmtl m\nmap_Kd rgba.png\nmap_d rgba.png\nnewmtl n\nmap_Kd -clamp on rgba.png\n");
  const Scene scene = load_scene_file(write("scene.json", kScene));
  EXPECT_EQ(scene.images.size(), 1u);
  EXPECT_EQ(scene.textures.size(), 2u);  // repeat and clamp
  EXPECT_EQ(scene.materials[0].alpha_channel, 3);
  EXPECT_EQ(scene.materials[0].alpha_texture, scene.materials[0].base_color_texture);
}

TEST_F(ObjTextures, IgnoredStatementsWarnOncePerFileAndUnusedMaterialsReadNoImage) {
  SceneLoadReport report;
  const Scene scene = load(
      "newmtl m\nKd 1 1 1\nmap_Ks s.png\nmap_bump b.png\n"
      "newmtl unused\nmap_Kd not-there.png\n",
      &report);
  EXPECT_TRUE(scene.images.empty());
  EXPECT_TRUE(scene.triangle_uvs.empty());  // an untextured scene keeps none
  ASSERT_EQ(report.warnings.size(), 2u);
  EXPECT_NE(report.warnings[0].find("quad.mtl: map_Ks is not rendered; ignored in 1 material ('m')"), std::string::npos)
      << report.warnings[0];
  EXPECT_NE(report.warnings[1].find("quad.mtl: map_bump is not rendered"), std::string::npos) << report.warnings[1];
}

TEST_F(ObjTextures, MissingOrUndecodableImagesNameTheMtlFileMaterialAndStatement) {
  std::string message = error("newmtl m\nmap_Kd textures/none.png\n");
  EXPECT_NE(message.find("quad.mtl: material 'm': map_Kd: cannot open 'textures/none.png' (No such file or directory"),
            std::string::npos)
      << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
  write("broken.png", "\x89PNG\r\n\x1a\n but nothing after it");
  message = error("newmtl m\nmap_d broken.png\n");
  EXPECT_NE(message.find("quad.mtl: material 'm': map_d: 'broken.png' is not an image stb_image can decode"),
            std::string::npos)
      << message;
}

TEST_F(ObjTextures, BrokenTextureCoordinatesAreErrorsWithTheirLine) {
  write("t.png", test::uniform_png(1, 1, 9, 9, 9));
  std::string message = error("newmtl m\nmap_Kd t.png\n", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt nan 0\nf 1/1 2/1 3/1\n");
  EXPECT_NE(message.find("quad.obj: line 4: texture coordinate 'nan' is not a finite decimal number"), std::string::npos)
      << message;
  message = error("newmtl m\n", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt \nf 1 2 3\n");
  EXPECT_NE(message.find("quad.obj: line 4: texture coordinate has 0 values"), std::string::npos) << message;
}

TEST_F(ObjTextures, LargeFannedFacesAndOutOfRangeIndicesKeepTheirCoordinates) {
  write("t.png", test::uniform_png(1, 1, 9, 9, 9));
  // A convex 70-gon (fanned by pmrender, not tinyobjloader), each corner with its own vt, and one
  // triangle whose vt index is out of range (a warning; (0, 0) there).
  std::string obj = "mtllib quad.mtl\nusemtl m\n";
  std::string face = "f";
  for (int i = 0; i < 70; ++i) {
    const double a = 2 * M_PI * i / 70;
    obj += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
    obj += "vt " + std::to_string(i / 100.0) + " 0.5\n";
    face += " " + std::to_string(i + 1) + "/" + std::to_string(i + 1);
  }
  obj += face + "\nf 1/1 2/2 3/99\n";
  SceneLoadReport report;
  const Scene scene = load("newmtl m\nmap_Kd t.png\n", &report, obj);
  ASSERT_EQ(scene.triangle_count(), 69u);
  ASSERT_EQ(scene.triangle_uvs.size(), 3u * 69u);
  // tinyobjloader's triangle (the last face) comes first, then the fan (1, i, i + 1).
  EXPECT_EQ(scene.triangle_uvs[2].u, 0.0f);
  EXPECT_EQ(scene.triangle_uvs[2].v, 0.0f);
  EXPECT_FLOAT_EQ(scene.triangle_uvs[3 + 1].u, 0.01f);
  EXPECT_FLOAT_EQ(scene.triangle_uvs[3 + 2].u, 0.02f);
  EXPECT_FLOAT_EQ(scene.triangle_uvs[3 + 2].v, 0.5f);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("face texture coordinate index 99 out of range (70 texture coordinates); ignored: "
                                    "such corners get texture coordinates (0, 0)"),
            std::string::npos)
      << report.warnings[0];
}

}  // namespace
}  // namespace pm

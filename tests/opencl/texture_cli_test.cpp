// Textured scenes through the command line on the OpenCL backend: an OBJ/MTL scene whose image
// the test writes renders its texel's colour, `bench` reports the textures' device memory (text
// and JSON), and `export-scene`, whose JSON materials are plain colours, refuses a textured
// scene with one line and exit code 2 instead of writing a different scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "render/exr_io.h"
#include "support/pmrender_process.h"
#include "support/texture_images.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

// A floor quad under a light, seen from above, with map_Kd (a uniform texel) and Kd 1; the
// same floor white beside it in a second scene.
class TextureCli : public test::PmrenderProcessTest {
 protected:
  void SetUp() override {
    PmrenderProcessTest::SetUp();
    write("tile.png", test::uniform_png(4, 4, 64, 128, 192));
    write("floor.obj",
          "mtllib floor.mtl\nv -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
          "usemtl tile\nf 1/1 2/2 3/3 4/4\n");
    write("floor.mtl", "newmtl tile\nKd 1 1 1\nmap_Kd tile.png\nnewmtl white\nKd 1 1 1\n");
    write("white.obj", "mtllib floor.mtl\nv -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nusemtl white\nf 1 2 3 4\n");
    const std::string rest = R"(], "lights": [{"position": [0, 2, 0], "power": [10, 10, 10]}],
      "camera": {"position": [0, 3, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "vertical_fov": 30, "resolution": [16, 16]} })";
    write("tiled.json", R"({ "format": "pmrender-scene", "version": 1, "meshes": [{"file": "floor.obj"})" + rest);
    write("white.json", R"({ "format": "pmrender-scene", "version": 1, "meshes": [{"file": "white.obj"})" + rest);
  }
  void write(const std::string& name, const std::string& content) { std::ofstream(dir_ / name, std::ios::binary) << content; }
};

TEST_F(TextureCli, RenderShowsTheTexelsColour) {
  for (const char* scene : {"tiled", "white"}) {
    const test::ProcessResult r = pmrender(std::string("render --backend opencl --photons 0 -q --float ") +
                                           (dir_ / (std::string(scene) + ".json")).string() + " -o " +
                                           (dir_ / (std::string(scene) + "_#.exr")).string());
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  }
  const FrameImage tiled = read_exr((dir_ / "tiled_0.exr").string()), white = read_exr((dir_ / "white_0.exr").string());
  const std::vector<float>& a = tiled.find("direct")->rgb;
  const std::vector<float>& b = white.find("direct")->rgb;
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_GT(b[i], 0.0f) << i;
    EXPECT_NEAR(a[i] / b[i], test::srgb_to_linear(64 * (1 + int(i % 3))), 1e-4) << "value " << i;
  }
}

TEST_F(TextureCli, BenchReportsTheTexturesDeviceMemory) {
  const fs::path json = dir_ / "bench.json";
  const test::ProcessResult r = pmrender("bench --backend opencl --photons 1000 --warmup 0 --repeat 1 --json " +
                                         json.string() + " " + (dir_ / "tiled.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  // 16 texels of 4 bytes, one 16-byte descriptor, two triangles' texture coordinates (64 bytes),
  // the 256-entry sRGB table.
  EXPECT_NE(r.out.find("textures: 1 images, 16 texels, 0.0 MiB on the device"), std::string::npos) << r.out;
  const nlohmann::json j = nlohmann::json::parse(test::read_text(json));
  EXPECT_EQ(j["memory"]["texture_bytes"].get<uint64_t>(), 16u * 4u + 16u + 2u * 32u + 256u * 4u);
  EXPECT_EQ(j["scene"]["texels"].get<uint64_t>(), 16u);
}

TEST_F(TextureCli, ExportSceneRefusesATexturedScene) {
  const test::ProcessResult r =
      pmrender("export-scene " + (dir_ / "tiled.json").string() + " -o " + (dir_ / "out.json").string());
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("tiled.json: textures and alpha masks cannot be exported"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "out.json"));
}

}  // namespace
}  // namespace pm

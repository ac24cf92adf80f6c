// Loading a JSON scene's environment: the constant radiance, an OpenEXR map (written here with
// the project's EXR writer) with its scale and turn and its path relative to the scene file, an
// environment as the scene's only light, export-scene keeping it, and the one-line errors
// naming the scene file, the field and the map file: a missing or unreadable map, negative or
// NaN texels, negative or infinite radiance, both or neither of radiance and map, map-only keys
// on a constant.
#include <ImfRgbaFile.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "render/errors.h"
#include "render/exr_io.h"
#include "render/scene_environment.h"
#include "scene_io/scene_export.h"
#include "scene_io/scene_file.h"
#include "support/scene_load_error.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

class EnvironmentScene : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) / (std::string("pm_environment_scene_") + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "skies");
    std::ofstream(dir_ / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A scene with no light but its environment (the JSON object's text).
  std::string scene_with(const std::string& environment) {
    const fs::path path = dir_ / "scene.json";
    std::ofstream(path) << R"({"format": "pmrender-scene", "version": 1, "meshes": [{"file": "tri.obj"}],
      "environment": )" << environment << R"(, "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0]}})";
    return path.string();
  }
  // Writes a 4 x 2 map into skies/NAME whose texel (3, 1) green is `odd` (FLOAT channels).
  void write_map(const std::string& name, float odd) {
    FrameImage map;
    map.width = 4;
    map.height = 2;
    std::vector<float> rgb(4 * 2 * 3);
    for (size_t k = 0; k < rgb.size(); ++k) rgb[k] = 0.25f * float(k % 5);
    rgb[3 * (1 * 4 + 3) + 1] = odd;
    map.layers.push_back(ImageLayer{"", rgb});
    write_exr((dir_ / "skies" / name).string(), map, true);
  }
  // A 2 x 1 HALF map whose texel (1, 0) green is NaN, written with OpenEXR itself: the project's
  // writer refuses NaN, as it should for its own images.
  void write_nan_map(const std::string& name) {
    Imf::Rgba pixels[2] = {Imf::Rgba(1, 1, 1), Imf::Rgba(1, std::numeric_limits<float>::quiet_NaN(), 1)};
    Imf::RgbaOutputFile file((dir_ / "skies" / name).c_str(), 2, 1, Imf::WRITE_RGB);
    file.setFrameBuffer(pixels, 1, 2);
    file.writePixels(1);
  }
  static std::string error_of(const std::string& path) { return test::scene_load_error(path); }
  void expect_error(const std::string& environment, const std::string& expected) {
    const std::string message = error_of(scene_with(environment));
    EXPECT_EQ(message.rfind((dir_ / "scene.json").string() + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << "message: " << message << "\nexpected: " << expected;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  fs::path dir_;
};

TEST_F(EnvironmentScene, ConstantRadianceIsALight) {
  const Scene scene = load_scene_file(scene_with(R"({"radiance": [0.5, 1, 2]})"));
  EXPECT_EQ(scene.environment.type, EnvironmentType::constant);
  EXPECT_FLOAT_EQ(scene.environment.radiance.z, 2.0f);
  EXPECT_TRUE(scene.lights.empty());
  EXPECT_TRUE(scene.has_light());
}

TEST_F(EnvironmentScene, MapIsReadRelativeToTheSceneWithScaleAndTurn) {
  write_map("sky.exr", 3.0f);
  const Scene scene = load_scene_file(scene_with(R"({"map": "skies/sky.exr", "scale": 2, "rotation_deg": -90})"));
  const EnvironmentDesc& env = scene.environment;
  ASSERT_EQ(env.type, EnvironmentType::map);
  EXPECT_EQ(env.width, 4);
  EXPECT_EQ(env.height, 2);
  EXPECT_FLOAT_EQ(env.texels[3 * (1 * 4 + 3) + 1], 6.0f);  // scaled
  EXPECT_FLOAT_EQ(env.texels[1], 0.5f);
  EXPECT_FLOAT_EQ(env.rotation_degrees, -90.0f);
  EXPECT_EQ(fs::path(env.map_file), dir_ / "skies" / "sky.exr");
  EXPECT_TRUE(scene.has_light());
  EXPECT_EQ(build_environment_distribution(env).type, PM_ENVIRONMENT_MAP);
}

TEST_F(EnvironmentScene, ExportedScenesKeepTheEnvironment) {
  write_map("sky.exr", 3.0f);
  const Scene scene = load_scene_file(scene_with(R"({"map": "skies/sky.exr", "scale": 2, "rotation_deg": 15})"));
  export_scene(scene, 0, (dir_ / "export" / "scene.json").string());
  const Scene again = load_scene_file((dir_ / "export" / "scene.json").string());
  EXPECT_EQ(again.environment.type, EnvironmentType::map);
  EXPECT_EQ(again.environment.texels, scene.environment.texels);  // the file once, scaled once
  EXPECT_FLOAT_EQ(again.environment.rotation_degrees, 15.0f);
  const Scene constant = load_scene_file(scene_with(R"({"radiance": [0.5, 1, 2]})"));
  export_scene(constant, 0, (dir_ / "export2" / "scene.json").string());
  EXPECT_FLOAT_EQ(load_scene_file((dir_ / "export2" / "scene.json").string()).environment.radiance.z, 2.0f);
}

TEST_F(EnvironmentScene, BadMapsNameTheFieldAndTheFile) {
  expect_error(R"({"map": "skies/none.exr"})", "environment.map: cannot open '" + (dir_ / "skies/none.exr").string() +
                                                   "' (no such file)");
  std::ofstream(dir_ / "skies" / "text.exr") << "not an image\n";
  expect_error(R"({"map": "skies/text.exr"})", "environment.map: EXR file '" + (dir_ / "skies/text.exr").string() +
                                                   "': not an OpenEXR file");
  expect_error(R"({"map": "skies"})", "environment.map: cannot open '" + (dir_ / "skies").string() + "' (it is a directory)");
  write_map("negative.exr", -1.0f);
  expect_error(R"({"map": "skies/negative.exr"})", "environment.map: '" + (dir_ / "skies/negative.exr").string() +
                                                       "': texel (3, 1) green is -1; an environment's radiance must be "
                                                       "finite and >= 0");
  write_nan_map("nan.exr");
  expect_error(R"({"map": "skies/nan.exr"})", "': texel (1, 0) green is nan");
  expect_error(R"({"map": "skies/negative.exr", "scale": -1})", "environment.scale: must be in [0, 1e30], got -1");
}

TEST_F(EnvironmentScene, BadFieldsAreRefused) {
  expect_error(R"({"radiance": [1, -0.5, 1]})", "environment.radiance[1]: must be >= 0 W sr^-1 m^-2, got -0.5");
  expect_error(R"({"radiance": [1, 1e999, 1]})", "environment.radiance[1]: expected a finite number");
  expect_error(R"({"radiance": [1, 1, 1], "map": "sky.exr"})", "environment: expected exactly one of \"radiance\"");
  expect_error(R"({})", "environment: expected exactly one of \"radiance\"");
  expect_error(R"({"radiance": [1, 1, 1], "scale": 2})", "environment.scale: only a map has this key");
  expect_error(R"({"radiance": [1, 1, 1], "colour": 2})", "environment.colour: unknown key");
  expect_error(R"({"radiance": [0, 0, 0]})", "lights: no light: no light with power above zero under lights and no "
                                             "emitting material (materials' emission, MTL Ke) on any triangle, and no "
                                             "environment with radiance above zero");
}

}  // namespace
}  // namespace pm

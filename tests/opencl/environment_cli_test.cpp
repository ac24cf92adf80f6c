// --environment on the command line: a constant radiance or an OpenEXR map (written here) with
// --environment-scale replaces the scene's environment and counts as its light, in a JSON scene
// without lights and in a glTF scene without lights; the sky the camera sees is that radiance.
// The EXR header's settings name it. Bad values are refused with one line naming the option,
// exit code 2, before any device work.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "render/exr_io.h"
#include "support/image_stats.h"
#include "support/paths.h"
#include "support/pmrender_process.h"

namespace pm {
namespace {

using test::ProcessResult;

class EnvironmentCli : public test::PmrenderProcessTest {
 protected:
  // A floor quad without any light; the camera looks up into the sky.
  std::string sky_scene() {
    std::ofstream(dir_ / "floor.obj") << "v -4 0 -4\nv -4 0 4\nv 4 0 4\nv 4 0 -4\nf 1 2 3\nf 1 3 4\n";
    std::ofstream(dir_ / "sky.json") << R"({"format": "pmrender-scene", "version": 1,
      "meshes": [{"file": "floor.obj"}],
      "camera": {"position": [0, 1, 0], "look_at": [0, 3, 0.1], "vertical_fov": 30, "resolution": [8, 8]}})";
    return (dir_ / "sky.json").string();
  }
  ProcessResult render(const std::string& args) {
    return pmrender("render " + args + " --backend opencl --photons 1000 -o " + (dir_ / "out.exr").string());
  }
  void expect_refused(const std::string& args, const std::string& expect) {
    SCOPED_TRACE(args);
    const ProcessResult r = render(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err.rfind("pmrender: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(expect), std::string::npos) << r.err;
  }
};

TEST_F(EnvironmentCli, ConstantRadianceLightsASceneWithoutLights) {
  const std::string scene = sky_scene();
  expect_refused(scene, "no light");
  const ProcessResult r = render(scene + " --environment 0.25,0.5,1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const FrameImage image = read_exr((dir_ / "out.exr").string());
  // The settings (and so a checkpoint's fingerprint) name the environment.
  std::string settings;
  for (const auto& [key, value] : image.attributes)
    if (key == "pmrender/settings") settings = value;
  EXPECT_NE(settings.find(" environment=0.25,0.5,1 "), std::string::npos) << settings;
  const std::vector<float>& rgb = image.find("")->rgb;
  for (size_t p = 0; p < rgb.size() / 3; ++p) {
    EXPECT_EQ(rgb[3 * p], 0.25f);
    EXPECT_EQ(rgb[3 * p + 1], 0.5f);
    EXPECT_EQ(rgb[3 * p + 2], 1.0f);
  }
}

TEST_F(EnvironmentCli, MapWithScaleAndAGltfScene) {
  FrameImage map;
  map.width = 8;
  map.height = 4;
  map.layers.push_back(ImageLayer{"", std::vector<float>(8 * 4 * 3, 0.75f)});
  write_exr((dir_ / "map.exr").string(), map, true);
  const ProcessResult r = render(sky_scene() + " --environment " + (dir_ / "map.exr").string() +
                                 " --environment-scale 2 --environment-rotation 45");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NEAR(test::mean(read_exr((dir_ / "out.exr").string()).find("")->rgb), 1.5, 1e-6);
  // glTF has no environment of its own: the option lights a glTF scene without lights.
  const std::string gltf = test::test_data_dir() + "/bad_input/scenes/gltf_no_light.gltf";
  expect_refused(gltf, "no light");
  EXPECT_EQ(render(gltf + " --environment 1,1,1").exit_code, 0);
}

TEST_F(EnvironmentCli, BadValuesNameTheOption) {
  const std::string scene = sky_scene();
  expect_refused(scene + " --environment 1,2", "--environment: expected R,G,B (three numbers >= 0) or an OpenEXR file");
  expect_refused(scene + " --environment 1,-1,2", "--environment: expected a finite number >= 0, got '-1'");
  expect_refused(scene + " --environment nan,1,1", "--environment: expected a finite number");
  expect_refused(scene + " --environment no_such_sky.exr", "--environment: cannot open 'no_such_sky.exr' (no such file)");
  expect_refused(scene + " --environment " + scene, "--environment: EXR file '" + scene + "'");
  expect_refused(scene + " --environment 1,1,1 --environment-scale 2",
                 "--environment-scale: applies to an --environment map, not to a constant radiance");
  expect_refused(scene + " --environment-rotation 5", "--environment-rotation: applies to an --environment map");
  expect_refused(scene + " --environment-scale -1", "--environment-scale: expected a number from 0");
}

}  // namespace
}  // namespace pm

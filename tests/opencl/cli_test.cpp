// The pmrender command line as a user meets it, run as a separate process on the OpenCL
// backend: exit codes (0 ok, 1 device failure, 2 bad usage or input), one-line messages that
// name the file and field, and no output file after any failure.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "render/exr_io.h"
#include "support/image_stats.h"
#include "support/paths.h"
#include "support/pmrender_process.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

using test::ProcessResult;

class Cli : public test::PmrenderProcessTest {
 protected:


  std::string data(const std::string& name) { return test::test_data_dir() + "/cli/" + name; }
  bool any_exr_written() {
    for (auto& entry : fs::recursive_directory_iterator(dir_))
      if (entry.path().extension() == ".exr" || entry.path().string().find(".tmp-") != std::string::npos) return true;
    return false;
  }

  // A failed render: exit code 2, one line on stderr naming `expect`, nothing written.
  void expect_input_error(const std::string& args, const std::string& expect) {
    ProcessResult r = pmrender(args + " -o " + (dir_ / "f_####.exr").string());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(expect), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(any_exr_written());
  }

};

TEST_F(Cli, DefaultSceneRendersAFiniteLitExr) {
  ProcessResult r = pmrender("render --backend opencl --resolution 48x40 -o " + (dir_ / "cb_####.exr").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  fs::path out = dir_ / "cb_0000.exr";
  ASSERT_TRUE(fs::exists(out));
  FrameImage image = read_exr(out.string());
  EXPECT_EQ(image.width, 48);
  EXPECT_EQ(image.height, 40);
  ASSERT_NE(image.find("direct"), nullptr);
  const std::vector<float>& rgb = image.find("")->rgb;
  EXPECT_TRUE(test::all_finite(rgb));
  double sum = 0;
  for (float v : rgb) sum += v;
  EXPECT_GT(sum / rgb.size(), 1e-3);
  bool has_scene_attribute = false;
  for (auto& [key, value] : image.attributes) has_scene_attribute |= key == "pmrender/scene" && value.find("cornell") != std::string::npos;
  EXPECT_TRUE(has_scene_attribute);
}

TEST_F(Cli, SceneFileRendersWithFloatChannels) {
  ProcessResult r = pmrender("render " + data("valid.json") + " --backend opencl --float -o " + (dir_ / "q.exr").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  FrameImage image = read_exr((dir_ / "q.exr").string());
  EXPECT_EQ(image.width, 32);
  EXPECT_EQ(image.height, 24);
}

TEST_F(Cli, MalformedJsonNamesFileAndLine) { expect_input_error("render " + data("bad_json.json"), "bad_json.json: line"); }
TEST_F(Cli, MissingMeshNamesTheField) { expect_input_error("render " + data("missing_mesh.json"), "missing.obj"); }
TEST_F(Cli, UnknownKeyNamesTheField) { expect_input_error("render " + data("unknown_key.json"), "lights[0].colour"); }
TEST_F(Cli, NonFinitePositionNamesTheField) { expect_input_error("render " + data("nan_position.json"), "lights[0].position"); }
TEST_F(Cli, MissingSceneFileIsAnInputError) { expect_input_error("render " + data("nope.json"), "nope.json"); }
TEST_F(Cli, BadResolutionIsAnInputError) { expect_input_error("render --resolution 12by4", "--resolution"); }
TEST_F(Cli, OutOfRangeDeviceIsAnInputError) { expect_input_error("render --backend opencl --device 99", "--device: no device 99"); }

TEST_F(Cli, UnknownOptionIsUsageError) {
  ProcessResult r = pmrender("render --no-such-option");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_FALSE(any_exr_written());
}

TEST_F(Cli, DevicesListsAnOpenclDevice) {
  ProcessResult r = pmrender("devices");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("opencl  --device 0"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace pm

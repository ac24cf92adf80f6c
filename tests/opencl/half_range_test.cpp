// Light powers whose images do not fit half channels: the values are clamped at 65504 or rounded
// to 0 in the file, and pmrender says so and names --float; with --float the values are kept and
// nothing is said. Normal scenes say nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "render/exr_io.h"
#include "support/paths.h"
#include "support/pmrender_process.h"

namespace pm {
namespace {

class HalfRange : public test::PmrenderProcessTest {
 protected:
  // The command-line test quad scene with the light's power replaced.
  std::string scene_with_power(const std::string& power) {
    std::string text = test::read_text(test::test_data_dir() + "/cli/valid.json");
    const std::string from = "\"power\": [20, 20, 20]";
    text.replace(text.find(from), from.size(), "\"power\": [" + power + ", " + power + ", " + power + "]");
    const std::string mesh = "\"file\": \"quad.obj\"";
    text.replace(text.find(mesh), mesh.size(), "\"file\": \"" + test::test_data_dir() + "/cli/quad.obj\"");
    const std::string path = (dir_ / "scene.json").string();
    std::ofstream(path) << text;
    return path;
  }
  test::ProcessResult render(const std::string& power, const std::string& extra) {
    return pmrender("render " + scene_with_power(power) + " --backend opencl --photons 2000 --frames 0-2 -o " +
                    (dir_ / "f_#.exr").string() + " " + extra);
  }
  size_t count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
  }
};

TEST_F(HalfRange, OverflowIsClampedWithOneWarningNamingFloat) {
  const test::ProcessResult r = render("1e30", "");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("frame 0: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("exceed the half-float range and were clamped to 65504; use --float"), std::string::npos) << r.err;
  EXPECT_EQ(count(r.err, "pmrender: warning:"), 1u) << r.err;  // three frames, one line
  const FrameImage image = read_exr((dir_ / "f_0.exr").string());
  EXPECT_EQ(*std::max_element(image.find("")->rgb.begin(), image.find("")->rgb.end()), 65504.0f);
}

TEST_F(HalfRange, UnderflowToZeroWarnsNamingFloat) {
  const test::ProcessResult r = render("1e-20", "");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("below the half-float range and were written as 0; use --float"), std::string::npos) << r.err;
  const FrameImage image = read_exr((dir_ / "f_0.exr").string());
  EXPECT_EQ(*std::max_element(image.find("")->rgb.begin(), image.find("")->rgb.end()), 0.0f);
}

TEST_F(HalfRange, FloatChannelsKeepTheValuesSilently) {
  for (const char* power : {"1e30", "1e-20"}) {
    const test::ProcessResult r = render(power, "--float");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "") << power;
    const FrameImage image = read_exr((dir_ / "f_0.exr").string());
    const float peak = *std::max_element(image.find("")->rgb.begin(), image.find("")->rgb.end());
    EXPECT_TRUE(std::string(power) == "1e30" ? peak > 65504.0f : peak > 0.0f && peak < 1e-10f) << power << " " << peak;
  }
}

TEST_F(HalfRange, AnOrdinaryLightSaysNothing) {
  const test::ProcessResult r = render("20", "");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
}

}  // namespace
}  // namespace pm

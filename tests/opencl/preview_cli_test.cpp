// `render --preview` and `--exposure` as the user meets them: the PNG beside the EXR carries the
// exposure it was made with, automatic by default (the rule of preview_exposure.h applied to the
// frame the EXR holds), --exposure EV when given; bad values are one-line errors naming the
// option, exit code 2, nothing written.
#include <gtest/gtest.h>
#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "render/exr_io.h"
#include "render/preview_exposure.h"
#include "render/preview_png.h"
#include "support/png_text.h"
#include "support/pmrender_process.h"

namespace pm {
namespace {

namespace fs = std::filesystem;
using test::ProcessResult;

// Direct light only, full-float EXR: the EXR holds exactly the values the preview was made from.
const char kTiny[] = "render --backend opencl --resolution 16x12 --photons 0 --float";

class PreviewCli : public test::PmrenderProcessTest {
 protected:
  std::string at(const std::string& name) { return (dir_ / name).string(); }

  // Every byte of the PNG against the EXR's combined layer tone-mapped at ev.
  void expect_png_is_exr_at(const std::string& png, const std::string& exr, double ev) {
    const FrameImage image = read_exr(exr);
    const ImageLayer* combined = image.find("");
    ASSERT_NE(combined, nullptr);
    int w = 0, h = 0, channels = 0;
    std::unique_ptr<unsigned char, void (*)(void*)> pixels(stbi_load(png.c_str(), &w, &h, &channels, 3), stbi_image_free);
    ASSERT_TRUE(pixels) << stbi_failure_reason();
    ASSERT_EQ(w, image.width);
    ASSERT_EQ(h, image.height);
    const float scale = float(std::exp2(ev));
    for (size_t i = 0; i < combined->rgb.size(); ++i)
      ASSERT_EQ(pixels.get()[i], preview_tone_map(combined->rgb[i], scale)) << i;
  }

  void expect_refused(const std::string& args, const std::string& expect) {
    SCOPED_TRACE(args);
    const ProcessResult r = pmrender(std::string(kTiny) + " " + args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err.rfind("pmrender: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(expect), std::string::npos) << r.err;
    EXPECT_TRUE(fs::is_empty(dir_ / "out")) << "something was written";
  }
};

TEST_F(PreviewCli, TheDefaultExposureIsTheAutomaticOneOfTheFrameAndIsRecorded) {
  const ProcessResult r = pmrender(std::string(kTiny) + " -o " + at("f.exr") + " --preview " + at("f.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto text = test::png_text(at("f.png"));
  ASSERT_EQ(text.count(kPreviewExposureKeyword), 1u);
  const double ev = std::stod(text.at(kPreviewExposureKeyword));
  EXPECT_EQ(ev, automatic_exposure_ev(read_exr(at("f.exr")).find("")->rgb));
  EXPECT_EQ(text.at(kPreviewExposureSourceKeyword).rfind("automatic", 0), 0u);
  expect_png_is_exr_at(at("f.png"), at("f.exr"), ev);
}

TEST_F(PreviewCli, ExposureOverridesTheAutomaticOne) {
  const ProcessResult r =
      pmrender(std::string(kTiny) + " -o " + at("f.exr") + " --preview " + at("f.png") + " --exposure -1.5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto text = test::png_text(at("f.png"));
  EXPECT_EQ(text.at(kPreviewExposureKeyword), "-1.5");
  EXPECT_EQ(text.at(kPreviewExposureSourceKeyword), "--exposure");
  expect_png_is_exr_at(at("f.png"), at("f.exr"), -1.5);
}

TEST_F(PreviewCli, BadExposuresAreOneLineErrorsAndNothingIsWritten) {
  fs::create_directories(dir_ / "out");
  const std::string preview = " --preview " + at("out/p.png") + " -o " + at("out/f.exr");
  expect_refused(preview + " --exposure nan", "--exposure");
  expect_refused(preview + " --exposure inf", "--exposure");
  expect_refused(preview + " --exposure 33", "--exposure");
  expect_refused(preview + " --exposure -40", "--exposure");
  expect_refused(preview + " --exposure 2stops", "--exposure");
  expect_refused(preview + " --exposure ''", "--exposure");
  expect_refused("-o " + at("out/f.exr") + " --exposure 1", "--exposure: sets the exposure of the --preview PNG");
}

}  // namespace
}  // namespace pm

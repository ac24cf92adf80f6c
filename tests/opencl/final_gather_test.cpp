// Final gathering (photon mapping with --final-gather; kernels/common/final_gather.h) on PoCL, in
// the spot-lit box of the lights tests against a long path-traced render of the same box: it reads
// the photon map only at its rays' hits, so a map made deliberately blurry (footprints 64 times
// the paper's smoothing, their flux spread over the whole ellipse: coverage off) costs the image
// only the share of its bias that falls on the light after the first bounce, and shrinking passes
// take what is left towards the path tracer's answer. With one bounce it needs no map: the direct light at
// its rays' hits alone is the first bounce, which the path tracer must agree with.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "render/path/path_settings.h"
#include "render/photon/photon_settings.h"
#include "render/renderer.h"
#include "support/device_checks.h"
#include "support/image_stats.h"
#include "support/lit_boxes.h"
#include "support/render_settings.h"

namespace pm {
namespace {

class FinalGather : public ::testing::Test {
 protected:
  void SetUp() override {
    device_ = test::open_first_device("opencl");
    ASSERT_NE(device_, nullptr);
  }

  // The indirect mean (indirect and caustic layers) of one frame of the spot-lit box.
  double indirect_mean(std::shared_ptr<const MethodSettings> method, uint32_t passes) {
    RenderSettings settings;
    settings.width = settings.height = 16;
    settings.passes = passes;
    settings.control_paths = 0;  // the image only
    settings.method = std::move(method);
    Renderer renderer(*device_, scene_, settings);
    const FrameImage image = renderer.render_frame(0);
    EXPECT_TRUE(test::all_finite(image.find("")->rgb));
    return test::mean(image.find("indirect")->rgb) + test::mean(image.find("caustic")->rgb);
  }

  double path_mean(int bounces) {
    auto path = std::make_shared<PathSettings>();
    path->samples = 256;
    path->bounces = bounces;
    return indirect_mean(path, 16);
  }

  static std::shared_ptr<PhotonSettings> blurry_map(int bounces, uint32_t rays) {
    auto photons = std::make_shared<PhotonSettings>();
    photons->photons = 32768;
    photons->bounces = bounces;
    photons->smoothing = 64;
    photons->footprint_coverage = false;
    photons->final_gather = rays;
    return photons;
  }

  std::unique_ptr<Device> device_;
  Scene scene_ = test::spot_box();
};

TEST_F(FinalGather, HidesTheBlurOfTheMapAndConvergesAsItsPassesShrink) {
  const double reference = path_mean(2);
  const double read_at_x = indirect_mean(blurry_map(2, 0), 1) / reference - 1;
  const double gathered = indirect_mean(blurry_map(2, 16), 1) / reference - 1;
  auto shrinking = blurry_map(2, 16);
  shrinking->progressive = kProgressiveShrink;
  shrinking->alpha = 0.5f;
  const double shrunk = indirect_mean(shrinking, 16) / reference - 1;
  std::printf("spot-lit box, blurry map: read at the shading point %+.4f, final gather %+.4f, final gather over 16 "
              "shrinking passes %+.4f\n", read_at_x, gathered, shrunk);
  // Read at the rays' hits the map supplies only the light after the first bounce: in a box of
  // albedo rho about rho / (1 + rho) of two bounces' light (0.375 here), so that share of its
  // bias is left at one pass. Measured: -2.99 % read at the shading point, -1.35 % gathered.
  EXPECT_LT(std::fabs(gathered), std::fabs(read_at_x) / 2) << "the gather rays average the map's blur away";
  EXPECT_LT(std::fabs(shrunk), std::fabs(gathered));
  EXPECT_LT(std::fabs(shrunk), 0.01);
}

TEST_F(FinalGather, OneBounceIsTheDirectLightAtItsRaysHits) {
  const double reference = path_mean(1);
  const double gathered = indirect_mean(blurry_map(1, 64), 4) / reference - 1;
  std::printf("spot-lit box, first bounce: final gather %+.4f against the path tracer\n", gathered);
  EXPECT_LT(std::fabs(gathered), 0.01);
}

}  // namespace
}  // namespace pm

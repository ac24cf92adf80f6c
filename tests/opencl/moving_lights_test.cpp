// A spot light that turns and then stands (tests/data/animation/turning_spot.json: its direction
// sweeps from frame 0 to frame 6, 0.25 s at 24 fps, and holds; the camera stands): each method
// recomputes only what the light changes, as for point lights (sequence_test.cpp, radiosity_test.cpp).
// Radiosity builds its links once and re-runs the light links and the gathering only while the
// spot turns; photon mapping traces new photons only while it turns and reuses them after. Each
// relit frame equals a fresh render of that frame.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "render/renderer.h"
#include "scene_io/scene_file.h"
#include "support/device_checks.h"
#include "support/image_stats.h"
#include "support/paths.h"
#include "support/render_settings.h"
#include "support/same_image.h"

namespace pm {
namespace {

constexpr int kLastTurningFrame = 6;

Scene turning_spot() { return load_scene_file(test::test_data_dir() + "/animation/turning_spot.json"); }

double stat(const FrameStats& s, const char* name) { return s.method.get(name, -1); }

class MovingLights : public ::testing::Test {
 protected:
  void SetUp() override {
    device_ = test::open_first_device("opencl");
    if (!device_) GTEST_SKIP() << "no OpenCL device";
  }
  std::unique_ptr<Device> device_;
};

TEST_F(MovingLights, RadiosityRelightsOnlyWhileTheSpotTurns) {
  const Scene scene = turning_spot();
  RadiositySettings radiosity;
  radiosity.directions = 16;
  RenderSettings settings = test::radiosity_render_settings(radiosity);
  settings.width = 40;
  settings.height = 30;
  Renderer renderer(*device_, scene, settings);
  FrameImage first, turned;
  for (int f = 0; f <= kLastTurningFrame + 2; ++f) {
    SCOPED_TRACE("frame " + std::to_string(f));
    FrameStats stats;
    FrameImage image = renderer.render_frame(f, &stats);
    EXPECT_EQ(stat(stats, "link_builds"), 1);
    EXPECT_EQ(stat(stats, "light_links_run"), f <= kLastTurningFrame ? 1 : 0);
    EXPECT_EQ(stat(stats, "light_link_runs"), f <= kLastTurningFrame ? f + 1 : kLastTurningFrame + 1);
    if (f == 0) first = image;
    if (f == kLastTurningFrame - 1) turned = image;
  }
  // The spot turned: the indirect light changed.
  EXPECT_GT(test::compare_rgb(turned.find("indirect")->rgb, first.find("indirect")->rgb).mean_relative, 0.01);
  Renderer fresh(*device_, scene, settings);
  test::expect_same_image(turned, fresh.render_frame(kLastTurningFrame - 1), "relit against fresh");
}

TEST_F(MovingLights, PhotonsAreTracedOnlyWhileTheSpotTurns) {
  const Scene scene = turning_spot();
  PhotonSettings photons;
  photons.photons = 20000;
  RenderSettings settings = test::photon_render_settings(photons);
  settings.width = 48;
  settings.height = 36;
  Renderer renderer(*device_, scene, settings);
  FrameImage first, turned;
  for (int f = 0; f <= kLastTurningFrame + 2; ++f) {
    SCOPED_TRACE("frame " + std::to_string(f));
    FrameStats stats;
    FrameImage image = renderer.render_frame(f, &stats);
    EXPECT_EQ(stat(stats, "photons_reused"), f > kLastTurningFrame ? 1 : 0);
    EXPECT_EQ(stat(stats, "photon_frame"), f > kLastTurningFrame ? kLastTurningFrame : f);
    EXPECT_GT(stat(stats, "hits"), 0.0);
    if (f == 0) first = image;
    if (f == kLastTurningFrame + 2) turned = image;
  }
  // The spot turned (the camera pass's direct light shows it without the photons' noise).
  EXPECT_GT(test::compare_rgb(turned.find("direct")->rgb, first.find("direct")->rgb).mean_relative, 0.01);
  // A reused frame is what a fresh renderer computes for it (photons keyed by the run's first frame).
  Renderer fresh(*device_, scene, settings);
  test::expect_same_image(turned, fresh.render_frame(kLastTurningFrame + 2), "reused against fresh");
}

}  // namespace
}  // namespace pm

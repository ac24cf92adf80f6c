// A spot light that turns and then stands (tests/data/animation/turning_spot.json: its direction
// sweeps from frame 0 to frame 6, 0.25 s at 24 fps, and holds; the camera stands): each method
// recomputes only what the light changes, as for point lights (sequence_test.cpp, radiosity_test.cpp).
// Radiosity builds its links once and re-runs the light links and the gathering only while the
// spot turns; photon mapping traces new photons only while it turns and reuses them after. Each
// relit frame equals a fresh render of that frame.
#include <gtest/gtest.h>

#include <functional>
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

// Renders frames 0 to kLastTurningFrame + 2 of the turning spot in one renderer, checks each
// frame's statistics with `check`, and returns frame `kept`'s image after checking that a fresh
// renderer computes the same image for it, and that `layer` changed from frame 0 to it.
FrameImage render_turning(Device& device, const RenderSettings& settings, int kept, const char* layer,
                          const std::function<void(int, const FrameStats&)>& check) {
  const Scene scene = turning_spot();
  Renderer renderer(device, scene, settings);
  FrameImage first, image;
  for (int f = 0; f <= kLastTurningFrame + 2; ++f) {
    SCOPED_TRACE("frame " + std::to_string(f));
    FrameStats stats;
    FrameImage frame = renderer.render_frame(f, &stats);
    check(f, stats);
    if (f == 0) first = frame;
    if (f == kept) image = frame;
  }
  EXPECT_GT(test::compare_rgb(image.find(layer)->rgb, first.find(layer)->rgb).mean_relative, 0.01) << layer;
  Renderer fresh(device, scene, settings);
  test::expect_same_image(image, fresh.render_frame(kept), "against a fresh render");
  return image;
}

TEST_F(MovingLights, RadiosityRelightsOnlyWhileTheSpotTurns) {
  RadiositySettings radiosity;
  radiosity.directions = 16;
  RenderSettings settings = test::radiosity_render_settings(radiosity);
  settings.width = 40;
  settings.height = 30;
  // A relit frame (the spot still turning), whose indirect light changed.
  render_turning(*device_, settings, kLastTurningFrame - 1, "indirect", [](int f, const FrameStats& stats) {
    EXPECT_EQ(stat(stats, "link_builds"), 1);
    EXPECT_EQ(stat(stats, "light_links_run"), f <= kLastTurningFrame ? 1 : 0);
    EXPECT_EQ(stat(stats, "light_link_runs"), f <= kLastTurningFrame ? f + 1 : kLastTurningFrame + 1);
  });
}

TEST_F(MovingLights, PhotonsAreTracedOnlyWhileTheSpotTurns) {
  PhotonSettings photons;
  photons.photons = 20000;
  RenderSettings settings = test::photon_render_settings(photons);
  settings.width = 48;
  settings.height = 36;
  // A reused frame (photons keyed by the run's first frame); the camera pass's direct light shows
  // that the spot turned without the photons' noise.
  render_turning(*device_, settings, kLastTurningFrame + 2, "direct", [](int f, const FrameStats& stats) {
    EXPECT_EQ(stat(stats, "photons_reused"), f > kLastTurningFrame ? 1 : 0);
    EXPECT_EQ(stat(stats, "photon_frame"), f > kLastTurningFrame ? kLastTurningFrame : f);
    EXPECT_GT(stat(stats, "hits"), 0.0);
  });
}

}  // namespace
}  // namespace pm

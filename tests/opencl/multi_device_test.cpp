// Several devices on one frame (render/renderer_pool.h): the passes of a frame shared between
// devices add up to what one device renders. Two OpenCL contexts on the same PoCL device stand in
// for two GPUs here; the GPU machine runs the same code on two H200s.
#include <gtest/gtest.h>

#include <cmath>

#include "render/renderer_pool.h"
#include "scene_io/cornell_box.h"
#include "support/device_checks.h"
#include "support/render_settings.h"
#include "support/same_image.h"

namespace pm {
namespace {

TEST(MultiDevice, SharedPassesSumToTheSingleDeviceFrame) {
  std::unique_ptr<Device> a = test::open_first_device("opencl"), b = test::open_first_device("opencl");
  ASSERT_NE(a, nullptr);
  ASSERT_NE(b, nullptr);
  const Scene scene = builtin_cornell_box();
  PhotonSettings photons;
  photons.photons = 5000;
  photons.progressive = kProgressiveShrink;
  RenderSettings settings = test::photon_render_settings(photons, 12);
  settings.width = settings.height = 32;
  PassBudget budget;
  budget.max_passes = 12;

  RendererPool one({a.get()}, scene, settings);
  one.render_progressive(3, budget, nullptr, 0);
  const FrameImage single = one.first().read_image();

  RendererPool two({a.get(), b.get()}, scene, settings);
  const ProgressiveResult r = two.render_progressive(3, budget, nullptr, 0);
  const FrameImage shared = two.first().read_image();
  EXPECT_EQ(r.passes, 12u);
  EXPECT_EQ(two.passes_per_device()[0] + two.passes_per_device()[1], 12u);
  EXPECT_GT(two.passes_per_device()[1], 0u) << "the second device ran no pass";

  // The same twelve passes, summed in another order: equal up to float rounding.
  test::expect_same_passes_in_another_order(single, shared);
  // The error estimate sees the frame's passes too.
  EXPECT_GT(r.error, 0.0);
}

TEST(MultiDevice, ABudgetStopsEveryDevice) {
  std::unique_ptr<Device> a = test::open_first_device("opencl"), b = test::open_first_device("opencl");
  const Scene scene = builtin_cornell_box();
  PhotonSettings photons;
  photons.photons = 5000;
  RenderSettings settings = test::photon_render_settings(photons, 100000);
  settings.width = settings.height = 32;
  RendererPool two({a.get(), b.get()}, scene, settings);
  PassBudget budget;
  budget.max_passes = 100000;
  budget.seconds = 0.4;
  const ProgressiveResult r = two.render_progressive(0, budget, nullptr, 0);
  EXPECT_EQ(r.stopped_by, "time");
  EXPECT_GE(r.seconds, 0.4);
  EXPECT_LT(r.seconds, 5.0);
  EXPECT_EQ(r.passes, two.passes_per_device()[0] + two.passes_per_device()[1]);
}

}  // namespace
}  // namespace pm

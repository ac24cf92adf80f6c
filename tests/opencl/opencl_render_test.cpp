// End-to-end renders on the OpenCL backend (PoCL in CI): the built-in Cornell box comes out
// finite, lit, red on the left and green on the right, and equal to the same stage functions
// run on the host.
#include <gtest/gtest.h>

#include "render/renderer.h"
#include "scene_io/cornell_box.h"
#include "support/device_checks.h"
#include "support/host_render.h"
#include "support/image_stats.h"

namespace pm {
namespace {

std::vector<float> rgb_of(const std::vector<float4>& pixels) {
  std::vector<float> rgb;
  for (const float4& p : pixels) rgb.insert(rgb.end(), {p.x, p.y, p.z});
  return rgb;
}

// The built-in Cornell box at 64x64, direct light only, on the first OpenCL device.
FrameImage render_direct_cornell_64() {
  std::unique_ptr<Device> device = test::open_first_device("opencl");
  EXPECT_NE(device, nullptr);
  if (!device) return {};
  RenderSettings settings;  // no indirect-light method: direct light only
  settings.width = 64;
  settings.height = 64;
  const Scene scene = builtin_cornell_box();
  Renderer renderer(*device, scene, settings);
  return renderer.render_frame(0);
}

TEST(OpenclRender, CornellBoxMatchesHostExecutionOfTheSameKernels) {
  Scene scene = builtin_cornell_box();
  FrameImage image = render_direct_cornell_64();
  const ImageLayer* direct = image.find("direct");
  ASSERT_NE(direct, nullptr);
  ASSERT_TRUE(test::all_finite(direct->rgb));

  std::vector<float> host = rgb_of(test::render_direct_on_host(scene, 64, 64, 1));
  test::ImageDifference d = test::compare_rgb(direct->rgb, host);
  EXPECT_GT(d.mean_value, 1e-3) << "image is black";
  EXPECT_LT(d.mean_relative, 1e-4);
  std::printf("OpenCL vs host: mean relative difference %.3g, max absolute %.3g, mean %.4g\n", d.mean_relative,
              d.max_absolute, d.mean_value);
}

TEST(OpenclRender, CornellBoxWallsHaveTheirColours) {
  FrameImage image = render_direct_cornell_64();
  const ImageLayer* combined = image.find("");
  ASSERT_NE(combined, nullptr);
  auto pixel = [&](int x, int y, int c) { return combined->rgb[3 * (y * 64 + x) + c]; };
  // The light is warm, so colours are judged against the white back wall: the left wall is far
  // redder than it, the right wall far greener; the floor in front of the tall block is lit.
  auto ratio = [&](int x, int y, int a, int b) { return pixel(x, y, a) / pixel(x, y, b); };
  const float back_red_to_green = ratio(32, 24, 0, 1);
  EXPECT_GT(ratio(4, 32, 0, 1), 3.0f * back_red_to_green);
  EXPECT_GT(ratio(59, 32, 1, 0), 2.0f / back_red_to_green);
  EXPECT_GT(pixel(10, 61, 0), 0.0f);
}

// A scene without mirrors keeps one shading point a pixel whatever --mirror-depth says (the
// frame's largest buffers); one with mirrors keeps mirror_depth + 1, and its mirrors show the
// coloured walls where depth 0 shades the mirrors themselves (black: no diffuse part).
TEST(OpenclRender, ShadingPointsAreKeptForTheMirrorsTheSceneHas) {
  std::unique_ptr<Device> device = test::open_first_device("opencl");
  ASSERT_NE(device, nullptr);
  RenderSettings settings;
  settings.width = settings.height = 32;
  settings.mirror_depth = 2;
  const uint64_t record_bytes = 32 * 32 * sizeof(float2);
  const Scene plain = builtin_cornell_box();
  {
    Renderer renderer(*device, plain, settings);
    EXPECT_EQ(renderer.mirror_depth(), 0);
    EXPECT_EQ(renderer.buffers()[BufferSlot::shade_hit].bytes(), record_bytes);
  }
  Scene mirrored = plain;
  MaterialDesc& white = mirrored.materials.at(0);  // floor, ceiling, back wall and blocks
  ASSERT_EQ(white.name, "white");
  white.diffuse = Float3{0, 0, 0};
  white.mirror = Float3{0.9f, 0.9f, 0.9f};
  double means[2] = {0, 0};
  for (int depth : {0, 2}) {
    settings.mirror_depth = depth;
    Renderer renderer(*device, mirrored, settings);
    EXPECT_EQ(renderer.mirror_depth(), depth);
    EXPECT_EQ(renderer.buffers()[BufferSlot::shade_hit].bytes(), uint64_t(depth + 1) * record_bytes);
    const FrameImage image = renderer.render_frame(0);
    const ImageLayer* direct = image.find("direct");
    ASSERT_NE(direct, nullptr);
    for (float v : direct->rgb) means[depth / 2] += v;
  }
  EXPECT_GT(means[1], 1.2 * means[0]) << "the mirror reflected nothing at depth 2";
}

}  // namespace
}  // namespace pm

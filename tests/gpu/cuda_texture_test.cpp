// Textures and alpha masks on CUDA against OpenCL: the closed room with checkered white surfaces
// and a half-masked panel under its light renders alike on both backends, direct light (the
// camera pass's lookups and the mask in its shadow rays) and photon-mapped indirect light (the
// lookups at photon hits and shading points). Skipped where no CUDA device exists.
#include <gtest/gtest.h>

#include "render/renderer.h"
#include "support/device_checks.h"
#include "support/image_stats.h"
#include "support/render_settings.h"
#include "support/room_scenes.h"

namespace pm {
namespace {

// A width x height RGBA image as a texture of the scene, sampled with `wrap`.
int add_texture(Scene& s, int width, int height, uint8_t (*texel)(int x, int y, int channel), TextureWrap wrap) {
  TextureImage image;
  image.source = "test";
  image.width = width;
  image.height = height;
  image.file_channels = 4;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 4; ++c) image.rgba.push_back(texel(x, y, c));
  s.images.push_back(image);
  s.textures.push_back(TextureRef{uint32_t(s.images.size() - 1), wrap, wrap});
  return int(s.textures.size() - 1);
}

Scene textured_room() {
  Scene s = test::closed_room();
  for (size_t q = 0; q < s.triangle_count() / 2; ++q)
    s.triangle_uvs.insert(s.triangle_uvs.end(), {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}});
  s.materials[0].diffuse = {1, 1, 1};
  s.materials[0].base_color_texture = add_texture(
      s, 32, 32, [](int x, int y, int c) { return uint8_t(c == 3 ? 255 : ((x / 8 + y / 8) % 2 ? 230 : 70)); },
      TextureWrap::repeat);
  MaterialDesc panel = test::diffuse_material("panel", {0.5f, 0.5f, 0.5f});
  panel.alpha_mask = true;
  panel.alpha_texture =
      add_texture(s, 64, 1, [](int x, int, int c) { return uint8_t(c < 3 || x >= 32 ? 255 : 0); }, TextureWrap::clamp_to_edge);
  s.materials.push_back(panel);
  s.triangle_uvs.resize(3 * s.triangle_count());
  test::add_quad(s, {1.0f, 1.6f, 1.5f}, {3.0f, 1.6f, 1.5f}, {3.0f, 1.6f, 3.5f}, {1.0f, 1.6f, 3.5f},
                 uint32_t(s.materials.size() - 1));
  s.triangle_uvs.insert(s.triangle_uvs.end(), {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}});
  return s;
}

TEST(CudaTextures, CheckeredRoomWithAMaskedPanelMatchesOpencl) {
  std::unique_ptr<Device> cuda = test::open_first_device("cuda");
  if (!cuda) GTEST_SKIP() << "no CUDA device on this machine";
  std::unique_ptr<Device> opencl = test::open_opencl_preferring_gpu();
  ASSERT_NE(opencl, nullptr);
  const Scene scene = textured_room();
  RenderSettings settings = test::photon_render_settings(PhotonSettings{});
  settings.width = 128;
  settings.height = 96;
  Renderer cuda_renderer(*cuda, scene, settings);
  Renderer opencl_renderer(*opencl, scene, settings);
  const FrameImage a = cuda_renderer.render_frame(0), b = opencl_renderer.render_frame(0);
  const test::ImageDifference direct = test::compare_rgb(a.find("direct")->rgb, b.find("direct")->rgb);
  const double mean_a = test::mean(a.find("indirect")->rgb), mean_b = test::mean(b.find("indirect")->rgb);
  std::printf("textured room: direct mean relative difference %.3g; indirect means %.6g (CUDA) vs %.6g (OpenCL)\n",
              direct.mean_relative, mean_a, mean_b);
  // As for the untextured Cornell box (backend_equivalence_test.cpp): only compiler rounding
  // differs, and it sends an occasional photon another way.
  EXPECT_GT(direct.mean_value, 1e-3);
  EXPECT_LT(direct.mean_relative, 1e-3);
  EXPECT_NEAR(mean_a / mean_b, 1.0, 0.01);
}

}  // namespace
}  // namespace pm

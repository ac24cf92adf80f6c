// PNG previews: the tone map against the sRGB definition, the encoded file decoded back with
// stb_image (a separate decoder), and the atomic write leaving no temporary.
#include <gtest/gtest.h>
#include <stb_image.h>

#include <cmath>
#include <filesystem>
#include <memory>

#include "render/errors.h"
#include "render/preview_png.h"
#include "support/paths.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

TEST(PreviewPng, ToneMapIsClampedSrgb) {
  EXPECT_EQ(preview_tone_map(-3.0f), 0);
  EXPECT_EQ(preview_tone_map(0.0f), 0);
  EXPECT_EQ(preview_tone_map(1.0f), 255);
  EXPECT_EQ(preview_tone_map(65504.0f), 255);
  // IEC 61966-2-1 by hand: 0.5 -> 1.055 * 0.5^(1/2.4) - 0.055 = 0.73536 -> 187.5 -> 188;
  // 0.002 is on the linear segment: 12.92 * 0.002 * 255 = 6.59 -> 7.
  EXPECT_EQ(preview_tone_map(0.5f), 188);
  EXPECT_EQ(preview_tone_map(0.002f), 7);
  EXPECT_EQ(preview_tone_map(0.18f), 118);  // 1.055 * 0.18^(1/2.4) - 0.055 = 0.46135 -> 117.6
}

TEST(PreviewPng, DecodesToTheToneMappedCombinedLayer) {
  const fs::path dir = test::process_temp_dir() / "preview_png";
  fs::remove_all(dir);
  FrameImage image;
  image.width = 3;
  image.height = 2;
  image.layers.push_back({"direct", std::vector<float>(18, 5.0f)});
  image.layers.push_back({"", {0, 0.5f, 1, 2, 0.18f, 0.002f, 0, 0, 0, 1, 1, 1, 0.25f, 0.5f, 0.75f, -1, 3, 0.01f}});
  const std::string path = (dir / "sub" / "p.png").string();
  write_preview_png(path, image);

  int w = 0, h = 0, channels = 0;
  std::unique_ptr<unsigned char, void (*)(void*)> pixels(stbi_load(path.c_str(), &w, &h, &channels, 3), stbi_image_free);
  ASSERT_TRUE(pixels) << stbi_failure_reason();
  EXPECT_EQ(w, 3);
  EXPECT_EQ(h, 2);
  EXPECT_EQ(channels, 3);
  for (size_t i = 0; i < 18; ++i) EXPECT_EQ(pixels.get()[i], preview_tone_map(image.layers[1].rgb[i])) << i;
  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir / "sub")) files += entry.is_regular_file();
  EXPECT_EQ(files, 1u);  // no temporary left beside it
  fs::remove_all(dir);
}

TEST(PreviewPng, AnImageWithoutCombinedLayerIsRefused) {
  FrameImage image;
  image.width = 1;
  image.height = 1;
  image.layers.push_back({"direct", {1, 1, 1}});
  EXPECT_THROW(write_preview_png((test::process_temp_dir() / "none.png").string(), image), DeviceError);
}

}  // namespace
}  // namespace pm

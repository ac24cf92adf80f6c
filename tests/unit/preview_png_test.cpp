// PNG previews: the tone map against the sRGB definition, the encoded file decoded back with
// stb_image (a separate decoder), the exposure recorded in its text chunks, and the atomic write
// leaving no temporary.
#include <gtest/gtest.h>
#include <stb_image.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "render/errors.h"
#include "render/preview_exposure.h"
#include "render/preview_png.h"
#include "support/paths.h"
#include "support/png_text.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

TEST(PreviewPng, ToneMapIsClampedSrgb) {
  EXPECT_EQ(preview_tone_map(-3.0f, 1.0f), 0);
  EXPECT_EQ(preview_tone_map(0.0f, 1.0f), 0);
  EXPECT_EQ(preview_tone_map(1.0f, 1.0f), 255);
  EXPECT_EQ(preview_tone_map(65504.0f, 1.0f), 255);
  // IEC 61966-2-1 by hand: 0.5 -> 1.055 * 0.5^(1/2.4) - 0.055 = 0.73536 -> 187.5 -> 188;
  // 0.002 is on the linear segment: 12.92 * 0.002 * 255 = 6.59 -> 7.
  EXPECT_EQ(preview_tone_map(0.5f, 1.0f), 188);
  EXPECT_EQ(preview_tone_map(0.002f, 1.0f), 7);
  EXPECT_EQ(preview_tone_map(0.18f, 1.0f), 118);  // 1.055 * 0.18^(1/2.4) - 0.055 = 0.46135 -> 117.6
}

TEST(PreviewPng, ToneMapScalesBeforeClamping) {
  EXPECT_EQ(preview_tone_map(0.125f, 4.0f), 188);  // 0.5 after two stops
  EXPECT_EQ(preview_tone_map(0.5f, 2.0f), 255);
  EXPECT_EQ(preview_tone_map(2.0f, 0.25f), 188);
}

// The decoded 8-bit RGB of a PNG.
std::vector<unsigned char> decode(const std::string& path, int width, int height) {
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<unsigned char, void (*)(void*)> pixels(stbi_load(path.c_str(), &w, &h, &channels, 3), stbi_image_free);
  if (!pixels) {
    ADD_FAILURE() << stbi_failure_reason();
    return {};
  }
  EXPECT_EQ(w, width);
  EXPECT_EQ(h, height);
  return std::vector<unsigned char>(pixels.get(), pixels.get() + size_t(w) * size_t(h) * 3);
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
  EXPECT_EQ(write_preview_png(path, image, 0.0), 0.0);

  const std::vector<unsigned char> pixels = decode(path, 3, 2);
  ASSERT_EQ(pixels.size(), 18u);
  for (size_t i = 0; i < 18; ++i) EXPECT_EQ(pixels[i], preview_tone_map(image.layers[1].rgb[i], 1.0f)) << i;
  const auto text = test::png_text(path);
  EXPECT_EQ(text.at(kPreviewExposureKeyword), "0");
  EXPECT_EQ(text.at(kPreviewExposureSourceKeyword), "--exposure");
  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir / "sub")) files += entry.is_regular_file();
  EXPECT_EQ(files, 1u);  // no temporary left beside it
  fs::remove_all(dir);
}

TEST(PreviewPng, WithoutAnExposureTheAutomaticOneIsUsedAndRecorded) {
  const fs::path dir = test::process_temp_dir() / "preview_png_auto";
  fs::remove_all(dir);
  FrameImage image;  // a dim room: at exposure 1 every pixel would be 0..12 of 255
  image.width = 4;
  image.height = 1;
  image.layers.push_back({"", {0.001f, 0.001f, 0.001f, 0.002f, 0.002f, 0.002f, 0.003f, 0.003f, 0.003f, 0.004f, 0.004f, 0.004f}});
  const std::string path = (dir / "auto.png").string();
  const double ev = write_preview_png(path, image);
  EXPECT_EQ(ev, automatic_exposure_ev(image.layers[0].rgb));
  EXPECT_GT(ev, 7.0);  // 0.004 to white: log2(250) = 7.97 stops
  const std::vector<unsigned char> pixels = decode(path, 4, 1);
  ASSERT_EQ(pixels.size(), 12u);
  EXPECT_GE(pixels[9], 254);  // the brightest pixel near white, the others graded below it
  EXPECT_LT(pixels[0], pixels[3]);
  EXPECT_LT(pixels[3], pixels[6]);
  const auto text = test::png_text(path);
  EXPECT_EQ(std::stod(text.at(kPreviewExposureKeyword)), ev);  // exactly: --exposure with it reproduces the file
  EXPECT_EQ(text.at(kPreviewExposureSourceKeyword).rfind("automatic", 0), 0u);
  fs::remove_all(dir);
}

TEST(PreviewPng, AnExposureOutOfRangeIsRefused) {
  FrameImage image;
  image.width = 1;
  image.height = 1;
  image.layers.push_back({"", {1, 1, 1}});
  const std::string path = (test::process_temp_dir() / "out_of_range.png").string();
  EXPECT_THROW(write_preview_png(path, image, 33.0), DeviceError);
  EXPECT_THROW(write_preview_png(path, image, std::nan("")), DeviceError);
  EXPECT_FALSE(fs::exists(path));
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

// The automatic preview exposure: a dim image is brightened, a bright one darkened, a black one
// left at a finite EV 0, and the percentile and its fallbacks are the documented ones.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "render/preview_exposure.h"

namespace pm {
namespace {

std::vector<float> grey_image(size_t pixels, float value) { return std::vector<float>(pixels * 3, value); }

TEST(PreviewExposure, ADimImageGetsAPositiveEvThatShowsItsPercentileAsWhite) {
  // Grey 1/16 everywhere: luminance 0.0625, shown as white at 2^4.
  EXPECT_DOUBLE_EQ(automatic_exposure_ev(grey_image(100, 0.0625f)), 4.0);
  EXPECT_GT(automatic_exposure_ev(grey_image(100, 0.003f)), 0.0);
}

TEST(PreviewExposure, ABrightImageGetsANegativeEv) {
  EXPECT_DOUBLE_EQ(automatic_exposure_ev(grey_image(100, 8.0f)), -3.0);
  EXPECT_LT(automatic_exposure_ev(grey_image(10, 250.0f)), 0.0);
}

TEST(PreviewExposure, ABlackOrEmptyImageGetsAFiniteEvZero) {
  EXPECT_EQ(automatic_exposure_ev(grey_image(64, 0.0f)), 0.0);
  EXPECT_EQ(automatic_exposure_ev({}), 0.0);
  EXPECT_EQ(automatic_exposure_ev(grey_image(64, -1.0f)), 0.0);  // negatives count as black
}

TEST(PreviewExposure, TheBrightestOnePercentMayClip) {
  // Luminances 1/64 ... 100/64 (grey pixels 1..100 / 64): the 99th percentile by nearest rank is
  // 99/64, so a light of 100/64 clips and everything else keeps its gradation.
  std::vector<float> rgb;
  for (int i = 1; i <= 100; ++i) rgb.insert(rgb.end(), 3, float(i) / 64.0f);
  EXPECT_DOUBLE_EQ(automatic_exposure_ev(rgb), std::round(-std::log2(99.0 / 64.0) * 100.0) / 100.0);
  // One pixel of a thousand 1000 times brighter changes nothing.
  std::vector<float> lamp = grey_image(1000, 0.25f);
  lamp[0] = lamp[1] = lamp[2] = 250.0f;
  EXPECT_DOUBLE_EQ(automatic_exposure_ev(lamp), 2.0);
}

TEST(PreviewExposure, LuminanceWeighsTheChannelsAsRec709) {
  // Pure green 0.5 has luminance 0.7152 * 0.5 = 0.3576: EV = -log2(0.3576) = 1.4836 -> 1.48.
  std::vector<float> green(300, 0.0f);
  for (size_t i = 1; i < green.size(); i += 3) green[i] = 0.5f;
  EXPECT_DOUBLE_EQ(automatic_exposure_ev(green), 1.48);
}

TEST(PreviewExposure, AnImageBlackButForAFewPixelsIsExposedForItsBrightestPixel) {
  std::vector<float> rgb = grey_image(1000, 0.0f);
  rgb[30] = rgb[31] = rgb[32] = 0.5f;  // one lit pixel of 1000: the 99th percentile is black
  EXPECT_DOUBLE_EQ(automatic_exposure_ev(rgb), 1.0);
}

TEST(PreviewExposure, NonFiniteValuesCountAsBlackAndExtremesAreClamped) {
  std::vector<float> rgb = grey_image(10, 0.5f);
  rgb[0] = std::numeric_limits<float>::quiet_NaN();
  rgb[4] = std::numeric_limits<float>::infinity();
  EXPECT_DOUBLE_EQ(automatic_exposure_ev(rgb), 1.0);
  EXPECT_EQ(automatic_exposure_ev(grey_image(10, 1e-30f)), kMaxExposureStops);
  EXPECT_EQ(automatic_exposure_ev(grey_image(10, 3e38f)), -kMaxExposureStops);
}

TEST(PreviewExposure, TheEvIsRoundedToAHundredthOfAStop) {
  const double ev = automatic_exposure_ev(grey_image(10, 0.3f));
  EXPECT_DOUBLE_EQ(ev * 100.0, std::round(ev * 100.0));
  EXPECT_NEAR(ev, -std::log2(0.3), 0.005);
}

}  // namespace
}  // namespace pm

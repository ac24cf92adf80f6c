// FLIP (render/flip.h) against the properties and values its papers state: zero for identical
// images, values in [0, 1], the largest colour distance (green against blue) mapping to exactly 1,
// the p_c -> p_t knee of the error remapping, monotonic growth with a colour shift, fireflies
// caught by the point detector, detail hidden by viewing distance, and HDR-FLIP's exposure range,
// tone mapper and invariance to a common exposure.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "render/flip.h"

namespace pm::flip {
namespace {

constexpr double kPpd = 67.0;

std::vector<float> constant_image(int w, int h, float r, float g, float b) {
  std::vector<float> image(size_t(w) * h * 3);
  for (size_t i = 0; i < image.size(); i += 3) {
    image[i] = r;
    image[i + 1] = g;
    image[i + 2] = b;
  }
  return image;
}

std::vector<float> random_image(int w, int h, float scale, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, scale);
  std::vector<float> image(size_t(w) * h * 3);
  for (float& v : image) v = u(rng);
  return image;
}

double mean(const std::vector<float>& v) {
  double s = 0;
  for (float x : v) s += x;
  return s / double(v.size());
}

TEST(FlipViewing, DefaultIsTheMonitorOfThePaper) {
  // 0.7 m from a 0.7 m wide 3840-pixel monitor: about 67 pixels per degree.
  EXPECT_NEAR(default_pixels_per_degree(), 67.02, 0.01);
  EXPECT_NEAR(pixels_per_degree(1.4, 3840, 0.7), 2 * default_pixels_per_degree(), 1e-9);
}

TEST(FlipColor, ConversionsMatchCieValues) {
  // Reference white: linear RGB (1,1,1) is Y = 1, YyCxCz (100, 0, 0), L*a*b* (100, 0, 0).
  Color w = linear_rgb_to_xyz({1, 1, 1});
  EXPECT_NEAR(w.y, 1.0f, 1e-5f);
  Color ycc = xyz_to_ycxcz(w);
  EXPECT_NEAR(ycc.x, 100.0f, 1e-3f);
  EXPECT_NEAR(ycc.y, 0.0f, 1e-3f);
  EXPECT_NEAR(ycc.z, 0.0f, 1e-3f);
  Color lab = xyz_to_lab(w);
  EXPECT_NEAR(lab.x, 100.0f, 1e-3f);
  // 18 % grey is L* = 49.5; the sRGB primaries' L*a*b* (D65) are the textbook values.
  EXPECT_NEAR(xyz_to_lab(linear_rgb_to_xyz({0.18f, 0.18f, 0.18f})).x, 49.50f, 0.02f);
  Color green = xyz_to_lab(linear_rgb_to_xyz({0, 1, 0}));
  EXPECT_NEAR(green.x, 87.74f, 0.02f);
  EXPECT_NEAR(green.y, -86.18f, 0.05f);
  EXPECT_NEAR(green.z, 83.18f, 0.05f);
  Color blue = xyz_to_lab(linear_rgb_to_xyz({0, 0, 1}));
  EXPECT_NEAR(blue.x, 32.30f, 0.02f);
  EXPECT_NEAR(blue.y, 79.19f, 0.05f);
  EXPECT_NEAR(blue.z, -107.86f, 0.05f);
  // Round trips.
  Color rgb{0.2f, 0.5f, 0.9f};
  Color back = xyz_to_linear_rgb(ycxcz_to_xyz(xyz_to_ycxcz(linear_rgb_to_xyz(rgb))));
  EXPECT_NEAR(back.x, rgb.x, 1e-5f);
  EXPECT_NEAR(back.y, rgb.y, 1e-5f);
  EXPECT_NEAR(back.z, rgb.z, 1e-5f);
}

TEST(FlipColor, HuntAdjustmentAndHyab) {
  Color h = hunt_adjust({50, 20, -10});
  EXPECT_FLOAT_EQ(h.x, 50);
  EXPECT_FLOAT_EQ(h.y, 10);
  EXPECT_FLOAT_EQ(h.z, -5);
  // HyAB: city-block in lightness plus Euclidean in the chroma plane.
  EXPECT_FLOAT_EQ(hyab({50, 0, 0}, {40, 3, 4}), 15.0f);
  EXPECT_FLOAT_EQ(hyab({40, 3, 4}, {50, 0, 0}), 15.0f);
  // c_max: Hunt-adjusted green and blue, from the primaries' L*a*b* above.
  const double dl = 87.74 - 32.30, da = 0.8774 * -86.18 - 0.3230 * 79.19, db = 0.8774 * 83.18 - 0.3230 * -107.86;
  EXPECT_NEAR(max_color_distance(), dl + std::sqrt(da * da + db * db), 0.1);
}

TEST(FlipColor, RemappingHasThePapersKneeAndEnds) {
  const float cmax = max_color_distance();
  EXPECT_FLOAT_EQ(remap_color_error(0.0f), 0.0f);
  EXPECT_NEAR(remap_color_error(cmax), 1.0f, 1e-5f);
  // (p_c c_max^q_c)^(1/q_c) = p_c^(1/q_c) c_max maps to p_t = 0.95.
  EXPECT_NEAR(remap_color_error(std::pow(0.4f, 1.0f / 0.7f) * cmax), 0.95f, 1e-4f);
  float last = 0;
  for (float d = 1; d <= cmax; d += 1) {
    float e = remap_color_error(d);
    EXPECT_GT(e, last);
    last = e;
  }
  EXPECT_LE(remap_color_error(10 * cmax), 1.0f);
}

TEST(FlipColor, CombinationAndFeatureError) {
  EXPECT_FLOAT_EQ(combine_errors(0.25f, 0.0f), 0.25f);
  EXPECT_FLOAT_EQ(combine_errors(0.25f, 0.5f), 0.5f);  // 0.25^(1 - 0.5)
  EXPECT_FLOAT_EQ(combine_errors(0.25f, 1.0f), 1.0f);
  EXPECT_FLOAT_EQ(feature_error(0.3f, 0.3f, 0.1f, 0.1f), 0.0f);
  // (max(|de|, |dp|) / sqrt 2)^(1/2)
  EXPECT_NEAR(feature_error(0.5f, 0.0f, 0.1f, 0.2f), std::sqrt(0.5f / std::sqrt(2.0f)), 1e-6f);
}

double kernel_sum(const SeparableKernel& k, int sign) {
  double total = 0;
  for (const SeparableTerm& t : k)
    for (float x : t.x_taps)
      for (float y : t.y_taps) {
        double v = t.weight * double(x) * y;
        if (sign == 0 || (sign > 0 && v > 0) || (sign < 0 && v < 0)) total += v;
      }
  return total;
}

TEST(FlipFilters, CsfKernelsAreNormalisedWithThePapersRadius) {
  for (int c = 0; c < 3; ++c) {
    SeparableKernel k = csf_kernel(c, default_pixels_per_degree());
    EXPECT_NEAR(kernel_sum(k, 0), 1.0, 1e-5) << c;
    // r = ceil(3 sqrt(0.04 / (2 pi^2)) ppd) = ceil(9.05) = 10 at 67.02 px/degree.
    EXPECT_EQ(k[0].x_taps.size(), 21u) << c;
    EXPECT_FLOAT_EQ(k[0].x_taps.front(), k[0].x_taps.back());
  }
  EXPECT_EQ(csf_kernel(2, default_pixels_per_degree()).size(), 2u);  // blue-yellow: two Gaussians
  // The achromatic filter is narrower than the blue-yellow one (spatial acuity for luminance).
  auto centre = [](const SeparableKernel& k) {
    double c = 0;
    for (const SeparableTerm& t : k) c += t.weight * double(t.x_taps[10]) * t.y_taps[10];
    return c;
  };
  EXPECT_GT(centre(csf_kernel(0, 67.02)), 2 * centre(csf_kernel(2, 67.02)));
}

TEST(FlipFilters, FeatureKernelsHaveUnitPositiveAndNegativeWeights) {
  for (bool along_x : {true, false}) {
    for (const SeparableKernel& k : {edge_kernel(kPpd, along_x), point_kernel(kPpd, along_x)}) {
      EXPECT_NEAR(kernel_sum(k, +1), 1.0, 1e-5);
      EXPECT_NEAR(kernel_sum(k, -1), -1.0, 1e-5);
      // sigma = 0.5 * 0.082 * 67 = 2.75 px, radius ceil(3 sigma) = 9.
      EXPECT_EQ(k[0].x_taps.size(), 19u);
    }
  }
  // A unit step in luminance is an edge of magnitude 1 (the positive taps sum to 1).
  std::vector<float> step(32 * 32);
  for (int y = 0; y < 32; ++y)
    for (int x = 16; x < 32; ++x) step[size_t(y) * 32 + x] = 1.0f;
  EXPECT_NEAR(std::fabs(convolve(step, 32, 32, edge_kernel(kPpd, true))[16 * 32 + 16]), 1.0f, 1e-5f);
  EXPECT_NEAR(convolve(step, 32, 32, edge_kernel(kPpd, false))[16 * 32 + 16], 0.0f, 1e-6f);
  // A constant image has no edges or points.
  std::vector<float> flat(32 * 32, 0.6f);
  for (float v : convolve(flat, 32, 32, point_kernel(kPpd, true))) EXPECT_NEAR(v, 0.0f, 1e-6f);
  for (float v : convolve(flat, 32, 32, edge_kernel(kPpd, false))) EXPECT_NEAR(v, 0.0f, 1e-6f);
}

TEST(LdrFlip, IdenticalImagesGiveZero) {
  std::vector<float> a = random_image(40, 30, 1.0f, 1);
  for (float e : ldr_flip(a, a, 40, 30, kPpd)) EXPECT_EQ(e, 0.0f);
}

TEST(LdrFlip, ErrorsLieInZeroToOne) {
  for (uint32_t seed = 0; seed < 4; ++seed) {
    std::vector<float> a = random_image(33, 21, 1.0f, 10 + seed), b = random_image(33, 21, 1.0f, 20 + seed);
    for (float e : ldr_flip(a, b, 33, 21, kPpd)) {
      EXPECT_GE(e, 0.0f);
      EXPECT_LE(e, 1.0f);
    }
  }
  // Out-of-range input is clamped first, so it cannot escape [0, 1] either.
  std::vector<float> hot = random_image(16, 16, 1e6f, 3), cold = constant_image(16, 16, -5, -5, -5);
  for (float e : ldr_flip(hot, cold, 16, 16, kPpd)) EXPECT_LE(e, 1.0f);
}

TEST(LdrFlip, GreenAgainstBlueIsTheLargestErrorOne) {
  std::vector<float> g = constant_image(24, 24, 0, 1, 0), b = constant_image(24, 24, 0, 0, 1);
  for (float e : ldr_flip(g, b, 24, 24, kPpd)) EXPECT_NEAR(e, 1.0f, 1e-4f);
  // Black against white is large but below the maximum.
  std::vector<float> black = constant_image(24, 24, 0, 0, 0), white = constant_image(24, 24, 1, 1, 1);
  const double bw = mean(ldr_flip(black, white, 24, 24, kPpd));
  EXPECT_GT(bw, 0.9);
  EXPECT_LT(bw, 0.999);
}

TEST(LdrFlip, GrowsMonotonicallyWithAColourShift) {
  std::vector<float> ref = constant_image(20, 20, 0.4f, 0.4f, 0.4f);
  for (int channel = 0; channel < 3; ++channel) {
    double last = 0;
    for (float shift = 0.02f; shift <= 0.5f; shift += 0.04f) {
      std::vector<float> test = ref;
      for (size_t i = channel; i < test.size(); i += 3) test[i] += shift;
      const double e = mean(ldr_flip(ref, test, 20, 20, kPpd));
      EXPECT_GT(e, last) << "channel " << channel << " shift " << shift;
      last = e;
    }
  }
}

TEST(LdrFlip, PointDetectorCatchesAFirefly) {
  const int n = 31;
  std::vector<float> ref = constant_image(n, n, 0.2f, 0.2f, 0.2f), test = ref;
  const size_t centre = size_t(n / 2) * n + n / 2;
  for (int k = 0; k < 3; ++k) test[3 * centre + k] = 1.0f;
  const std::vector<float> e = ldr_flip(ref, test, n, n, kPpd);
  // The same energy spread over the whole image is nearly invisible; concentrated in one pixel it
  // stands out, and the point detector raises it above what the CSF-filtered colour alone gives.
  std::vector<float> spread = ref;
  for (float& v : spread) v += 0.8f / float(n * n);
  EXPECT_GT(e[centre], 0.3f);
  EXPECT_GT(e[centre], 20 * mean(ldr_flip(ref, spread, n, n, kPpd)));
  EXPECT_LT(e[0], 0.05f);  // far from the firefly
  std::vector<float> luminance(size_t(n) * n, 0.2f), lit = luminance;
  lit[centre] = 1.0f;
  const float point = std::hypot(convolve(lit, n, n, point_kernel(kPpd, true))[centre],
                                 convolve(lit, n, n, point_kernel(kPpd, false))[centre]);
  EXPECT_GT(point, 0.0f);
  EXPECT_GT(feature_error(0, 0, point, 0), 0.1f);
}

TEST(LdrFlip, FineDetailFadesWithViewingDistance) {
  // A one-pixel checkerboard against the grey of the same linear mean: the farther the observer
  // (more pixels per degree), the less of the difference is visible.
  const int n = 48;
  std::vector<float> checker(size_t(n) * n * 3), grey = constant_image(n, n, 0.5f, 0.5f, 0.5f);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      for (int k = 0; k < 3; ++k) checker[3 * (size_t(y) * n + x) + k] = ((x + y) % 2) ? 1.0f : 0.0f;
  const double near = mean(ldr_flip(grey, checker, n, n, 10));
  const double mid = mean(ldr_flip(grey, checker, n, n, 40));
  const double far = mean(ldr_flip(grey, checker, n, n, 120));
  EXPECT_GT(near, mid);
  EXPECT_GT(mid, far);
}

TEST(HdrFlip, ToneMapperIsTheAcesFit) {
  EXPECT_EQ(tone_map(0.0f), 0.0f);
  EXPECT_EQ(tone_map(-3.0f), 0.0f);
  EXPECT_EQ(tone_map(1e9f), 1.0f);  // the fit tends to 2.51 / 2.43 > 1, clamped
  // t(1) = (0.36 * 2.51 + 0.6 * 0.03) / (0.36 * 2.43 + 0.6 * 0.59 + 0.14)
  EXPECT_NEAR(tone_map(1.0f), (0.9036 + 0.018) / (0.8748 + 0.354 + 0.14), 1e-6);
  // Increasing until it reaches white (the fit crosses 1 near x = 12 and is clamped there).
  float last = 0;
  for (float x = 0.01f; x < 100; x *= 1.3f) {
    const float t = tone_map(x);
    if (last < 1.0f) {
      EXPECT_GT(t, last) << x;
    } else {
      EXPECT_EQ(t, 1.0f) << x;
    }
    last = t;
    if (t < 0.99f) {
      EXPECT_NEAR(inverse_tone_map(t), x, 1e-3f * x);
    }
  }
}

TEST(HdrFlip, ExposureRangeSpansMaximumToMedian) {
  // Luminance of grey g is g: pixels 0.5 (x3), 2 (x1), 8 (x1) -> max 8, median 0.5.
  std::vector<float> rgb;
  for (float g : {0.5f, 8.0f, 0.5f, 2.0f, 0.5f}) rgb.insert(rgb.end(), {g, g, g});
  const ExposureRange r = exposure_range(rgb);
  const double x85 = inverse_tone_map(0.85f);
  EXPECT_NEAR(tone_map(float(x85)), 0.85f, 1e-6f);
  EXPECT_NEAR(r.start, std::log2(x85 / 8.0), 1e-6);
  EXPECT_NEAR(r.stop, std::log2(x85 / 0.5), 1e-6);
  EXPECT_EQ(r.count, 4);  // ceil(log2(8 / 0.5)) = 4
  // Mostly black: the median of the lit pixels.
  std::vector<float> dark(30, 0.0f);
  dark.insert(dark.end(), {1, 1, 1, 4, 4, 4, 2, 2, 2});
  EXPECT_NEAR(exposure_range(dark).stop, std::log2(x85 / 2.0), 1e-6);
  // All black: one exposure, 0.
  const ExposureRange black = exposure_range(std::vector<float>(12, 0.0f));
  EXPECT_EQ(black.start, 0.0);
  EXPECT_EQ(black.stop, 0.0);
  EXPECT_EQ(black.count, 2);
}

TEST(HdrFlip, IdenticalZeroBoundedAndInvariantToACommonExposure) {
  std::vector<float> a = random_image(40, 32, 20.0f, 5), b = random_image(40, 32, 20.0f, 6);
  EXPECT_EQ(hdr_flip(a, a, 40, 32, kPpd).mean, 0.0);
  const HdrFlipResult r = hdr_flip(a, b, 40, 32, kPpd);
  for (float e : r.error) {
    EXPECT_GE(e, 0.0f);
    EXPECT_LE(e, 1.0f);
  }
  // The exposures follow the reference, so scaling both images by 2^k changes nothing.
  std::vector<float> a4 = a, b4 = b;
  for (float& v : a4) v *= 4.0f;
  for (float& v : b4) v *= 4.0f;
  EXPECT_NEAR(hdr_flip(a4, b4, 40, 32, kPpd).mean, r.mean, 1e-5);
  // Every pixel takes the largest LDR-FLIP over the exposures.
  const double c = r.exposures.start;
  std::vector<float> ta(a.size()), tb(b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    ta[i] = tone_map(float(std::exp2(c)) * a[i]);
    tb[i] = tone_map(float(std::exp2(c)) * b[i]);
  }
  const std::vector<float> first = ldr_flip(ta, tb, 40, 32, kPpd);
  for (size_t i = 0; i < first.size(); ++i) EXPECT_GE(r.error[i], first[i]);
}

TEST(HdrFlip, GrowsWithAGlobalBrightnessError) {
  std::vector<float> ref = random_image(48, 48, 5.0f, 9);
  double last = 0;
  for (float scale : {1.01f, 1.02f, 1.05f, 1.1f, 1.3f, 2.0f}) {
    std::vector<float> test = ref;
    for (float& v : test) v *= scale;
    const double e = hdr_flip(ref, test, 48, 48, kPpd).mean;
    EXPECT_GT(e, last) << scale;
    last = e;
  }
}

// hdr_flip evaluates its exposures on several threads: the result must be, bit for bit, the
// maximum over the exposures taken one after the other.
TEST(HdrFlip, IsTheMaximumOfItsExposuresTakenInTurn) {
  const int w = 37, h = 23;  // odd sizes: kernels wider than the image reach both borders
  std::vector<float> ref = random_image(w, h, 1.0f, 3), test = random_image(w, h, 1.0f, 4);
  for (std::vector<float>* image : {&ref, &test})
    for (float& v : *image) v = std::exp2(12.0f * v - 6.0f);  // 12 stops: many exposures
  const HdrFlipResult r = hdr_flip(ref, test, w, h, kPpd);
  ASSERT_GE(r.exposures.count, 3) << "several exposures, so several threads can take part";
  std::vector<float> expected(size_t(w) * h, 0.0f), a(ref.size()), b(test.size());
  for (int k = 0; k < r.exposures.count; ++k) {
    const double c = r.exposures.start + k * (r.exposures.stop - r.exposures.start) / double(r.exposures.count - 1);
    const float scale = float(std::exp2(c));
    for (size_t i = 0; i < ref.size(); ++i) {
      a[i] = tone_map(scale * ref[i]);
      b[i] = tone_map(scale * test[i]);
    }
    const std::vector<float> e = ldr_flip(a, b, w, h, kPpd);
    for (size_t i = 0; i < e.size(); ++i) expected[i] = std::max(expected[i], e[i]);
  }
  ASSERT_EQ(r.error.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) ASSERT_EQ(r.error[i], expected[i]) << "pixel " << i;
}

// The convolution against its definition, a clamped-border sum per pixel, at sizes smaller and
// larger than the kernel.
TEST(FlipFilters, ConvolutionIsTheClampedBorderSum) {
  for (const auto& size : {std::pair<int, int>{5, 3}, std::pair<int, int>{41, 29}}) {
    const int w = size.first, h = size.second;
    std::vector<float> image(size_t(w) * h);
    for (size_t i = 0; i < image.size(); ++i) image[i] = float((i * 7919) % 101) / 100.0f;
    const SeparableKernel kernel = csf_kernel(2, kPpd);  // two terms
    const std::vector<float> out = convolve(image, w, h, kernel);
    for (int y = 0; y < h; y += 2)
      for (int x = 0; x < w; x += 3) {
        double sum = 0;
        for (const SeparableTerm& term : kernel) {
          const int rx = int(term.x_taps.size() / 2), ry = int(term.y_taps.size() / 2);
          for (int j = -ry; j <= ry; ++j)
            for (int i = -rx; i <= rx; ++i) {
              const int xx = std::min(std::max(x + i, 0), w - 1), yy = std::min(std::max(y + j, 0), h - 1);
              sum += double(term.weight) * term.x_taps[i + rx] * term.y_taps[j + ry] * image[size_t(yy) * w + xx];
            }
        }
        EXPECT_NEAR(out[size_t(y) * w + x], sum, 1e-5 * (1.0 + std::fabs(sum))) << x << "," << y;
      }
  }
}

TEST(HdrFlip, RefusesMismatchedBuffers) {
  std::vector<float> a(12), b(9);
  EXPECT_THROW(hdr_flip(a, b, 2, 2, kPpd), std::invalid_argument);
  EXPECT_THROW(ldr_flip(a, a, 0, 2, kPpd), std::invalid_argument);
}

}  // namespace
}  // namespace pm::flip

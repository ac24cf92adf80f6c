// Two images equal bit for bit, every layer: the check behind "chunks, farm tasks and resumed
// runs write the same pixels as one run"; and equal up to the order of a float sum.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "render/image.h"

namespace pm::test {

inline void expect_same_image(const FrameImage& a, const FrameImage& b, const std::string& what) {
  ASSERT_EQ(a.layers.size(), b.layers.size()) << what;
  for (size_t i = 0; i < a.layers.size(); ++i) {
    const ImageLayer* other = b.find(a.layers[i].name);
    ASSERT_NE(other, nullptr) << what;
    EXPECT_TRUE(a.layers[i].rgb == other->rgb) << what << ": layer '" << a.layers[i].name << "' differs";
  }
}

// The same passes summed in another order (several devices): the direct layers equal, the indirect
// layers within 1e-5 relative per pixel, and not black.
inline void expect_same_passes_in_another_order(const FrameImage& a, const FrameImage& b) {
  EXPECT_EQ(a.find("direct")->rgb, b.find("direct")->rgb);
  const std::vector<float>& x = a.find("indirect")->rgb;
  const std::vector<float>& y = b.find("indirect")->rgb;
  ASSERT_EQ(x.size(), y.size());
  double worst = 0, total = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    worst = std::max(worst, std::fabs(double(x[i]) - y[i]) / std::max(1e-6, std::fabs(double(x[i]))));
    total += x[i];
  }
  EXPECT_GT(total, 0.0);
  EXPECT_LT(worst, 1e-5) << "largest relative difference of a pixel";
}

}  // namespace pm::test

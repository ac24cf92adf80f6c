// Two images equal bit for bit, every layer: the check behind "chunks, farm tasks and resumed
// runs write the same pixels as one run".
#pragma once

#include <gtest/gtest.h>

#include <string>

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

}  // namespace pm::test

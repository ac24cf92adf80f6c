// Checks of a rendered image's extra layers against the hand-computed values of
// tests/support/layer_scene.h, for the backends' end-to-end tests.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "render/image.h"
#include "support/layer_scene.h"

namespace pm::test {

// Every pixel of a width x height render of layer_scene with every layer: albedo, normal and
// position within `tolerance` (absolute, their values are of order 1), depth within `tolerance`
// relative, ids exact.
inline void expect_layers_match_layer_scene(const FrameImage& image, int width, int height, int mirror_depth,
                                            float tolerance) {
  const ImageLayer* albedo = image.find("albedo");
  const DataLayer *normal = image.find_data("N"), *depth = image.find_data(""), *position = image.find_data("P");
  const DataLayer *object = image.find_data("object_id"), *material = image.find_data("material_id");
  ASSERT_TRUE(albedo && normal && depth && position && object && material);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      SCOPED_TRACE("pixel " + std::to_string(x) + ", " + std::to_string(y));
      const ExpectedLayers e = expected_layers(x, y, width, height, mirror_depth);
      const size_t i = size_t(y) * width + x;
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(albedo->rgb[3 * i + c], e.albedo[c], tolerance);
        EXPECT_NEAR(normal->values[3 * i + c], e.normal[c], tolerance);
        EXPECT_NEAR(position->values[3 * i + c], e.position[c], tolerance);
      }
      EXPECT_NEAR(depth->values[i], e.depth, tolerance * e.depth);
      EXPECT_EQ(object->values[i], e.object_id);
      EXPECT_EQ(material->values[i], e.material_id);
    }
}

}  // namespace pm::test

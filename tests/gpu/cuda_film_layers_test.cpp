// The film's extra layers on CUDA: the hand-computed albedo, normal, depth, position and ids of
// tests/support/layer_scene.h with direct light only and with the path tracer (both read the
// same camera pass), within CUDA's fast-math rounding; skipped without a CUDA device.
#include <gtest/gtest.h>

#include <memory>

#include "render/path/path_settings.h"
#include "render/renderer.h"
#include "support/device_checks.h"
#include "support/layer_checks.h"
#include "support/layer_scene.h"

namespace pm {
namespace {

constexpr int kWidth = 32, kHeight = 24;

TEST(CudaFilmLayers, LayersMatchTheHandComputedScene) {
  std::unique_ptr<Device> cuda = test::open_first_device("cuda");
  if (!cuda) GTEST_SKIP() << "no CUDA device on this machine";
  const Scene scene = test::layer_scene(kWidth, kHeight);
  auto path = std::make_shared<PathSettings>();
  path->samples = 4;
  for (std::shared_ptr<const MethodSettings> method : {std::shared_ptr<const MethodSettings>(),
                                                       std::shared_ptr<const MethodSettings>(path)}) {
    SCOPED_TRACE(method ? "path" : "direct light only");
    for (int mirror_depth : {0, 1}) {
      RenderSettings settings;
      settings.method = method;
      settings.mirror_depth = mirror_depth;
      settings.layers = parse_film_layers("all");
      Renderer renderer(*cuda, scene, settings);
      // --use_fast_math: divisions and square roots within a few ulps, hence 1e-4 rather than 1e-5.
      test::expect_layers_match_layer_scene(renderer.render_frame(0), kWidth, kHeight, mirror_depth, 1e-4f);
    }
  }
}

}  // namespace
}  // namespace pm

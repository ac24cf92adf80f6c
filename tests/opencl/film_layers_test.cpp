// The film's extra layers on the OpenCL backend: every method (direct light only, photon mapping
// with the pd, knn and radius estimators, the path tracer, radiosity) gives the hand-computed
// albedo, normal, depth, position and ids of tests/support/layer_scene.h, since all of them share
// the camera pass; asking for layers changes no colour layer; without them nothing is allocated.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "render/path/path_settings.h"
#include "render/renderer.h"
#include "support/device_checks.h"
#include "support/layer_checks.h"
#include "support/layer_scene.h"
#include "support/render_settings.h"

namespace pm {
namespace {

constexpr int kWidth = 16, kHeight = 12;

struct MethodCase {
  const char* name;
  std::shared_ptr<const MethodSettings> method;
};

std::vector<MethodCase> method_cases() {
  std::vector<MethodCase> cases = {{"direct light only", nullptr}};
  for (int estimator : {PM_ESTIMATOR_PD, PM_ESTIMATOR_KNN, PM_ESTIMATOR_RADIUS}) {
    auto photons = std::make_shared<PhotonSettings>();
    photons->photons = 4096;
    photons->estimator = estimator;
    cases.push_back({estimator == PM_ESTIMATOR_PD ? "photon pd" : estimator == PM_ESTIMATOR_KNN ? "photon knn" : "photon radius",
                     photons});
  }
  auto path = std::make_shared<PathSettings>();
  path->samples = 2;
  cases.push_back({"path", path});
  auto radiosity = std::make_shared<RadiositySettings>();
  radiosity->directions = 16;
  radiosity->max_edge = 4.0f;
  cases.push_back({"radiosity", radiosity});
  return cases;
}

void expect_layers_match_the_scene(const FrameImage& image, int mirror_depth) {
  test::expect_layers_match_layer_scene(image, kWidth, kHeight, mirror_depth, 1e-5f);
}

TEST(OpenclFilmLayers, EveryMethodGivesTheHandComputedLayers) {
  Device& device = test::shared_opencl_device();
  const Scene scene = test::layer_scene(kWidth, kHeight);
  for (const MethodCase& c : method_cases()) {
    SCOPED_TRACE(c.name);
    RenderSettings settings;
    settings.method = c.method;
    settings.layers = parse_film_layers("all");
    Renderer renderer(device, scene, settings);
    expect_layers_match_the_scene(renderer.render_frame(0), settings.mirror_depth);
  }
}

TEST(OpenclFilmLayers, WithoutMirrorBouncesTheMirrorHasNoAlbedo) {
  RenderSettings settings;
  settings.mirror_depth = 0;
  settings.layers = parse_film_layers("all");
  const Scene scene = test::layer_scene(kWidth, kHeight);
  Renderer renderer(test::shared_opencl_device(), scene, settings);
  expect_layers_match_the_scene(renderer.render_frame(0), 0);
}

TEST(OpenclFilmLayers, LayersChangeNoColourLayerAndCostNothingUnasked) {
  Device& device = test::shared_opencl_device();
  const Scene scene = test::layer_scene(kWidth, kHeight);
  RenderSettings plain;
  auto path = std::make_shared<PathSettings>();
  path->samples = 2;
  plain.method = path;
  RenderSettings layered = plain;
  layered.layers = parse_film_layers("depth,albedo");

  Renderer without(device, scene, plain);
  EXPECT_EQ(without.buffers()[BufferSlot::film_albedo].bytes(), 0u);
  EXPECT_EQ(without.buffers()[BufferSlot::film_normal].bytes(), 0u);
  EXPECT_EQ(without.buffers()[BufferSlot::film_position].bytes(), 0u);
  const FrameImage a = without.render_frame(0);
  std::vector<std::string> names;
  for (const ImageLayer& layer : a.layers) names.push_back(layer.name);
  EXPECT_EQ(names, (std::vector<std::string>{"", "direct", "indirect", "caustic"}));
  EXPECT_TRUE(a.data_layers.empty());

  Renderer with(device, scene, layered);
  const FrameImage b = with.render_frame(0);
  ASSERT_EQ(b.layers.size(), 5u);  // the four, then albedo
  EXPECT_EQ(b.layers[4].name, "albedo");
  ASSERT_EQ(b.data_layers.size(), 1u);  // depth alone
  EXPECT_EQ(b.data_layers[0].channels, std::vector<std::string>{"Z"});
  for (size_t l = 0; l < a.layers.size(); ++l) {
    SCOPED_TRACE(a.layers[l].name);
    EXPECT_EQ(a.layers[l].rgb, b.layers[l].rgb);  // same seed, same kernels: the same pixels
  }
}

}  // namespace
}  // namespace pm

// The indirect light of every method against path-traced references of the benchmark and golden
// scenes (tests/accuracy/references/, made by bench/accuracy_suite.sh: 65536 paths per pixel,
// 96 x 54), on the OpenCL backend (PoCL in CI). Each check is the signed bias of the indirect
// light with the direct light matched (render/image_metrics.h, as `pmrender compare` prints it),
// and the frame's own error estimate must see it: a deliberately biased estimate (footprints
// spread over the whole ellipse, the estimator before footprint coverage) fails the bias check
// and is reported by the estimate. The benchmark scenes read their meshes from ../shared/scenes;
// where that folder is missing at configure time, their cases are not built (CMake says so).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <tuple>

#include "render/exr_io.h"
#include "render/image_metrics.h"
#include "render/progressive.h"
#include "render/renderer.h"
#include "scene_io/cornell_box.h"
#include "scene_io/scene_file.h"
#include "support/device_checks.h"
#include "support/render_settings.h"

namespace pm {
namespace {

constexpr int kWidth = 96, kHeight = 54;

Device& device() {
  static std::unique_ptr<Device> d = test::open_first_device("opencl");
  if (!d) throw std::runtime_error("no OpenCL device");
  return *d;
}

// The committed references of the benchmark scenes were path traced before pmrender read
// textures and emission (tests/accuracy/references/README.md): Sponza's and Sibenik's map_Kd
// images and the emissive panel of McGuire's box (MTL Ke, which lights it besides the scene's
// point light) are left out here, so both sides see the scenes as the references did, until
// they are remade.
void as_referenced(Scene& scene) {
  for (MaterialDesc& m : scene.materials) {
    m.base_color_texture = -1;
    m.alpha_mask = false;
    m.emission = Float3{0, 0, 0};
  }
  scene.images.clear();
  scene.textures.clear();
  scene.triangle_uvs.clear();
}

// The built-in box, a benchmark scene (bench/scenes) or a golden scene (golden/scenes), loaded
// once per process: the benchmark scenes' meshes take 0.2-0.4 s to read, and each is rendered by
// about ten checks.
const Scene& scene_named(const std::string& name) {
  static std::map<std::string, Scene> loaded;
  auto found = loaded.find(name);
  if (found != loaded.end()) return found->second;
  Scene scene;
  if (name == "builtin") {
    scene = builtin_cornell_box();
  } else {
    const std::string bench = std::string(PM_SOURCE_DIR) + "/bench/scenes/" + name + ".json";
    const std::string golden = std::string(PM_SOURCE_DIR) + "/golden/scenes/" + name + ".json";
    scene = load_scene_file(std::filesystem::exists(bench) ? bench : golden);
    as_referenced(scene);
  }
  return loaded.emplace(name, std::move(scene)).first->second;
}

struct Accuracy {
  double bias = 0;       // signed bias of the indirect light, the direct light matched
  double estimate = -1;  // the frame's error estimate (pmrender/error_estimate)
};

Accuracy render_against_reference(const std::string& scene_name, RenderSettings settings, int bounces = 2) {
  const Scene& scene = scene_named(scene_name);
  settings.width = kWidth;
  settings.height = kHeight;
  Renderer renderer(device(), scene, settings);
  PassBudget budget;
  budget.max_passes = settings.passes;
  const ProgressiveResult result = render_progressive(renderer, 0, budget, nullptr, 0);
  const FrameImage test = renderer.read_image();
  const FrameImage reference = read_exr(std::string(PM_SOURCE_DIR) + "/tests/accuracy/references/ref_" + scene_name +
                                        "_b" + std::to_string(bounces) + ".exr");
  Accuracy a;
  a.bias = light_bias(reference, test).indirect;
  a.estimate = result.error;
  std::printf("%-16s %-40s bias %+.4f  estimate %.4f\n", scene_name.c_str(), renderer.describe().c_str(), a.bias,
              a.estimate);
  return a;
}

RenderSettings photon_defaults() { return test::photon_render_settings(PhotonSettings{}); }

// The path tracer's noise at the references' 65536 paths per pixel, summed over the image, is
// under 0.1 % in every scene (tests/accuracy/references/README.md), so the tolerances below are
// the targets, not noise allowances.
constexpr double kPhotonTolerance = 0.015;
// The k-nearest-neighbour and fixed-radius baselines: the 3 %.
constexpr double kBaselineTolerance = 0.03;

class SceneAccuracy : public testing::TestWithParam<const char*> {};

TEST_P(SceneAccuracy, PhotonMappingAtItsDefaultsIsWithinOneAndAHalfPercent) {
  const Accuracy a = render_against_reference(GetParam(), photon_defaults());
  EXPECT_LE(std::fabs(a.bias), kPhotonTolerance);
  EXPECT_GE(a.estimate, 2.0 / 3.0 * std::fabs(a.bias)) << "the estimate sees the bias";
}

// pd's consistent mode (`--progressive shrink`, the default under a budget) with its own
// defaults (overlap 50, alpha 0.2, facet weighting; docs/accuracy.md "Shrink that converges") on
// the benchmark scenes, whose creases, bends and rims the closed boxes lack (the boxes'
// shrinking passes: tests/opencl/progressive_test.cpp). Four passes, 14-16 s a scene on PoCL
// (2 cores): Sponza -0.89, Sibenik -0.63, Conference -0.53 %; eight passes, twice the time, read
// -0.39, -0.33, -0.24 % (alpha 0.3: -0.61, -0.44, -0.26 %).
class ShrinkAccuracy : public testing::TestWithParam<const char*> {};
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(ShrinkAccuracy);

TEST_P(ShrinkAccuracy, ShrinkingPassesAtTheirDefaultsAreWithinOneAndAHalfPercent) {
  PhotonSettings photons;
  photons.progressive = kProgressiveShrink;
  const Accuracy a = render_against_reference(GetParam(), test::photon_render_settings(photons, 4));
  EXPECT_LE(std::fabs(a.bias), kPhotonTolerance);
  EXPECT_GE(a.estimate, 2.0 / 3.0 * std::fabs(a.bias)) << "the estimate sees the bias";
}

TEST_P(SceneAccuracy, NearestNeighboursAtTheirDefaultsAreWithinThreePercent) {
  // Jensen's estimate over the whole disc read -26 to -56 % in the benchmark scenes; the knn
  // region's area on the surface (knn_gather.h) brings it here.
  RenderSettings settings = photon_defaults();
  test::edit_photons(settings).estimator = PM_ESTIMATOR_KNN;
  const Accuracy a = render_against_reference(GetParam(), settings);
  EXPECT_LE(std::fabs(a.bias), kBaselineTolerance);
  EXPECT_GE(a.estimate, 2.0 / 3.0 * std::fabs(a.bias)) << "the estimate sees the bias";
}

TEST_P(SceneAccuracy, FixedRadiusAtItsDefaultsIsWithinThreePercent) {
  // The radius's spheres reach across the bends of tessellated curved surfaces (Sibenik's ribs and
  // columns); counted in full there, its light read +3.2 % at 960 x 540; its default weighs each
  // photon by what it delivers on the tilted facet (gather_reach.h, docs/accuracy.md).
  // Conference's image mean under one pass of the radius's wide spheres moves with the photons'
  // seed (PoCL, 96 x 54: +4.29, -0.35, +3.60 % at seeds 1-3; 16 passes +1.65 %), so there the
  // check averages four passes (+1.64, +0.26, +1.63 %); elsewhere one pass reads within 1.4 %.
  const bool noisy = std::string(GetParam()) == "conference";
  RenderSettings settings = test::photon_render_settings(PhotonSettings{}, noisy ? 4 : 1);
  test::edit_photons(settings).estimator = PM_ESTIMATOR_RADIUS;
  const Accuracy a = render_against_reference(GetParam(), settings);
  EXPECT_LE(std::fabs(a.bias), kBaselineTolerance);
  EXPECT_GE(a.estimate, 2.0 / 3.0 * std::fabs(a.bias)) << "the estimate sees the bias";
}

TEST_P(SceneAccuracy, ABiasedEstimateIsCaughtByTheBiasCheckAndTheErrorEstimate) {
  // Footprints whose flux is spread over the whole ellipse, hanging over edges or not, at the
  // automatic smoothing's former overlap of 800: the estimator before footprint coverage, 4 to 20 %
  // too dark in these scenes. (At today's smaller footprints, overlap 100, the built-in box loses
  // only 1 % without coverage: too little for the 1.5 % check to tell from a right answer.)
  RenderSettings settings = photon_defaults();
  test::edit_photons(settings).footprint_coverage = false;
  test::edit_photons(settings).overlap = 800;
  const Accuracy a = render_against_reference(GetParam(), settings);
  EXPECT_GT(std::fabs(a.bias), kPhotonTolerance) << "the bias check catches it";
  EXPECT_GE(a.estimate, 2.0 / 3.0 * std::fabs(a.bias)) << "the error estimate reports it";
}

// Final gathering over photons (docs/final-gathering.md) at its defaults (16 rays a pass, the map
// at overlap 3, shrinking passes) but for 65,536 photons a pass, over four passes, on the boxes,
// the golden scenes and the benchmark scenes, against the photon methods' 1.5 % target. Measured
// on PoCL:
// -0.60, +0.83, +0.04, -0.30, +1.01, +0.38 and -0.05 % (the two boxes, glossy, three-lights,
// Sponza, Sibenik, Conference). The golden mirror-box and ring are not here: a point light's
// light through a perfect mirror is beyond the path tracer (docs/tradeoff.md, "Which light
// paths"), so their references lack what the photon methods find there: final gathering's
// indirect light read +21 % on the mirror box (this check's bias) and +27 % on the ring (the
// indirect layer's mean), pd alone +7 % and +24 % (the mean).
class FinalGatherAccuracy : public testing::TestWithParam<const char*> {};
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(FinalGatherAccuracy);

TEST_P(FinalGatherAccuracy, FinalGatheringAtItsDefaultsIsWithinOneAndAHalfPercent) {
  PhotonSettings photons;
  photons.final_gather = 16;
  photons.photons = 65536;
  photons.progressive = kProgressiveShrink;
  // The photon maps move the image's mean from seed to seed by about as much as the tolerance in
  // the boxes (the built-in box at 16 passes, seeds 1-4: -1.50, +0.31, -1.01, +2.20 %; at 4 passes
  // McGuire's box -2.15, +0.04, -3.95 %; the same spread before final gathering's rays became
  // scrambled nets), by a few tenths of a percent on the benchmark scenes: the boxes are read over
  // 16 passes and three seeds averaged, the benchmark scenes over 4 passes and one seed.
  const std::string scene = GetParam();
  const bool benchmark = scene == "sponza" || scene == "sibenik" || scene == "conference";
  const uint32_t passes = benchmark ? 4 : 16, seeds = benchmark ? 1 : 3;
  Accuracy mean;
  mean.estimate = 0;
  for (uint32_t seed = 1; seed <= seeds; ++seed) {
    RenderSettings settings = test::photon_render_settings(photons, passes);
    settings.seed = seed;
    const Accuracy a = render_against_reference(scene, settings);
    mean.bias += a.bias / seeds;
    mean.estimate += a.estimate / seeds;
  }
  std::printf("%s: mean bias %+.4f, mean estimate %.4f over %u seeds\n", scene.c_str(), mean.bias, mean.estimate, seeds);
  EXPECT_LE(std::fabs(mean.bias), kPhotonTolerance);
  EXPECT_GE(mean.estimate, 2.0 / 3.0 * std::fabs(mean.bias)) << "the estimate sees the bias";
}

// Vertex link radiosity at its defaults, per bounce (the first bounce alone, then both), against
// the same references and the same 1.5 % target. The closed boxes at the defaults: they take 4 to
// 6 s each on PoCL; the benchmark scenes 1 to 3 minutes each there (69 million link rays in
// Sponza), so below they trace a quarter of the directions, and bench/accuracy_suite.sh measures
// their defaults (docs/accuracy.md, radiosity section).
class RadiosityAccuracy : public testing::TestWithParam<std::tuple<const char*, int>> {};

TEST_P(RadiosityAccuracy, RadiosityAtItsDefaultsIsWithinOneAndAHalfPercent) {
  const auto [scene, bounces] = GetParam();
  RadiositySettings radiosity;
  radiosity.bounces = bounces;
  const Accuracy a = render_against_reference(scene, test::radiosity_render_settings(radiosity), bounces);
  EXPECT_LE(std::fabs(a.bias), kPhotonTolerance);
  EXPECT_GE(a.estimate, 2.0 / 3.0 * std::fabs(a.bias)) << "the estimate sees the bias";
}

// Radiosity on the benchmark scenes with 32 link directions per element instead of 256: 9-25 s a
// scene on PoCL (2 cores), reading -0.40 / -0.58 / -0.56 % on Sponza, Sibenik and Conference (64
// directions, final gathering's own default, -0.29 / -0.20 / -0.41 % in 21-53 s), where the
// defaults took 66-201 s.
class RadiosityBenchmarkAccuracy : public testing::TestWithParam<const char*> {};
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(RadiosityBenchmarkAccuracy);

TEST_P(RadiosityBenchmarkAccuracy, ThirtyTwoDirectionsAreWithinOneAndAHalfPercent) {
  RadiositySettings radiosity;
  radiosity.directions = 32;
  const Accuracy a = render_against_reference(GetParam(), test::radiosity_render_settings(radiosity));
  EXPECT_LE(std::fabs(a.bias), kPhotonTolerance);
  EXPECT_GE(a.estimate, 2.0 / 3.0 * std::fabs(a.bias)) << "the estimate sees the bias";
}

TEST(RadiosityAccuracy, VertexOriginsAndVertexLightLinksAreCaughtByTheBiasCheck) {
  // The paper's sampling at the vertex alone, for the link rays and the light links: light
  // leaks through the walls at concave edges and a vertex near the lamp is over-weighted.
  RadiositySettings radiosity;
  radiosity.link_origins = PM_RADIOSITY_ORIGINS_VERTEX;
  radiosity.light_samples = PM_RADIOSITY_LIGHT_VERTEX;
  const Accuracy a = render_against_reference("builtin", test::radiosity_render_settings(radiosity));
  EXPECT_GT(std::fabs(a.bias), kPhotonTolerance) << "the bias check catches it";
}

INSTANTIATE_TEST_SUITE_P(Closed, RadiosityAccuracy,
                         testing::Combine(testing::Values("builtin", "cornell-mcguire"), testing::Values(1, 2)));

INSTANTIATE_TEST_SUITE_P(Closed, SceneAccuracy, testing::Values("builtin", "cornell-mcguire"));
INSTANTIATE_TEST_SUITE_P(Golden, FinalGatherAccuracy,
                         testing::Values("builtin", "cornell-mcguire", "glossy", "three-lights"));
#if PM_HAVE_BENCH_SCENES
INSTANTIATE_TEST_SUITE_P(Benchmark, SceneAccuracy, testing::Values("sponza", "sibenik", "conference"));
INSTANTIATE_TEST_SUITE_P(Benchmark, ShrinkAccuracy, testing::Values("sponza", "sibenik", "conference"));
INSTANTIATE_TEST_SUITE_P(Benchmark, RadiosityBenchmarkAccuracy, testing::Values("sponza", "sibenik", "conference"));
INSTANTIATE_TEST_SUITE_P(Benchmark, FinalGatherAccuracy, testing::Values("sponza", "sibenik", "conference"));
#endif

}  // namespace
}  // namespace pm

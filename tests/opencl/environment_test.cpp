// The environment light on PoCL. A plane under a constant environment: its direct light is
// albedo x L (irradiance pi L) and no method finds indirect light on it. The white furnace: a
// floor and a wall of albedo 1 under a constant environment reflect exactly L in the limit of
// many bounces, so direct + indirect of the path tracer, photon mapping and radiosity is L up to
// the bounces left out (at most 2^-B of it: no point sees more than half its hemisphere
// covered). An importance-sampled OpenEXR map (written here, read through a JSON scene): the
// floor's direct light against the exact integral of the piecewise-constant map, a map varying
// in azimuth only against the constant environment of its mean, the three methods' indirect
// light under it, and the path tracer's MIS against light samples alone.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "render/exr_io.h"
#include "render/path/path_settings.h"
#include "render/renderer.h"
#include "scene_io/scene_file.h"
#include "support/device_checks.h"
#include "support/image_stats.h"
#include "support/lit_boxes.h"
#include "support/render_settings.h"
#include "support/room_scenes.h"

namespace pm {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = 3.14159265358979323846;

EnvironmentDesc constant_environment(float radiance) {
  EnvironmentDesc env;
  env.type = EnvironmentType::constant;
  env.radiance = {radiance, radiance, radiance};
  return env;
}

// A large floor quad at y = 0 of albedo rho, seen from above through a narrow view of its centre.
Scene floor_under_sky(float rho, const EnvironmentDesc& env) {
  Scene s;
  s.name = "floor";
  s.source = "test";
  s.materials = {test::diffuse_material("floor", {rho, rho, rho})};
  test::add_quad(s, {-4, 0, -4}, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4});
  s.environment = env;
  s.camera.position = {0, 1, 0};
  s.camera.look_at = {0, 0, 0};
  s.camera.up = {0, 0, 1};
  s.camera.vertical_fov_degrees = 60;
  return s;
}

RenderSettings settings_for(std::shared_ptr<const MethodSettings> method, int size, uint32_t passes,
                            uint32_t light_samples = 16) {
  RenderSettings settings;
  settings.width = settings.height = size;
  settings.passes = passes;
  settings.area_light_samples = light_samples;
  settings.method = std::move(method);
  return settings;
}

std::shared_ptr<PathSettings> path_method(int bounces, uint32_t samples, bool mis = true) {
  auto path = std::make_shared<PathSettings>();
  path->samples = samples;
  path->bounces = bounces;
  path->mis = mis;
  return path;
}

std::shared_ptr<PhotonSettings> photon_method(int bounces, uint64_t photons_per_pass = 65536) {
  auto photons = std::make_shared<PhotonSettings>();
  photons->photons = photons_per_pass;
  photons->bounces = bounces;
  photons->estimator = PM_ESTIMATOR_RADIUS;
  photons->radius = 0.04f;
  return photons;
}

std::shared_ptr<RadiositySettings> radiosity_method(int bounces) {
  auto radiosity = std::make_shared<RadiositySettings>();
  radiosity->max_edge = 0.1f;
  radiosity->directions = 256;
  radiosity->bounces = bounces;
  return radiosity;
}

double layer_mean(const FrameImage& image, const char* layer) { return test::mean(image.find(layer)->rgb); }

class Environment : public ::testing::Test {
 protected:
  void SetUp() override {
    device_ = test::open_first_device("opencl");
    dir_ = fs::path(::testing::TempDir()) / "pm_environment_test";
    fs::create_directories(dir_);
  }
  FrameImage render(const Scene& scene, const RenderSettings& settings) {
    Renderer renderer(*device_, scene, settings);
    return renderer.render_frame(0);
  }
  // Writes a W x H map (rgb per texel, top row first) and loads a JSON floor scene lit by it.
  Scene floor_with_map(const std::vector<float>& rgb, int width, int height, float rho) {
    FrameImage map;
    map.width = width;
    map.height = height;
    map.layers.push_back(ImageLayer{"", rgb});
    write_exr((dir_ / "sky.exr").string(), map, true);
    std::ofstream(dir_ / "floor.obj") << "usemtl floor\nv -4 0 -4\nv -4 0 4\nv 4 0 4\nv 4 0 -4\nf 1 2 3\nf 1 3 4\n";
    std::ofstream(dir_ / "floor.json") << R"({"format": "pmrender-scene", "version": 1,
      "meshes": [{"file": "floor.obj"}],
      "materials": {"floor": {"diffuse": [)" << rho << ", " << rho << ", " << rho << R"(]}},
      "environment": {"map": "sky.exr", "rotation_deg": 40},
      "camera": {"position": [0, 1, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "vertical_fov": 60}})";
    return load_scene_file((dir_ / "floor.json").string());
  }
  std::unique_ptr<Device> device_;
  fs::path dir_;
};

TEST_F(Environment, PlaneUnderAConstantSkyReflectsAlbedoTimesRadiance) {
  ASSERT_NE(device_, nullptr);
  const float rho = 0.5f, radiance = 2.0f;
  const Scene scene = floor_under_sky(rho, constant_environment(radiance));
  const FrameImage direct = render(scene, settings_for(nullptr, 32, 1, 256));
  const double mean = layer_mean(direct, "direct");
  std::printf("plane under a constant sky: direct %.6g, albedo x L = %.6g (%+.4f)\n", mean, rho * radiance,
              mean / (rho * radiance) - 1);
  // 1024 pixels x 256 uniform sphere samples: the mean's noise is about 0.25 %.
  EXPECT_NEAR(mean / (rho * radiance), 1.0, 0.01);
  // Nothing reflects light back onto a lone plane: every method's indirect light is zero.
  for (auto method : {std::shared_ptr<const MethodSettings>(path_method(2, 4)),
                      std::shared_ptr<const MethodSettings>(photon_method(2)),
                      std::shared_ptr<const MethodSettings>(radiosity_method(2))}) {
    const FrameImage image = render(scene, settings_for(method, 16, 1));
    EXPECT_EQ(layer_mean(image, "indirect") + layer_mean(image, "caustic"), 0.0) << method->method_name();
  }
  // The sky itself, where the camera looks past the plane.
  Scene up = scene;
  up.camera.look_at = {0, 2, 0};
  EXPECT_NEAR(layer_mean(render(up, settings_for(nullptr, 8, 1)), "direct"), radiance, 1e-6);
}

TEST_F(Environment, WhiteFurnaceReflectsTheSkyForEveryMethod) {
  ASSERT_NE(device_, nullptr);
  const float radiance = 1.5f;
  const int bounces = 10;  // leaves out at most 2^-10 of L
  const Scene scene = test::floor_and_wall(1.0f, constant_environment(radiance));
  const int size = 24;
  struct Run {
    const char* name;
    std::shared_ptr<const MethodSettings> method;
    uint32_t passes;
    double tolerance;
  };
  const Run runs[] = {{"path", path_method(bounces, 64), 2, 0.02},
                      {"photon", photon_method(bounces), 4, 0.04},
                      {"radiosity", radiosity_method(bounces), 1, 0.04}};
  for (const Run& run : runs) {
    const FrameImage image = render(scene, settings_for(run.method, size, run.passes));
    const double direct = layer_mean(image, "direct");
    const double indirect = layer_mean(image, "indirect") + layer_mean(image, "caustic");
    std::printf("white furnace, %s: direct %.5g + indirect %.5g = %.5g, L = %.5g (%+.4f)\n", run.name, direct, indirect,
                direct + indirect, double(radiance), (direct + indirect) / radiance - 1);
    EXPECT_NEAR((direct + indirect) / radiance, 1.0, run.tolerance) << run.name;
    EXPECT_GT(indirect, 0.1 * radiance) << run.name;  // the wall and the floor light each other
    EXPECT_TRUE(test::all_finite(image.find("")->rgb)) << run.name;
  }
}

// The floor's irradiance from a map is the exact sum over its upper rows of
// L_ij (2 pi / W) int cos theta sin theta d theta, whatever the turn about +y.
TEST_F(Environment, MapDirectLightMatchesTheExactIntegral) {
  ASSERT_NE(device_, nullptr);
  const int width = 64, height = 32;
  std::vector<float> rgb(size_t(width * height * 3));
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const float sky = 0.2f + 0.8f * float(j) / height;  // brighter towards the horizon
      const bool sun = (i == 41 && j == 6);
      for (int c = 0; c < 3; ++c) rgb[size_t(3 * (j * width + i) + c)] = sun ? 400.0f : sky * (0.6f + 0.2f * c);
    }
  const float rho = 0.5f;
  const Scene scene = floor_with_map(rgb, width, height, rho);
  ASSERT_EQ(scene.environment.type, EnvironmentType::map);
  double irradiance[3] = {0, 0, 0};
  for (int j = 0; j < height / 2; ++j) {
    const double t0 = kPi * j / height, t1 = kPi * (j + 1) / height;
    const double band = 2 * kPi / width * 0.5 * (std::sin(t1) * std::sin(t1) - std::sin(t0) * std::sin(t0));
    for (int i = 0; i < width; ++i)
      for (int c = 0; c < 3; ++c) irradiance[c] += band * rgb[size_t(3 * (j * width + i) + c)];
  }
  const FrameImage image = render(scene, settings_for(nullptr, 32, 1, 256));
  const std::vector<float>& direct = image.find("direct")->rgb;
  for (int c = 0; c < 3; ++c) {
    double sum = 0;
    for (size_t p = 0; p < direct.size() / 3; ++p) sum += direct[3 * p + size_t(c)];
    const double mean = sum / double(direct.size() / 3), expected = rho / kPi * irradiance[c];
    std::printf("floor under a map, channel %d: direct %.6g, exact %.6g (%+.4f)\n", c, mean, expected, mean / expected - 1);
    EXPECT_NEAR(mean / expected, 1.0, 0.01);
  }
}

TEST_F(Environment, AzimuthOnlyMapMatchesTheConstantOfItsMean) {
  ASSERT_NE(device_, nullptr);
  const int width = 48, height = 16;
  std::vector<float> rgb(size_t(width * height * 3));
  double column_sum = 0;
  for (int i = 0; i < width; ++i) {
    const float value = i == 30 ? 40.0f : 0.5f + 0.4f * float(std::sin(3 * 2 * kPi * i / width));
    column_sum += value;
    for (int j = 0; j < height; ++j)
      for (int c = 0; c < 3; ++c) rgb[size_t(3 * (j * width + i) + c)] = value;
  }
  const float rho = 0.7f, mean_radiance = float(column_sum / width);
  const Scene mapped = floor_with_map(rgb, width, height, rho);
  const Scene constant = floor_under_sky(rho, constant_environment(mean_radiance));
  const double a = layer_mean(render(mapped, settings_for(nullptr, 32, 1, 256)), "direct");
  const double b = layer_mean(render(constant, settings_for(nullptr, 32, 1, 256)), "direct");
  std::printf("azimuth-only map %.6g against the constant of its mean %.6g (%+.4f)\n", a, b, a / b - 1);
  EXPECT_NEAR(a / b, 1.0, 0.015);
}

TEST_F(Environment, MethodsAgreeUnderAMapAndMisAgreesWithLightSampling) {
  ASSERT_NE(device_, nullptr);
  const int width = 32, height = 16;
  std::vector<float> rgb(size_t(width * height * 3));
  for (int t = 0; t < width * height; ++t)
    for (int c = 0; c < 3; ++c) rgb[size_t(3 * t + c)] = (t == 5 * width + 20) ? 300.0f : 0.3f + 0.1f * c;
  Scene scene = test::floor_and_wall(0.6f, floor_with_map(rgb, width, height, 0.6f).environment);
  const FrameImage traced = render(scene, settings_for(path_method(2, 64), 16, 4));
  const FrameImage light_only = render(scene, settings_for(path_method(2, 64, false), 16, 4));
  const FrameImage mapped = render(scene, settings_for(photon_method(2, 262144), 16, 8));
  const FrameImage solved = render(scene, settings_for(radiosity_method(2), 16, 1));
  const double path = layer_mean(traced, "indirect"), path_light = layer_mean(light_only, "indirect");
  const double photon = layer_mean(mapped, "indirect") + layer_mean(mapped, "caustic");
  const double rad = layer_mean(solved, "indirect");
  std::printf("map-lit corner: indirect path %.6g (light samples alone %.6g, %+.4f), photon %.6g (%+.4f), radiosity "
              "%.6g (%+.4f)\n", path, path_light, path_light / path - 1, photon, photon / path - 1, rad, rad / path - 1);
  EXPECT_GT(path, 0.0);
  EXPECT_NEAR(path_light / path, 1.0, 0.03);
  EXPECT_NEAR(photon / path, 1.0, 0.06);
  EXPECT_NEAR(rad / path, 1.0, 0.08);
}

}  // namespace
}  // namespace pm

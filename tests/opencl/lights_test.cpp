// Spot lights and area lights on PoCL: a spot's direct light on a plane against the closed form
// (inside the inner cone, the falloff between the cones, zero outside); an emitting square's
// irradiance at the centre of the floor under it against the closed form, and the emitter's
// own radiance seen from its front and nothing from its back; photon mapping, path tracing and
// radiosity (and final gathering over the photon map and over the radiosity solution) agreeing on
// the indirect light of a small spot-lit and of an area-lit box; and the
// path tracer's multiple importance sampling agreeing with light sampling alone.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "render/path/path_settings.h"
#include "render/renderer.h"
#include "support/device_checks.h"
#include "support/image_stats.h"
#include "support/render_settings.h"
#include "support/lit_boxes.h"
#include "support/room_scenes.h"

namespace pm {
namespace {

using test::area_box;
using test::spot_box;

constexpr double kPi = 3.14159265358979323846;

class Lights : public ::testing::Test {
 protected:
  void SetUp() override { device_ = test::open_first_device("opencl"); }
  // The direct layer of a render without an indirect method (the camera pass alone).
  FrameImage direct_only(const Scene& scene, int size, uint32_t area_samples = 16) {
    RenderSettings settings;
    settings.width = settings.height = size;
    settings.area_light_samples = area_samples;
    Renderer renderer(*device_, scene, settings);
    return renderer.render_frame(0);
  }
  std::unique_ptr<Device> device_;
};

// A large floor quad at y = 0, reflectance rho, facing up.
Scene floor_scene(float rho) {
  Scene s;
  s.name = "floor";
  s.source = "test";
  s.materials = {test::diffuse_material("floor", {rho, rho, rho})};
  test::add_quad(s, {-4, 0, -4}, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4});
  return s;
}

// The point where pixel (x, y)'s eye ray meets the plane y = 0.
Float3 floor_point(const Scene& scene, int size, int x, int y) {
  const CameraParams c = make_camera_params(scene.camera, size, size);
  const float u = 2.0f * (x + 0.5f) / size - 1.0f, v = 1.0f - 2.0f * (y + 0.5f) / size;
  const double d[3] = {c.forward.x + u * c.right.x + v * c.up.x, c.forward.y + u * c.right.y + v * c.up.y,
                       c.forward.z + u * c.right.z + v * c.up.z};
  const double t = -c.position.y / d[1];
  return Float3{float(c.position.x + t * d[0]), 0.0f, float(c.position.z + t * d[2])};
}

TEST_F(Lights, SpotDirectLightOnAPlaneMatchesTheClosedForm) {
  ASSERT_NE(device_, nullptr);
  const float rho = 0.5f, intensity = 10.0f, height = 1.0f;
  const double inner = 20 * kPi / 180, outer = 30 * kPi / 180;
  Scene scene = floor_scene(rho);
  LightDesc spot;
  spot.name = "spot";
  spot.type = LightType::spot;
  spot.position = {0, height, 0};
  spot.power = {float(4 * kPi * intensity), float(4 * kPi * intensity), float(4 * kPi * intensity)};
  spot.direction = {0, -1, 0};
  spot.inner_cone = float(inner);
  spot.outer_cone = float(outer);
  scene.lights = {spot};
  scene.camera.position = {0, 2, 0};
  scene.camera.look_at = {0, 0, 0};
  scene.camera.up = {0, 0, 1};
  scene.camera.vertical_fov_degrees = 70;
  const int size = 48;
  const FrameImage image = direct_only(scene, size);
  const std::vector<float>& rgb = image.find("direct")->rgb;
  int inside = 0, between = 0, outside = 0;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const Float3 p = floor_point(scene, size, x, y);
      const double r2 = double(p.x) * p.x + double(p.z) * p.z + double(height) * height, r = std::sqrt(r2);
      const double c = height / r;  // cos of the angle to the axis, and cos theta_i at the floor
      double falloff = 1;
      if (c <= std::cos(outer)) falloff = 0;
      else if (c < std::cos(inner)) falloff = std::pow((c - std::cos(outer)) / (std::cos(inner) - std::cos(outer)), 2);
      const double expected = rho / kPi * intensity * falloff * c / r2;
      const double got = rgb[3 * size_t(y * size + x)];
      if (c > std::cos(inner) + 1e-4) {
        ++inside;
        EXPECT_NEAR(got / expected, 1.0, 1e-4) << "inside the inner cone at " << x << ", " << y;
      } else if (c < std::cos(outer) - 1e-4) {
        ++outside;
        EXPECT_EQ(got, 0.0) << "outside the outer cone at " << x << ", " << y;
      } else if (c > std::cos(outer) + 1e-4 && c < std::cos(inner) - 1e-4) {
        ++between;
        EXPECT_NEAR(got, expected, 2e-3 * rho / kPi * intensity * c / r2) << "between the cones at " << x << ", " << y;
      }
    }
  }
  std::printf("spot on a plane: %d pixels inside the inner cone, %d between the cones, %d outside\n", inside, between, outside);
  EXPECT_GT(inside, 20);
  EXPECT_GT(between, 20);
  EXPECT_GT(outside, 100);
}

// An emitting square of side 2a at height h, facing down, over the floor.
Scene area_lit_floor(float rho, float half_side, float height, float radiance) {
  Scene s = floor_scene(rho);
  MaterialDesc lamp = test::diffuse_material("lamp", {0, 0, 0});
  lamp.emission = {radiance, radiance, radiance};
  s.materials.push_back(lamp);
  const float a = half_side;
  test::add_quad(s, {-a, height, -a}, {a, height, -a}, {a, height, a}, {-a, height, a}, 1);  // normal -y
  return s;
}

TEST_F(Lights, AreaLightIrradianceUnderASquareMatchesTheClosedForm) {
  ASSERT_NE(device_, nullptr);
  const float rho = 0.5f, a = 1.0f, h = 1.0f, radiance = 2.0f;
  Scene scene = area_lit_floor(rho, a, h, radiance);
  // A narrow view of the floor's centre from under the square.
  scene.camera.position = {0, 0.5f, 0};
  scene.camera.look_at = {0, 0, 0};
  scene.camera.up = {0, 0, 1};
  scene.camera.vertical_fov_degrees = 1;
  const FrameImage image = direct_only(scene, 8, 4096);
  // A Lambertian square of radiance L, side 2a, at height h over its centre's foot point:
  // E = 4 L X / sqrt(1 + X^2) atan(X / sqrt(1 + X^2)), X = a / h (four corner rectangles).
  const double x = a / h, s = std::sqrt(1 + x * x);
  const double irradiance = 4 * radiance * x / s * std::atan(x / s);
  const double expected = rho / kPi * irradiance;
  const double mean = test::mean(image.find("direct")->rgb);
  std::printf("area light over the floor's centre: %.6g, closed form %.6g (%+.4f)\n", mean, expected, mean / expected - 1);
  // 64 pixels x 4096 light samples: the mean's noise is about 0.2 %.
  EXPECT_NEAR(mean / expected, 1.0, 0.01);

  // The emitter's own radiance goes to the direct layer, from its front face only.
  scene.camera.look_at = {0, 1, 0};
  EXPECT_NEAR(test::mean(direct_only(scene, 8).find("direct")->rgb), radiance, 1e-5);
  scene.camera.position = {0, 2, 0};
  EXPECT_EQ(test::mean(direct_only(scene, 8).find("direct")->rgb), 0.0);
}

RenderSettings box_settings(std::shared_ptr<const MethodSettings> method, uint32_t passes) {
  RenderSettings settings;
  settings.width = settings.height = 16;
  settings.passes = passes;
  settings.method = std::move(method);
  return settings;
}

std::shared_ptr<PathSettings> path_method(bool mis) {
  auto path = std::make_shared<PathSettings>();
  path->samples = 64;
  path->bounces = 2;
  path->mis = mis;
  return path;
}

// The three methods' indirect means on the same box. Photon mapping: fixed radius 3 cm, 8 passes
// of 65,536 photons; radiosity: 5 cm elements; path tracing: 256 paths per pixel.
void expect_methods_agree(Device& device, const Scene& scene, const char* label) {
  PhotonSettings photons;
  photons.photons = 65536;
  photons.bounces = 2;
  photons.estimator = PM_ESTIMATOR_RADIUS;
  photons.radius = 0.03f;
  RadiositySettings radiosity;
  radiosity.max_edge = 0.05f;
  radiosity.directions = 128;
  radiosity.bounces = 2;
  // Final gathering: 16 rays a pass over the default pd map, whose light at the rays' hits comes
  // from the spot or the panel by next-event estimation.
  PhotonSettings gathered;
  gathered.photons = 65536;
  gathered.bounces = 2;
  gathered.final_gather = 16;
  // And over the radiosity solution, solved with one bounce fewer.
  RadiositySettings radiosity_gathered = radiosity;
  radiosity_gathered.final_gather = 16;
  Renderer path_renderer(device, scene, box_settings(path_method(true), 4));
  Renderer photon_renderer(device, scene, box_settings(std::make_shared<PhotonSettings>(photons), 8));
  Renderer radiosity_renderer(device, scene, box_settings(std::make_shared<RadiositySettings>(radiosity), 1));
  Renderer gather_renderer(device, scene, box_settings(std::make_shared<PhotonSettings>(gathered), 4));
  Renderer radiosity_gather_renderer(device, scene,
                                     box_settings(std::make_shared<RadiositySettings>(radiosity_gathered), 4));
  const FrameImage traced = path_renderer.render_frame(0), mapped = photon_renderer.render_frame(0),
                   solved = radiosity_renderer.render_frame(0), final_gathered = gather_renderer.render_frame(0),
                   solution_gathered = radiosity_gather_renderer.render_frame(0);
  const double path = test::mean(traced.find("indirect")->rgb);
  const double photon = test::mean(mapped.find("indirect")->rgb) + test::mean(mapped.find("caustic")->rgb);
  const double rad = test::mean(solved.find("indirect")->rgb);
  const double fg = test::mean(final_gathered.find("indirect")->rgb) + test::mean(final_gathered.find("caustic")->rgb);
  const double rad_fg = test::mean(solution_gathered.find("indirect")->rgb);
  std::printf("%s: indirect mean path %.6g, photon %.6g (%+.4f), radiosity %.6g (%+.4f), final gather %.6g (%+.4f), "
              "over radiosity %.6g (%+.4f); direct %.6g\n", label, path, photon, photon / path - 1, rad, rad / path - 1, fg,
              fg / path - 1, rad_fg, rad_fg / path - 1, test::mean(traced.find("direct")->rgb));
  EXPECT_GT(path, 0.0);
  EXPECT_NEAR(photon / path, 1.0, 0.05) << label;
  EXPECT_NEAR(rad / path, 1.0, 0.08) << label;
  EXPECT_NEAR(fg / path, 1.0, 0.03) << label;
  EXPECT_NEAR(rad_fg / path, 1.0, 0.03) << label;
  for (const FrameImage* image : {&traced, &mapped, &solved, &final_gathered, &solution_gathered})
    EXPECT_TRUE(test::all_finite(image->find("")->rgb));
}

TEST_F(Lights, MethodsAgreeOnASpotLitBox) {
  ASSERT_NE(device_, nullptr);
  expect_methods_agree(*device_, spot_box(), "spot-lit box");
}

TEST_F(Lights, MethodsAgreeOnAnAreaLitBox) {
  ASSERT_NE(device_, nullptr);
  expect_methods_agree(*device_, area_box(), "area-lit box");
}

// Both strategies estimate the same integral: MIS changes the noise, not the mean.
TEST_F(Lights, PathMisAgreesWithLightSamplingAlone) {
  ASSERT_NE(device_, nullptr);
  const Scene scene = area_box();
  Renderer mis(*device_, scene, box_settings(path_method(true), 4));
  Renderer light_only(*device_, scene, box_settings(path_method(false), 4));
  const double a = test::mean(mis.render_frame(0).find("indirect")->rgb);
  const double b = test::mean(light_only.render_frame(0).find("indirect")->rgb);
  std::printf("area-lit box, path tracer: MIS %.6g, light sampling alone %.6g (%+.4f)\n", a, b, a / b - 1);
  EXPECT_NEAR(a / b, 1.0, 0.02);
}

}  // namespace
}  // namespace pm

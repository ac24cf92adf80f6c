// Small scenes lit by the light types other than the point light: closed boxes lit by a spot light
// and by an emitting ceiling panel, and a floor and wall open to an environment, for the tests that
// compare the methods (tests/opencl/lights_test.cpp, environment_test.cpp) and the backends
// (tests/gpu/cuda_lights_test.cpp).
#pragma once

#include <cmath>
#include <memory>

#include "render/radiosity/radiosity_settings.h"
#include "render/scene.h"
#include "support/room_scenes.h"

namespace pm::test {

// A closed white box of 1 m with its light under the ceiling, seen from inside.
inline Scene lit_box() {
  Scene s;
  s.name = "box";
  s.source = "test";
  s.materials = {diffuse_material("white", {0.6f, 0.6f, 0.6f}), diffuse_material("red", {0.6f, 0.15f, 0.1f})};
  add_box(s, {0, 0, 0}, {1, 1, 1});
  for (size_t t = s.triangle_material.size() - 4; t < s.triangle_material.size() - 2; ++t) s.triangle_material[t] = 1;
  s.camera.position = {0.5f, 0.5f, 0.03f};
  s.camera.look_at = {0.5f, 0.45f, 1.0f};
  s.camera.vertical_fov_degrees = 80;
  return s;
}

inline Scene spot_box() {
  Scene s = lit_box();
  LightDesc spot;
  spot.name = "spot";
  spot.type = LightType::spot;
  spot.position = {0.5f, 0.95f, 0.5f};
  spot.power = {12, 12, 12};
  spot.direction = {0.1f, -1, 0.2f};
  spot.inner_cone = float(25 * M_PI / 180);
  spot.outer_cone = float(40 * M_PI / 180);
  s.lights = {spot};
  return s;
}

// Final gathering over a coarse solution of spot_box: elements of 0.1, light and link rays from
// the vertices only, 64 link directions, two bounces; its image levels at about 3.7 % off
// (tests/opencl/method_race_test.cpp, bias_probe_test.cpp).
inline std::shared_ptr<RadiositySettings> coarse_spot_box_radiosity(uint32_t final_gather) {
  auto r = std::make_shared<RadiositySettings>();
  r->max_edge = 0.1f;
  r->directions = 64;
  r->light_samples = PM_RADIOSITY_LIGHT_VERTEX;
  r->link_origins = PM_RADIOSITY_ORIGINS_VERTEX;
  r->bounces = 2;
  r->final_gather = final_gather;
  r->validate();
  return r;
}

inline Scene area_box() {
  Scene s = lit_box();
  MaterialDesc lamp = diffuse_material("lamp", {0.5f, 0.5f, 0.5f});
  lamp.emission = {6, 6, 6};
  s.materials.push_back(lamp);
  add_quad(s, {0.3f, 0.999f, 0.3f}, {0.7f, 0.999f, 0.3f}, {0.7f, 0.999f, 0.7f}, {0.3f, 0.999f, 0.7f}, 2);
  return s;
}

// A 2 x 2 m floor and a 2 x 2 m wall standing on its back edge, both of albedo rho.
inline Scene floor_and_wall(float rho, const EnvironmentDesc& env) {
  Scene s;
  s.name = "corner";
  s.source = "test";
  s.materials = {diffuse_material("white", {rho, rho, rho})};
  add_quad(s, {0, 0, 0}, {0, 0, 2}, {2, 0, 2}, {2, 0, 0});
  add_quad(s, {0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0});
  s.environment = env;
  s.camera.position = {1.0f, 1.6f, 2.6f};
  s.camera.look_at = {1.0f, 0.5f, 0.4f};
  s.camera.vertical_fov_degrees = 60;
  return s;
}

}  // namespace pm::test

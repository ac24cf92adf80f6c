// A scene whose extra layers (render/film_layers.h) can be worked out by hand, and those values:
// the camera at the origin looks down -z at a diffuse plane 2 m away (lower right quarter of the
// image), a perfect mirror 1 m away (left half) that shows a diffuse and glossy wall 3 m behind
// the camera, and nothing (upper right quarter). The expected values come from ray-plane
// intersections written out here, not from the renderer's camera code.
#pragma once

#include <cmath>
#include <cstdint>

#include "render/scene.h"

namespace pm::test {

constexpr float kLayerPlaneZ = -2.0f, kLayerMirrorZ = -1.0f, kLayerWallZ = 3.0f;
constexpr float kLayerFovDegrees = 60.0f;
enum : uint32_t { kLayerPlane, kLayerMirror, kLayerWall };  // object and material indices alike

inline Scene layer_scene(int width, int height) {
  Scene s;
  s.name = "layers";
  s.source = "test";
  auto quad = [&](Float3 a, Float3 b, Float3 c, Float3 d, uint32_t index) {
    const uint32_t base = uint32_t(s.positions.size());
    s.positions.insert(s.positions.end(), {a, b, c, d});
    s.indices.insert(s.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    s.triangle_material.insert(s.triangle_material.end(), {index, index});
    s.triangle_object.insert(s.triangle_object.end(), {index, index});
  };
  const float p = kLayerPlaneZ, m = kLayerMirrorZ, w = kLayerWallZ;
  quad({0, -10, p}, {10, -10, p}, {10, 0, p}, {0, 0, p}, kLayerPlane);        // x >= 0, y <= 0
  quad({-10, -10, m}, {0, -10, m}, {0, 10, m}, {-10, 10, m}, kLayerMirror);   // x <= 0
  quad({-20, -20, w}, {-20, 20, w}, {20, 20, w}, {20, -20, w}, kLayerWall);   // behind the camera
  s.object_names = {"plane", "mirror", "wall"};

  MaterialDesc plane, mirror, wall;
  plane.name = "plane";
  plane.diffuse = {0.6f, 0.4f, 0.2f};
  mirror.name = "mirror";
  mirror.diffuse = {0, 0, 0};
  mirror.mirror = {0.9f, 0.8f, 0.7f};
  wall.name = "wall";
  wall.diffuse = {0.2f, 0.4f, 0.6f};
  wall.glossy = {0.1f, 0.1f, 0.1f};
  wall.glossy_exponent = 10;
  s.materials = {plane, mirror, wall};
  s.lights = {LightDesc{"lamp", {0.5f, 0.5f, 0.5f}, {20, 20, 20}}};
  s.camera.position = {0, 0, 0};
  s.camera.look_at = {0, 0, -1};
  s.camera.up = {0, 1, 0};
  s.camera.vertical_fov_degrees = kLayerFovDegrees;
  s.camera.width = width;
  s.camera.height = height;
  return s;
}

// What one pixel's layers must hold (docs/layers.md).
struct ExpectedLayers {
  float albedo[3] = {0, 0, 0};
  float normal[3] = {0, 0, 0};
  float depth = 1.0e10f;  // a miss
  float position[3] = {0, 0, 0};
  float object_id = -1, material_id = -1;
};

// Pixel (x, y) of a width x height image of layer_scene, followed through at most mirror_depth
// mirror bounces.
inline ExpectedLayers expected_layers(int x, int y, int width, int height, int mirror_depth) {
  const double tan_half = std::tan(kLayerFovDegrees * 0.5 * 3.14159265358979323846 / 180.0);
  const double u = (2.0 * (x + 0.5) / width - 1.0) * tan_half * width / height;
  const double v = (1.0 - 2.0 * (y + 0.5) / height) * tan_half;
  const double length = std::sqrt(u * u + v * v + 1.0);
  const double dx = u / length, dy = v / length, dz = -1.0 / length;
  ExpectedLayers e;
  auto set3 = [](float* out, double a, double b, double c) {
    out[0] = float(a);
    out[1] = float(b);
    out[2] = float(c);
  };
  const double t_mirror = kLayerMirrorZ / dz;
  if (dx * t_mirror < 0) {  // the mirror (x < 0); its reflection reaches the wall behind the camera
    e.depth = float(t_mirror);
    set3(e.position, dx * t_mirror, dy * t_mirror, kLayerMirrorZ);
    e.object_id = e.material_id = float(kLayerMirror);
    if (mirror_depth >= 1) {
      set3(e.albedo, 0.9 * 0.3, 0.8 * 0.5, 0.7 * 0.7);  // mirror reflectance x (diffuse + glossy)
      set3(e.normal, 0, 0, -1);
    }
    return e;
  }
  const double t_plane = kLayerPlaneZ / dz;
  if (dy * t_plane > 0) return e;  // above the plane: nothing
  e.depth = float(t_plane);
  set3(e.position, dx * t_plane, dy * t_plane, kLayerPlaneZ);
  e.object_id = e.material_id = float(kLayerPlane);
  set3(e.albedo, 0.6, 0.4, 0.2);
  set3(e.normal, 0, 0, 1);
  return e;
}

}  // namespace pm::test

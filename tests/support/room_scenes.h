// Small box-and-room scenes built in code for the numerical-extremes and light-leak tests, and the
// transformations that must not change an image: scaling a scene by k with its lights' power by
// k^2 (the same radiance everywhere), and translating it.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>

#include "render/scene.h"

namespace pm::test {

// One quad of two triangles with the given material, corners in order.
inline void add_quad(Scene& s, Float3 a, Float3 b, Float3 c, Float3 d, uint32_t material = 0) {
  const uint32_t base = uint32_t(s.positions.size());
  s.positions.insert(s.positions.end(), {a, b, c, d});
  s.indices.insert(s.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  s.triangle_material.insert(s.triangle_material.end(), {material, material});
}

// The faces of the axis-aligned box [lo, hi] as zero-thickness quads: the four sides and the
// top, and the bottom when `bottom` (without it, a floor under the box closes it).
inline void add_box(Scene& s, Float3 lo, Float3 hi, uint32_t material = 0, bool bottom = true) {
  auto p = [&](int x, int y, int z) { return Float3{x ? hi.x : lo.x, y ? hi.y : lo.y, z ? hi.z : lo.z}; };
  if (bottom) add_quad(s, p(0, 0, 0), p(1, 0, 0), p(1, 0, 1), p(0, 0, 1), material);
  add_quad(s, p(0, 1, 0), p(0, 1, 1), p(1, 1, 1), p(1, 1, 0), material);
  add_quad(s, p(0, 0, 0), p(0, 1, 0), p(1, 1, 0), p(1, 0, 0), material);
  add_quad(s, p(0, 0, 1), p(1, 0, 1), p(1, 1, 1), p(0, 1, 1), material);
  add_quad(s, p(0, 0, 0), p(0, 0, 1), p(0, 1, 1), p(0, 1, 0), material);
  add_quad(s, p(1, 0, 0), p(1, 1, 0), p(1, 1, 1), p(1, 0, 1), material);
}

inline MaterialDesc diffuse_material(const char* name, Float3 albedo) {
  MaterialDesc m;
  m.name = name;
  m.diffuse = albedo;
  return m;
}

// A 4 x 4 m floor at y = 0 for x < 0 that bends down at x = 0 into a slope of 20 degrees, white.
inline Scene bent_floor_scene() {
  Scene s;
  s.name = "bent-floor";
  s.source = "test";
  s.materials = {diffuse_material("white", {0.7f, 0.7f, 0.7f})};
  const float drop = 2.0f * std::tan(0.349066f);  // 20 degrees
  add_quad(s, {-2, 0, -2}, {-2, 0, 2}, {0, 0, 2}, {0, 0, -2});
  add_quad(s, {0, 0, -2}, {0, 0, 2}, {2, -drop, 2}, {2, -drop, -2});
  return s;
}

// A closed 4 x 2.5 x 5 m room [0, 4] x [0, 2.5] x [0, 5] (one corner at the world origin, so its
// floor and two walls lie on the planes x = 0, y = 0 and z = 0), white with a red wall at x = 0
// and a 0.8 x 1 x 0.8 m block standing on the floor. One 60 W point light 0.3 m under the ceiling;
// the camera stands in the far corner and looks at the corner at the origin.
inline Scene closed_room() {
  Scene s;
  s.name = "room";
  s.source = "test";
  s.materials = {diffuse_material("white", {0.7f, 0.7f, 0.7f}), diffuse_material("red", {0.7f, 0.2f, 0.15f})};
  add_box(s, {0, 0, 0}, {4, 2.5f, 5});
  for (size_t t = s.triangle_material.size() - 4; t < s.triangle_material.size() - 2; ++t) s.triangle_material[t] = 1;
  add_box(s, {2.4f, 0, 1.0f}, {3.2f, 1.0f, 1.8f}, 0, false);
  s.lights = {LightDesc{"ceiling", {2.0f, 2.2f, 2.5f}, {60, 60, 60}}};
  s.camera.position = {3.6f, 1.7f, 4.6f};
  s.camera.look_at = {0.8f, 0.6f, 0.7f};
  s.camera.vertical_fov_degrees = 70;
  return s;
}

// The scene scaled by k about the world origin, lights' power by k^2: every radiance, and so the
// image, stays the same.
inline Scene scaled(Scene s, double k) {
  auto scale = [k](Float3 p) { return Float3{float(p.x * k), float(p.y * k), float(p.z * k)}; };
  for (Float3& p : s.positions) p = scale(p);
  for (LightDesc& l : s.lights) {
    l.position = scale(l.position);
    l.power = {float(l.power.x * k * k), float(l.power.y * k * k), float(l.power.z * k * k)};
  }
  s.camera.position = scale(s.camera.position);
  s.camera.look_at = scale(s.camera.look_at);
  return s;
}

// The scene moved by `offset`, lights and camera with it.
inline Scene translated(Scene s, Float3 offset) {
  auto move = [offset](Float3 p) { return Float3{p.x + offset.x, p.y + offset.y, p.z + offset.z}; };
  for (Float3& p : s.positions) p = move(p);
  for (LightDesc& l : s.lights) l.position = move(l.position);
  s.camera.position = move(s.camera.position);
  s.camera.look_at = move(s.camera.look_at);
  return s;
}

}  // namespace pm::test

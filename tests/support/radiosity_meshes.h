// Small meshes for the radiosity tests, built in code: a folded sheet (two rectangles meeting at
// an edge at a chosen angle) and a closed cube.
#pragma once

#include <cmath>

#include "render/scene.h"

namespace pm::test {

inline MaterialDesc grey_material(float rho) {
  MaterialDesc m;
  m.name = "grey";
  m.diffuse = {rho, rho, rho};
  return m;
}

// Two width x depth rectangles sharing the edge along x at the origin: one in the plane y = 0
// (normal +y), the other turned up about that edge by `fold_degrees` (0: flat, 90: a wall
// along the floor's z = 0 edge). Each rectangle is two triangles; both normals point to the
// same (inner) side.
inline Scene folded_sheet(float width, float depth, float fold_degrees) {
  const float a = fold_degrees * float(M_PI) / 180.0f;
  Scene s;
  s.name = "folded-sheet";
  s.source = "test";
  // Floor: z from 0 to depth; the other rectangle goes from the shared edge towards -z, rising.
  s.positions = {{0, 0, 0}, {width, 0, 0}, {width, 0, depth}, {0, 0, depth},
                 {0, depth * std::sin(a), -depth * std::cos(a)}, {width, depth * std::sin(a), -depth * std::cos(a)}};
  s.indices = {0, 3, 2, 0, 2, 1,   // floor, normal +y
               0, 1, 5, 0, 5, 4};  // the folded part, normal towards +z (and +y)
  s.triangle_material.assign(4, 0);
  s.materials = {grey_material(0.5f)};
  s.lights = {LightDesc{"light", {width / 2, depth, depth / 2}, {10, 10, 10}}};
  return s;
}

// Axis-aligned cube [0, size]^3 with normals pointing outwards, 12 triangles, 8 shared vertices.
inline Scene closed_cube(float size) {
  Scene s;
  s.name = "cube";
  s.source = "test";
  for (int i = 0; i < 8; ++i) s.positions.push_back({(i & 1) * size, ((i >> 1) & 1) * size, ((i >> 2) & 1) * size});
  // Each face as two triangles, counter-clockwise seen from outside.
  const uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) s.indices.insert(s.indices.end(), {f[0], f[1], f[2], f[0], f[2], f[3]});
  s.triangle_material.assign(12, 0);
  s.materials = {grey_material(0.5f)};
  s.lights = {LightDesc{"light", {2 * size, 2 * size, 2 * size}, {10, 10, 10}}};
  return s;
}

}  // namespace pm::test

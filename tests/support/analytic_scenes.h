// Closed scenes with closed-form answers, built in code: a point light at the centre of a
// tessellated diffuse sphere, viewed from the centre.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "render/scene.h"
#include "render/scene_scale.h"

namespace pm::test {

// Icosahedron subdivided `levels` times and pushed onto the sphere; normals face inwards.
inline Scene diffuse_sphere(float radius, float albedo, int levels, Float3 light_power) {
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<Float3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                           {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<uint32_t> f = {0, 11, 5, 0, 5, 1,  0, 1, 7,   0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4,
                             11, 10, 2, 10, 7, 6, 7, 1, 8, 3, 9, 4,  3, 4, 2,  3, 2, 6, 3, 6, 8,
                             3, 8, 9,  4, 9, 5,  2, 4, 11, 6, 2, 10, 8, 6, 7,  9, 8, 1};
  auto normalise = [&](Float3 p) {
    float len = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    return Float3{p.x / len * radius, p.y / len * radius, p.z / len * radius};
  };
  for (Float3& p : v) p = normalise(p);
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoint;
    auto mid = [&](uint32_t a, uint32_t b) {
      auto key = std::minmax(a, b);
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      v.push_back(normalise({(v[a].x + v[b].x) / 2, (v[a].y + v[b].y) / 2, (v[a].z + v[b].z) / 2}));
      return midpoint[key] = uint32_t(v.size() - 1);
    };
    std::vector<uint32_t> next;
    for (size_t i = 0; i < f.size(); i += 3) {
      uint32_t a = f[i], b = f[i + 1], c = f[i + 2];
      uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    f = std::move(next);
  }
  Scene s;
  s.name = "diffuse-sphere";
  s.source = "test";
  s.positions = v;
  for (size_t i = 0; i < f.size(); i += 3) s.indices.insert(s.indices.end(), {f[i], f[i + 2], f[i + 1]});
  s.triangle_material.assign(s.indices.size() / 3, 0);
  MaterialDesc m;
  m.name = "grey";
  m.diffuse = {albedo, albedo, albedo};
  s.materials = {m};
  s.lights = {LightDesc{"centre", {0, 0, 0}, light_power}};
  s.camera.position = {0, 0, 0};
  s.camera.look_at = {0, 0, 1};
  s.camera.up = {0, 1, 0};
  s.camera.vertical_fov_degrees = 90;
  s.camera.width = 48;
  s.camera.height = 48;
  return s;
}

inline double surface_area(const Scene& s) {
  double area = 0;
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    const Float3 &a = s.positions[s.indices[3 * t]], &b = s.positions[s.indices[3 * t + 1]],
                 &c = s.positions[s.indices[3 * t + 2]];
    double e1[3] = {b.x - a.x, b.y - a.y, b.z - a.z}, e2[3] = {c.x - a.x, c.y - a.y, c.z - a.z};
    double x = e1[1] * e2[2] - e1[2] * e2[1], y = e1[2] * e2[0] - e1[0] * e2[2], z = e1[0] * e2[1] - e1[1] * e2[0];
    area += 0.5 * std::sqrt(x * x + y * y + z * z);
  }
  return area;
}

// The closed diffuse sphere lit from its centre that the progressive and --method auto tests
// render: every point's indirect radiance after two bounces is rho/pi * Phi/A * (rho + rho^2).
struct LitSphere {
  static constexpr float kRho = 0.5f, kRadius = 2.0f, kPower = 100.0f;
  Scene scene = diffuse_sphere(kRadius, kRho, 4, {kPower, kPower, kPower});
  double expected = kRho / double(PM_PI) * kPower / measure_scene(scene).surface_area * (kRho + kRho * kRho);
};

inline const LitSphere& lit_sphere() {
  static const LitSphere s;
  return s;
}

}  // namespace pm::test

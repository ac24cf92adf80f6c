// Builds the area-light records of render/scene_emitters.h in double precision, and defines
// the Scene helpers of render/scene.h that concern lights (has_emitters, light_emitted_fraction).
#include "render/scene_emitters.h"

#include <cmath>

namespace pm {

namespace {

struct Vec3d {
  double x, y, z;
};

Vec3d corner(const Scene& scene, size_t t, int k) {
  const Float3& p = scene.positions[scene.indices[3 * t + size_t(k)]];
  return {p.x, p.y, p.z};
}

double triangle_area(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Vec3d u{b.x - a.x, b.y - a.y, b.z - a.z}, v{c.x - a.x, c.y - a.y, c.z - a.z};
  const double x = u.y * v.z - u.z * v.y, y = u.z * v.x - u.x * v.z, z = u.x * v.y - u.y * v.x;
  return 0.5 * std::sqrt(x * x + y * y + z * z);
}

float4 point4(const Vec3d& p, float w) { return float4{float(p.x), float(p.y), float(p.z), w}; }

}  // namespace

SceneEmitters build_scene_emitters(const Scene& scene) {
  SceneEmitters out;
  if (!scene.has_emitters()) return out;
  for (const MaterialDesc& m : scene.materials) {
    const Float3& e = m.emission;
    out.material_emission.push_back(float4{e.x, e.y, e.z, float((double(e.x) + e.y + e.z) / 3.0)});
  }
  std::vector<double> power;
  for (size_t t = 0; t < scene.triangle_count(); ++t) {
    const MaterialDesc& m = scene.materials[scene.triangle_material[t]];
    if (!m.emits()) continue;
    const Vec3d a = corner(scene, t, 0), b = corner(scene, t, 1), c = corner(scene, t, 2);
    const double area = triangle_area(a, b, c);
    if (!(area > 0)) continue;
    const double mean = (double(m.emission.x) + m.emission.y + m.emission.z) / 3.0;
    out.records.push_back(point4(a, 0.0f));
    out.records.push_back(point4(b, 0.0f));
    out.records.push_back(point4(c, float(area)));
    out.records.push_back(float4{m.emission.x, m.emission.y, m.emission.z, float(mean)});
    power.push_back(M_PI * area * mean);
    out.power += power.back();
    out.power_rgb_sum += 3.0 * power.back();
  }
  out.count = uint32_t(power.size());
  // Cumulative shares; the last is exactly 1 so that every u in [0, 1) finds an emitter.
  double running = 0;
  for (size_t i = 0; i < power.size(); ++i) {
    running += power[i];
    out.records[PM_EMITTER_FLOAT4S * i].w = i + 1 == power.size() ? 1.0f : float(running / out.power);
  }
  return out;
}

bool Scene::has_emitters() const {
  for (uint32_t m : triangle_material)
    if (m < materials.size() && materials[m].emits()) return true;
  return false;
}

bool Scene::has_light() const {
  for (const LightDesc& l : lights)
    if (l.power.x > 0 || l.power.y > 0 || l.power.z > 0) return true;
  return has_emitters() || environment.emits();
}

double light_emitted_fraction(const LightDesc& light) {
  if (light.type != LightType::spot) return 1.0;
  const double ci = std::cos(double(light.inner_cone)), co = std::cos(double(light.outer_cone));
  return 0.5 * ((1.0 - ci) + (ci - co) / 3.0);
}

}  // namespace pm

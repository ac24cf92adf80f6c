// Scene measures and method statistics: the small shared pieces of the method interface.
#include "render/indirect_method.h"

#include <algorithm>
#include <cmath>

namespace pm {

SceneMeasures measure_scene(const Scene& scene) {
  SceneMeasures m;
  if (scene.positions.empty()) return m;
  m.lo = m.hi = scene.positions[0];
  for (const Float3& p : scene.positions) {
    m.lo = {std::min(m.lo.x, p.x), std::min(m.lo.y, p.y), std::min(m.lo.z, p.z)};
    m.hi = {std::max(m.hi.x, p.x), std::max(m.hi.y, p.y), std::max(m.hi.z, p.z)};
  }
  const double dx = double(m.hi.x) - m.lo.x, dy = double(m.hi.y) - m.lo.y, dz = double(m.hi.z) - m.lo.z;
  m.diagonal = std::sqrt(dx * dx + dy * dy + dz * dz);
  for (size_t t = 0; t < scene.triangle_count(); ++t) {
    const Float3& a = scene.positions[scene.indices[3 * t]];
    const Float3& b = scene.positions[scene.indices[3 * t + 1]];
    const Float3& c = scene.positions[scene.indices[3 * t + 2]];
    const double e1[3] = {double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z};
    const double e2[3] = {double(c.x) - a.x, double(c.y) - a.y, double(c.z) - a.z};
    const double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2],
                 cz = e1[0] * e2[1] - e1[1] * e2[0];
    m.surface_area += 0.5 * std::sqrt(cx * cx + cy * cy + cz * cz);
  }
  return m;
}

void MethodStats::set(const std::string& name, double value) {
  for (Entry& e : entries)
    if (e.name == name) {
      e.value = value;
      return;
    }
  entries.push_back({name, value});
}

bool MethodStats::has(const std::string& name) const {
  return std::any_of(entries.begin(), entries.end(), [&](const Entry& e) { return e.name == name; });
}

double MethodStats::get(const std::string& name, double fallback) const {
  for (const Entry& e : entries)
    if (e.name == name) return e.value;
  return fallback;
}

}  // namespace pm

// A scene's bounds, diagonal, surface area and ray-offset scale (render/scene_scale.h).
#include "render/scene_scale.h"

#include <algorithm>
#include <cmath>

#include "kernels/common/compat_host.h"
#include "kernels/common/vec3.h"
#include "kernels/common/ray.h"

namespace pm {

SceneBounds scene_bounds(const Scene& scene) {
  SceneBounds b;
  if (scene.positions.empty()) return b;
  b.lo = b.hi = scene.positions[0];
  for (const Float3& p : scene.positions) {
    b.lo = {std::min(b.lo.x, p.x), std::min(b.lo.y, p.y), std::min(b.lo.z, p.z)};
    b.hi = {std::max(b.hi.x, p.x), std::max(b.hi.y, p.y), std::max(b.hi.z, p.z)};
  }
  return b;
}

double scene_diagonal(const Scene& scene) {
  if (scene.positions.empty()) return 1.0;
  const SceneBounds b = scene_bounds(scene);
  const double dx = double(b.hi.x) - b.lo.x, dy = double(b.hi.y) - b.lo.y, dz = double(b.hi.z) - b.lo.z;
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

double scene_surface_area(const Scene& scene) {
  double area = 0;
  for (size_t t = 0; t < scene.triangle_count(); ++t) {
    const Float3& a = scene.positions[scene.indices[3 * t]];
    const Float3& b = scene.positions[scene.indices[3 * t + 1]];
    const Float3& c = scene.positions[scene.indices[3 * t + 2]];
    const double e1[3] = {double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z};
    const double e2[3] = {double(c.x) - a.x, double(c.y) - a.y, double(c.z) - a.z};
    const double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2],
                 cz = e1[0] * e2[1] - e1[1] * e2[0];
    area += 0.5 * std::sqrt(cx * cx + cy * cy + cz * cz);
  }
  return area;
}

float scene_ray_epsilon(const Scene& scene) {
  const SceneBounds b = scene_bounds(scene);
  const float largest = std::max(vec3_max_abs(vec3(b.lo.x, b.lo.y, b.lo.z)), vec3_max_abs(vec3(b.hi.x, b.hi.y, b.hi.z)));
  return PM_RAY_OFFSET_RELATIVE * largest;
}

SceneMeasures measure_scene(const Scene& scene) {
  SceneMeasures m;
  m.bounds = scene_bounds(scene);
  m.diagonal = scene_diagonal(scene);
  m.surface_area = scene_surface_area(scene);
  m.ray_epsilon = scene_ray_epsilon(scene);
  return m;
}

}  // namespace pm

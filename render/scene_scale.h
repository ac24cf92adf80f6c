// A scene's physical size as the host derives settings from it: its bounds and diagonal (default
// r_max and gather radius), its surface area (T_auto, automatic smoothing) and the scale of the
// secondary rays' origin offsets (LaunchParams::ray_epsilon, kernels/common/ray.h).
#pragma once

#include "render/scene.h"

namespace pm {

struct SceneBounds {
  Float3 lo, hi;  // of every vertex; both zero for a scene without vertices
};

SceneBounds scene_bounds(const Scene& scene);
// Length of the bounds' diagonal, metres; 1 for a scene without vertices.
double scene_diagonal(const Scene& scene);
// Sum of the triangles' areas, square metres (degenerate triangles add nothing).
double scene_surface_area(const Scene& scene);
// LaunchParams::ray_epsilon: PM_RAY_OFFSET_RELATIVE (2^-17) times the largest coordinate
// magnitude of the scene's vertices, the part of a ray offset that covers rounding in the
// triangles' planes. 0 for a scene without vertices.
float scene_ray_epsilon(const Scene& scene);

// All of the above, measured once per renderer for the methods (render/indirect_method.h).
struct SceneMeasures {
  SceneBounds bounds;
  double diagonal = 1;      // metres
  double surface_area = 0;  // square metres
  float ray_epsilon = 0;
};
SceneMeasures measure_scene(const Scene& scene);

}  // namespace pm

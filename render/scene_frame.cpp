// Evaluation of a scene's camera and light tracks at a frame, and the per-sequence facts built
// on it (light runs for reuse over camera-only motion, camera checks).
#include "render/scene_frame.h"

#include <cmath>
#include <cstring>

namespace pm {

namespace {

Float3 to_float3(const std::array<float, 3>& v) { return Float3{v[0], v[1], v[2]}; }

bool same_bits(const Float3& a, const Float3& b) { return std::memcmp(&a, &b, sizeof(Float3)) == 0; }

float length(const Float3& v) { return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }

}  // namespace

double frame_time(const Scene& scene, int frame) { return double(frame) / scene.animation.frame_rate; }

CameraDesc camera_at_frame(const Scene& scene, int frame) {
  CameraDesc camera = scene.camera;
  if (!scene.animation.enabled) return camera;
  const CameraAnimation& a = scene.animation.camera;
  const double t = frame_time(scene, frame);
  if (!a.position.empty()) camera.position = to_float3(a.position.evaluate(t));
  if (!a.look_at.empty()) camera.look_at = to_float3(a.look_at.evaluate(t));
  if (!a.up.empty()) camera.up = to_float3(a.up.evaluate(t));
  if (!a.vertical_fov.empty()) camera.vertical_fov_degrees = a.vertical_fov.evaluate(t)[0];
  return camera;
}

std::vector<LightDesc> lights_at_frame(const Scene& scene, int frame) {
  std::vector<LightDesc> lights = scene.lights;
  if (!scene.animation.enabled) return lights;
  const double t = frame_time(scene, frame);
  for (size_t i = 0; i < lights.size() && i < scene.animation.lights.size(); ++i) {
    const LightAnimation& a = scene.animation.lights[i];
    if (!a.position.empty()) lights[i].position = to_float3(a.position.evaluate(t));
    if (!a.power.empty()) lights[i].power = to_float3(a.power.evaluate(t));
    if (!a.direction.empty()) lights[i].direction = to_float3(a.direction.evaluate(t));
  }
  return lights;
}

bool same_lights(const std::vector<LightDesc>& a, const std::vector<LightDesc>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (!same_bits(a[i].position, b[i].position) || !same_bits(a[i].power, b[i].power) || a[i].type != b[i].type ||
        !same_bits(a[i].direction, b[i].direction) || std::memcmp(&a[i].inner_cone, &b[i].inner_cone, sizeof(float)) != 0 ||
        std::memcmp(&a[i].outer_cone, &b[i].outer_cone, sizeof(float)) != 0)
      return false;
  return true;
}

int light_run_start(const Scene& scene, int frame) {
  if (!scene.animation.enabled || frame <= scene.animation.first_frame) return frame;
  bool animated = false;
  for (const LightAnimation& a : scene.animation.lights) animated |= !a.empty();
  if (!animated) return scene.animation.first_frame;
  const std::vector<LightDesc> lights = lights_at_frame(scene, frame);
  int start = frame;
  while (start > scene.animation.first_frame && same_lights(lights_at_frame(scene, start - 1), lights)) --start;
  return start;
}

std::string camera_problem(const CameraDesc& camera) {
  const Float3 view{camera.look_at.x - camera.position.x, camera.look_at.y - camera.position.y,
                    camera.look_at.z - camera.position.z};
  const float view_length = length(view);
  if (!(view_length > 0)) return "look_at equals position (no view direction)";
  const float up_length = length(camera.up);
  if (!(up_length > 0)) return "up is the zero vector";
  const Float3 cross{view.y * camera.up.z - view.z * camera.up.y, view.z * camera.up.x - view.x * camera.up.z,
                     view.x * camera.up.y - view.y * camera.up.x};
  if (!(length(cross) > 1e-6f * view_length * up_length)) return "up is parallel to the view direction";
  if (!(camera.vertical_fov_degrees > 0 && camera.vertical_fov_degrees < 180))
    return "vertical_fov " + std::to_string(camera.vertical_fov_degrees) + " is outside (0, 180) degrees";
  return "";
}

}  // namespace pm

// Runs the shared camera-pass stage function on the host, pixel by pixel, as a reference for
// what every backend must produce from the same kernel source.
#pragma once

#include <vector>

#include "kernels/common/compat_host.h"
#include "kernels/common/camera_pass.h"
#include "render/renderer.h"
#include "render/scene_bvh.h"
#include "render/scene_scale.h"

namespace pm::test {

inline std::vector<float4> render_direct_on_host(const Scene& scene, int width, int height, int mirror_depth) {
  SceneBvh bvh = build_scene_bvh(scene);
  std::vector<Material> materials = to_device_materials(scene);
  std::vector<PointLight> lights = to_device_lights(scene.lights);
  const size_t pixels = size_t(width) * height;
  const size_t records = pixels * (mirror_depth + 1);
  std::vector<float4> position(records), normal(records), outgoing(records), weight(records), direct(pixels);

  KernelGlobals kg{};
  kg.scene_nodes = bvh.nodes.data();
  kg.triangles = bvh.triangles.data();
  kg.materials = materials.data();
  kg.lights = lights.data();
  kg.shade_position = position.data();
  kg.shade_normal = normal.data();
  kg.shade_outgoing = outgoing.data();
  kg.shade_weight = weight.data();
  kg.film_direct = direct.data();

  LaunchParams p{};
  p.camera = make_camera_params(scene.camera, width, height);
  p.width = uint32_t(width);
  p.height = uint32_t(height);
  p.light_count = uint32_t(lights.size());
  p.ray_epsilon = scene_ray_epsilon(scene);
  p.mirror_depth = uint32_t(mirror_depth);
  for (uint32_t i = 0; i < pixel_work_items(p.width, p.height); ++i) kernel_camera_pass(&kg, &p, i);
  return direct;
}

}  // namespace pm::test

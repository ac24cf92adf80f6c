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

// The camera pass's inputs and outputs on the host: the scene's device arrays, the shading
// records and the direct film, with kg and p pointing at them. run() fills them pixel by pixel.
struct HostCameraPass {
  HostCameraPass(const Scene& scene, int width, int height, int mirror_depth)
      : bvh(build_scene_bvh(scene)),
        materials(to_device_materials(scene)),
        lights(to_device_lights(scene.lights)),
        pixels(size_t(width) * size_t(height)) {
    const size_t records = pixels * size_t(mirror_depth + 1);
    hits.resize(records);
    direct.resize(pixels);
    kg.scene_nodes = bvh.nodes.data();
    kg.triangles = bvh.triangles.data();
    kg.materials = materials.data();
    kg.lights = lights.data();
    kg.shade_hit = hits.data();
    kg.film_direct = direct.data();
    p.camera = make_camera_params(scene.camera, width, height);
    p.width = uint32_t(width);
    p.height = uint32_t(height);
    p.light_count = uint32_t(lights.size());
    p.ray_epsilon = scene_ray_epsilon(scene);
    p.mirror_depth = uint32_t(mirror_depth);
  }
  HostCameraPass(const HostCameraPass&) = delete;  // kg points into this object
  HostCameraPass& operator=(const HostCameraPass&) = delete;

  void run() {
    for (uint32_t i = 0; i < pixel_work_items(p.width, p.height); ++i) kernel_camera_pass(&kg, &p, i);
  }

  SceneBvh bvh;
  std::vector<Material> materials;
  std::vector<PointLight> lights;
  size_t pixels;
  std::vector<float2> hits;  // per shading point: distance along its ray, triangle (camera_pass.h)
  std::vector<float4> direct;
  KernelGlobals kg{};
  LaunchParams p{};
};

inline std::vector<float4> render_direct_on_host(const Scene& scene, int width, int height, int mirror_depth) {
  HostCameraPass pass(scene, width, height, mirror_depth);
  pass.run();
  return pass.direct;
}

}  // namespace pm::test

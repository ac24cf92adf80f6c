// A scene's refined radiosity mesh and elements in host memory, bound into a KernelGlobals, so
// that host tests call the radiosity stage functions (kernels/common/radiosity_*.h) on them.
#pragma once

#include <cmath>
#include <vector>

#include "kernels/common/compat_host.h"
#include "kernels/common/kernel_globals.h"
#include "render/radiosity/mesh_refinement.h"
#include "render/radiosity/radiosity_elements.h"
#include "render/renderer.h"
#include "render/scene_bvh.h"

namespace pm::test {

struct HostMesh {
  SceneBvh bvh;
  RefinedMesh mesh;
  RadiosityElements el;
  std::vector<Material> materials;
  std::vector<PointLight> lights;
  std::vector<float4> radiance, irradiance;
  KernelGlobals kg{};
  LaunchParams p{};

  HostMesh(const Scene& scene, double max_edge, float feature_angle, bool two_sided)
      : bvh(build_scene_bvh(scene)), mesh(refine_mesh(scene, max_edge)),
        el(build_radiosity_elements(scene, mesh, feature_angle, two_sided)) {
    materials = to_device_materials(scene);
    lights = to_device_lights(scene.lights);
    radiance.assign(2 * el.count(), float4{0, 0, 0, 0});
    irradiance.assign(2 * el.count(), float4{0, 0, 0, 0});
    kg.scene_nodes = bvh.nodes.data();
    kg.triangles = bvh.triangles.data();
    kg.materials = materials.data();
    kg.lights = lights.data();
    kg.rad_elements = el.data.data();
    kg.rad_element_ranges = el.ranges.data();
    kg.rad_adjacency = el.adjacency.data();
    kg.rad_smooth_weights = el.smooth_weights.data();
    kg.rad_tree = mesh.tree.data();
    kg.rad_triangles = el.triangles.data();
    kg.rad_radiance = radiance.data();
    kg.rad_irradiance = irradiance.data();
    p.element_count = uint32_t(el.count());
    p.light_count = uint32_t(lights.size());
    p.feature_cos = std::cos(feature_angle * float(M_PI) / 180.0f);
  }
};

}  // namespace pm::test

// A scene's BVH built on the host as the device gets it, and the kernels' view of it
// (KernelGlobals with the scene nodes and triangles), for unit tests that call kernel functions
// that trace rays or query the scene on the CPU.
#pragma once

#include "kernels/common/compat_host.h"
#include "kernels/common/kernel_globals.h"
#include "render/scene_bvh.h"

namespace pm::test {

struct HostScene {
  SceneBvh bvh;
  KernelGlobals kg{};
  explicit HostScene(const Scene& scene) : bvh(build_scene_bvh(scene)) {
    kg.scene_nodes = bvh.nodes.data();
    kg.triangles = bvh.triangles.data();
  }
};

}  // namespace pm::test

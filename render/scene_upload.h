// What a renderer uploads of its scene, prepared on the host once: the BVH with its triangles in
// leaf order, the packed textures, the device materials, the area lights' records and the
// environment's distribution. A renderer prepares its own; renderers of one scene on one device
// (the candidates of --method auto's race, render/method_race.h) share one, so that the scene's
// BVH is built once rather than once per candidate (Conference: 371 ms each on the H200's host).
#pragma once

#include <memory>
#include <vector>

#include "render/kernel_abi.h"
#include "render/scene.h"
#include "render/scene_bvh.h"
#include "render/scene_emitters.h"
#include "render/scene_environment.h"
#include "render/scene_textures.h"
#include "render/startup_timing.h"

namespace pm {

struct SceneUpload {
  SceneBvh bvh;
  DeviceTextures textures;  // empty for an untextured scene
  std::vector<Material> materials;
  SceneEmitters emitters;               // no records without emitting materials
  EnvironmentDistribution environment;  // texels and CDFs for a map only
};

// Builds the upload; records its steps ("BVH build", "textures and materials") on clock.
std::shared_ptr<const SceneUpload> prepare_scene_upload(const Scene& scene, StepClock& clock,
                                                        std::vector<StartupStep>* steps);

}  // namespace pm

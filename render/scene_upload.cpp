// The host side of a scene's upload (scene_upload.h).
#include "render/scene_upload.h"

#include <string>

#include "render/renderer.h"  // to_device_materials

namespace pm {

std::shared_ptr<const SceneUpload> prepare_scene_upload(const Scene& scene, StepClock& clock,
                                                        std::vector<StartupStep>* steps) {
  auto upload = std::make_shared<SceneUpload>();
  upload->bvh = build_scene_bvh(scene);
  steps->push_back({"BVH build", clock.lap_ms(), std::to_string(upload->bvh.nodes.size()) + " nodes"});
  upload->textures = pack_scene_textures(scene, upload->bvh);
  upload->materials = to_device_materials(scene);
  upload->emitters = build_scene_emitters(scene);
  upload->environment = build_environment_distribution(scene.environment);
  steps->push_back({"textures and materials", clock.lap_ms(), std::to_string(scene.images.size()) + " images"});
  return upload;
}

}  // namespace pm

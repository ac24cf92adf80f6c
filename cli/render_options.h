// The options every rendering command shares (render, bench): scene, device, resolution and the
// photon-mapping settings, registered once and turned into a Scene and RenderSettings once.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "render/renderer.h"
#include "render/scene.h"

namespace pm::cli {

struct RenderOptions {
  std::string scene_path;  // empty: the built-in Cornell box
  std::string backend = "auto";
  int device = 0;
  std::string resolution;
  int mirror_depth = 1;
  uint32_t seed = 1;
  PhotonSettings photons;
  std::string estimator = "pd";
  std::string kernel = "constant";
  std::string leaf = "auto";
  std::string smoothing = "auto";
  std::string photon_bvh = "lbvh";
};

void add_render_options(CLI::App* cmd, RenderOptions& options);

// The scene the options name, and the settings they describe; InputError on bad values.
Scene load_scene(const RenderOptions& options);
RenderSettings render_settings(const RenderOptions& options);

}  // namespace pm::cli

// The options every rendering command shares (render, bench): scene, device, resolution, passes,
// the method and each method's own options, registered once and turned into a Scene and
// validated RenderSettings once.
#pragma once

#include <CLI/CLI.hpp>
#include <map>
#include <memory>
#include <string>

#include "cli/method_options.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "scene_io/scene_file.h"

namespace pm::cli {

struct RenderOptions {
  std::string scene_path;  // empty: the built-in Cornell box
  std::string backend = "auto";
  int device = 0;
  std::string resolution;
  int mirror_depth = 1;
  uint32_t seed = 1;
  uint32_t passes = 1;
  uint32_t control_paths = 1024;  // the error estimate's bias control (RenderSettings::control_paths)
  uint32_t area_light_samples = 16;  // RenderSettings::area_light_samples
  std::string method = "photon";
  bool no_reuse = false;
  // --environment: "r,g,b" (a constant radiance) or an OpenEXR lat-long map, replacing the scene's
  // environment; empty: the scene's own. Scale and turn apply to a map only.
  std::string environment;
  double environment_scale = 1.0;
  double environment_rotation = 0.0;
  CLI::Option* environment_scale_option = nullptr;
  CLI::Option* environment_rotation_option = nullptr;
  CLI::Option* passes_option = nullptr;  // given on the command line (a budget's cap then)
  std::map<std::string, std::shared_ptr<MethodOptions>> method_options;  // by method name
};

void add_render_options(CLI::App* cmd, RenderOptions& options);

// The scene the options name (with --environment's environment, if given), and the settings they
// describe; SettingError/InputError on bad values. report as for load_scene_file. budgeted: a
// --time or --target-error budget stops the passes (MethodOptions::settings).
Scene load_scene(const RenderOptions& options, SceneLoadReport* report = nullptr);
RenderSettings render_settings(const RenderOptions& options, bool budgeted = false);
// Every method's candidates for --method auto's race, validated (MethodOptions::candidates).
std::vector<RaceCandidate> method_candidates(const RenderOptions& options);

}  // namespace pm::cli

// Registration and interpretation of the shared rendering options, and the parsers of --resolution
// and --frames that several commands share.
#include "cli/render_options.h"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/number_parsing.h"
#include "render/errors.h"

#include "scene_io/cornell_box.h"
#include "scene_io/frame_spec.h"
#include "scene_io/environment_json.h"
#include "scene_io/scene_file.h"

namespace pm::cli {

void add_render_options(CLI::App* cmd, RenderOptions& o) {
  cmd->add_option("scene", o.scene_path, "Scene file (.json, .gltf or .glb; see docs/scene-format.md); default: the Cornell box");
  cmd->add_option("--backend", o.backend, "auto, cuda or opencl (auto: CUDA when a CUDA device exists)")
      ->check(CLI::IsMember({"auto", "cuda", "opencl"}));
  cmd->add_option("--device", o.device, "Device index within the backend (see 'pmrender devices')")
      ->transform(integer_in(0, 1023));
  cmd->add_option("--resolution", o.resolution, "WIDTHxHEIGHT, overrides the scene camera's");
  cmd->add_option("--mirror-depth", o.mirror_depth, "Perfect-mirror bounces followed from the eye")
      ->capture_default_str()->transform(any_int32());
  cmd->add_option("--seed", o.seed, "Random seed")->capture_default_str()->transform(any_unsigned32());
  o.passes_option = cmd->add_option("--passes", o.passes, "Passes of the indirect-light method per frame, summed in the film "
                                        "(photon mapping: independent photon batches; memory is one pass's)")
      ->capture_default_str()->transform(any_unsigned32());
  cmd->add_option("--control-paths", o.control_paths,
                  "Paths per control pixel of the frame's error estimate (a sparse path-traced control beside "
                  "biased methods; docs/accuracy.md), grown up to 16x (within the frame's own time) where it cannot resolve the error; 0: the "
                  "estimate sees the noise between passes only")
      ->capture_default_str()->transform(integer_in(0, 65536));
  cmd->add_option("--area-light-samples", o.area_light_samples,
                  "Light samples of the emitting surfaces and of the environment per pixel and mirror depth in the "
                  "direct light (and per element in radiosity's light links)")
      ->capture_default_str()->transform(integer_in(1, 65536));
  std::string method_help = "Indirect-light method:";
  for (const MethodEntry& m : methods()) method_help += std::string(" ") + m.name + " (" + m.summary + ")";
  method_help += " or auto (under --time or --target-error: the methods race on the frame and the one forecast "
                 "to meet the budget best goes on; docs/method-auto.md)";
  cmd->add_option("--method", o.method, method_help)->capture_default_str()->check(CLI::IsMember(method_names(true)));
  cmd->add_flag("--no-photon-reuse,--no-reuse", o.no_reuse,
                "Compute the lighting of every frame keyed by its own frame number, also over camera-only motion");
  cmd->add_option("--environment", o.environment,
                  "Light from every direction, replacing the scene's: R,G,B (a constant radiance, W sr^-1 m^-2) or "
                  "an OpenEXR lat-long map (docs/scene-format.md, \"Environment\")");
  o.environment_scale_option =
      cmd->add_option("--environment-scale", o.environment_scale, "Factor on every texel of the --environment map")
          ->capture_default_str()->transform(finite_in(0, 1e30));
  o.environment_rotation_option =
      cmd->add_option("--environment-rotation", o.environment_rotation,
                      "Degrees the --environment map turns about +y (right-handed)")
          ->capture_default_str()->transform(finite_in(-3600, 3600));
  for (const MethodEntry& m : methods()) o.method_options[m.name] = m.add_options(cmd);
}

namespace {

// "r,g,b": three decimal numbers >= 0 (InputError naming --environment otherwise).
Float3 parse_radiance(const std::string& text) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (size_t comma; (comma = text.find(',', start)) != std::string::npos; start = comma + 1)
    parts.push_back(text.substr(start, comma - start));
  parts.push_back(text.substr(start));
  if (parts.size() != 3)
    throw InputError("--environment: expected R,G,B (three numbers >= 0) or an OpenEXR file, got '" + text + "'");
  const double limit = double(std::numeric_limits<float>::max());
  return Float3{float(parse_finite("--environment", parts[0], 0, limit)),
                float(parse_finite("--environment", parts[1], 0, limit)),
                float(parse_finite("--environment", parts[2], 0, limit))};
}

// The environment --environment asks for; type none when it is not given.
EnvironmentDesc command_line_environment(const RenderOptions& o) {
  EnvironmentDesc env;
  const bool map_options = o.environment_scale_option->count() > 0 || o.environment_rotation_option->count() > 0;
  const char* map_option = o.environment_scale_option->count() > 0 ? "environment-scale" : "environment-rotation";
  if (o.environment.empty()) {
    if (map_options) throw SettingError(map_option, "applies to an --environment map; give --environment FILE.exr");
    return env;
  }
  // A comma makes it a radiance; anything else names a file.
  if (o.environment.find(',') != std::string::npos) {
    env.type = EnvironmentType::constant;
    env.radiance = parse_radiance(o.environment);
    if (map_options)
      throw SettingError(map_option, "applies to an --environment map, not to a constant radiance");
    return env;
  }
  return read_environment_map(o.environment, float(o.environment_scale), float(o.environment_rotation), "--environment");
}

}  // namespace

Scene load_scene(const RenderOptions& o, SceneLoadReport* report) {
  const EnvironmentDesc env = command_line_environment(o);
  const EnvironmentDesc* override_env = env.type == EnvironmentType::none ? nullptr : &env;
  if (!o.scene_path.empty()) return load_scene_file(o.scene_path, report, override_env);
  Scene scene = builtin_cornell_box();
  if (override_env) scene.environment = env;
  return scene;
}

RenderSettings render_settings(const RenderOptions& o, bool budgeted) {
  RenderSettings settings;
  settings.mirror_depth = o.mirror_depth;
  settings.seed = o.seed;
  settings.passes = o.passes;
  settings.control_paths = o.control_paths;
  settings.area_light_samples = o.area_light_samples;
  settings.reuse_lighting = !o.no_reuse;
  if (!o.resolution.empty()) parse_resolution(o.resolution, &settings.width, &settings.height);
  if (o.method == kAutoMethod) {
    if (!budgeted)
      throw SettingError("method", "auto races the methods under a budget, which only pmrender render takes: "
                                   "--time SECONDS or --target-error E");
    if (o.control_paths == 0)
      throw SettingError("control-paths", "0 leaves --method auto nothing to measure the methods with; give it paths");
    settings.method = method_candidates(o).front().method;  // the race's winner replaces it (render/method_race.h)
  } else {
    settings.method = o.method_options.at(o.method)->settings(budgeted);
  }
  settings.validate();
  return settings;
}

std::vector<RaceCandidate> method_candidates(const RenderOptions& o) {
  std::vector<RaceCandidate> all;
  for (const MethodEntry& m : methods())
    for (RaceCandidate& c : o.method_options.at(m.name)->candidates(m.name)) all.push_back(std::move(c));
  return all;
}

std::vector<int> parse_frames_option(const std::string& spec, int first, int last) {
  try {
    return parse_frame_spec(spec, first, last);
  } catch (const InputError& e) {
    throw InputError(std::string("--frames: ") + e.what());
  }
}

void parse_resolution(const std::string& text, int* width, int* height) {
  const size_t x = text.find_first_of("xX");
  try {
    if (x == std::string::npos) throw InputError("");
    *width = int(parse_unsigned("--resolution", text.substr(0, x), 1, 16384));
    *height = int(parse_unsigned("--resolution", text.substr(x + 1), 1, 16384));
  } catch (const InputError&) {
    throw InputError("--resolution: expected WIDTHxHEIGHT with each a whole number from 1 to 16384, got '" + text +
                     "'");
  }
}

}  // namespace pm::cli

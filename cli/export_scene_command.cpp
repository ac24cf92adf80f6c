// `pmrender export-scene [SCENE] -o OUT.json`: writes the scene as pmrender loaded it (metres,
// one OBJ per material, the camera and lights of one frame) for other renderers: the
// independent-renderer tests convert this file for Mitsuba 3 (tests/mitsuba/).
#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "render/errors.h"
#include "render/scene_frame.h"
#include "scene_io/cornell_box.h"
#include "scene_io/scene_export.h"
#include "scene_io/scene_file.h"

namespace pm::cli {

namespace {

struct ExportOptions {
  std::string scene_path;
  std::string output;
  int frame = 0;
};

int run_export(const ExportOptions& o) {
  if (o.output.size() < 6 || o.output.substr(o.output.size() - 5) != ".json")
    throw InputError("-o: expected a file name ending in .json, got '" + o.output + "'");
  const Scene scene = o.scene_path.empty() ? builtin_cornell_box() : load_scene_file(o.scene_path);
  // The export's JSON materials are plain colours: a textured scene would come out different.
  if (scene.has_textures())
    throw InputError(scene.source + ": textures and alpha masks cannot be exported (export-scene writes plain " +
                     "JSON materials, and the other renderer would see a different scene)");
  const std::string problem = camera_problem(camera_at_frame(scene, o.frame));
  if (!problem.empty()) throw InputError(scene.source + ": camera at frame " + std::to_string(o.frame) + ": " + problem);
  export_scene(scene, o.frame, o.output);
  std::printf("wrote %s (%zu triangles, %zu materials, %zu lights)\n", o.output.c_str(), scene.triangle_count(),
              scene.materials.size(), scene.lights.size());
  return 0;
}

}  // namespace

Run add_export_scene_command(CLI::App& app) {
  auto options = std::make_shared<ExportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "export-scene", "Write the scene as loaded (metres, one OBJ per material) for other renderers and tests");
  cmd->add_option("scene", options->scene_path, "Scene file; default: the built-in Cornell box");
  cmd->add_option("-o,--output", options->output, "The JSON file to write; the OBJ files go beside it")->required();
  cmd->add_option("--frame", options->frame, "Frame whose camera and lights to write")->check(CLI::NonNegativeNumber);
  return [options] { return run_export(*options); };
}

}  // namespace pm::cli

// `pmrender render [SCENE]`: loads the scene (or the built-in Cornell box), opens the device,
// renders and writes the frame as OpenEXR (temporary name, then rename).
#include <cstdio>
#include <memory>
#include <sstream>

#include "cli/commands.h"
#include "cli/render_options.h"
#include "render/device.h"
#include "render/errors.h"
#include "render/exr_io.h"
#include "render/output_pattern.h"
#include "render/preview_png.h"
#include "render/renderer.h"

namespace pm::cli {

namespace {

struct RenderCommandOptions {
  RenderOptions render;
  std::string output;
  bool full_float = false;
  std::string preview;
  int frame = 0;
  bool quiet = false;
};

int run_render(const RenderCommandOptions& o) {
  Scene scene = load_scene(o.render);
  RenderSettings settings = render_settings(o.render);
  if (!o.preview.empty() && !preview_available())
    throw InputError("--preview needs OpenImageIO, which this build does not have");
  const std::string pattern = o.output.empty() ? default_output_pattern(scene.name) : o.output;
  const std::string path = expand_output_pattern(pattern, o.frame);

  std::unique_ptr<Device> device = create_device(o.render.backend, o.render.device);
  Renderer renderer(*device, scene, settings);
  FrameStats stats;
  FrameImage image = renderer.render_frame(o.frame, &stats);
  if (stats.repaired_pixels > 0)
    std::fprintf(stderr, "pmrender: warning: %d pixel(s) were not finite and were written as black\n",
                 stats.repaired_pixels);

  const DeviceInfo& info = device->info();
  image.attributes = {{"pmrender/version", PMRENDER_VERSION},
                      {"pmrender/scene", scene.name + " (" + scene.source + ")"},
                      {"pmrender/frame", std::to_string(o.frame)},
                      {"pmrender/backend", info.backend},
                      {"pmrender/device", info.name},
                      {"pmrender/settings", settings.describe()},
                      {"pmrender/render_ms", std::to_string(stats.render_ms)}};
  write_exr(path, image, o.full_float);
  if (!o.preview.empty()) write_preview_png(o.preview, image);
  if (!o.quiet)
    std::printf("wrote %s (%dx%d, %s: %s, %.2f ms)\n", path.c_str(), image.width, image.height, info.backend.c_str(),
                info.name.c_str(), stats.render_ms);
  return 0;
}

}  // namespace

void parse_resolution(const std::string& text, int* width, int* height) {
  std::istringstream in(text);
  int w = 0, h = 0;
  char x = 0;
  std::string rest;
  if (!(in >> w >> x >> h) || (x != 'x' && x != 'X') || (in >> rest) || w <= 0 || h <= 0 || w > 16384 ||
      h > 16384)
    throw InputError("--resolution: expected WIDTHxHEIGHT with each from 1 to 16384, got '" + text + "'");
  *width = w;
  *height = h;
}

Run add_render_command(CLI::App& app) {
  auto options = std::make_shared<RenderCommandOptions>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene to OpenEXR (default: the built-in Cornell box)");
  add_render_options(cmd, options->render);
  cmd->add_option("-o,--output", options->output, "Output pattern; runs of # are the zero-padded frame number")
      ->default_str("out/<scene>_####.exr");
  cmd->add_flag("--float", options->full_float, "Write 32-bit float channels instead of half");
  cmd->add_option("--preview", options->preview, "Also write a tone-mapped PNG here (needs OpenImageIO)");
  cmd->add_option("--frame", options->frame, "Frame number")->check(CLI::NonNegativeNumber);
  cmd->add_flag("-q,--quiet", options->quiet, "Print nothing on success");
  return [options] { return run_render(*options); };
}

}  // namespace pm::cli

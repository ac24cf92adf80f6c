// `pmrender render [SCENE]`: loads the scene (or the built-in Cornell box), opens the device,
// renders and writes the frame as OpenEXR (temporary name, then rename).
#include <cstdio>
#include <memory>
#include <sstream>

#include "cli/commands.h"
#include "render/device.h"
#include "render/errors.h"
#include "render/exr_io.h"
#include "render/output_pattern.h"
#include "render/preview_png.h"
#include "render/renderer.h"
#include "scene_io/cornell_box.h"
#include "scene_io/scene_file.h"

namespace pm::cli {

namespace {

struct RenderOptions {
  std::string scene_path;
  std::string backend = "auto";
  int device = 0;
  std::string resolution;
  std::string output;
  bool full_float = false;
  std::string preview;
  int mirror_depth = 1;
  uint32_t seed = 1;
  int frame = 0;
  bool quiet = false;
  PhotonSettings photons;
  std::string estimator = "pd";
  std::string kernel = "constant";
  std::string leaf = "auto";
};

// Photon options shared by every command that renders.
void apply_photon_options(RenderOptions& o) {
  o.photons.estimator = o.estimator == "knn" ? PM_ESTIMATOR_KNN : o.estimator == "radius" ? PM_ESTIMATOR_RADIUS : PM_ESTIMATOR_PD;
  o.photons.kernel_shape = o.kernel == "epanechnikov" ? PM_KERNEL_EPANECHNIKOV : PM_KERNEL_CONSTANT;
  if (o.leaf == "auto") {
    o.photons.leaf_threshold = 0;
  } else {
    try {
      size_t used = 0;
      int t = std::stoi(o.leaf, &used);
      if (used != o.leaf.size() || t < 1) throw std::invalid_argument("");
      o.photons.leaf_threshold = t;
    } catch (const std::exception&) {
      throw InputError("--leaf: expected 'auto' or a positive integer, got '" + o.leaf + "'");
    }
  }
}

int run_render(RenderOptions& o) {
  apply_photon_options(o);
  Scene scene = o.scene_path.empty() ? builtin_cornell_box() : load_scene_file(o.scene_path);
  RenderSettings settings;
  settings.photons = o.photons;
  settings.mirror_depth = o.mirror_depth;
  settings.seed = o.seed;
  if (!o.resolution.empty()) parse_resolution(o.resolution, &settings.width, &settings.height);
  if (!o.preview.empty() && !preview_available())
    throw InputError("--preview needs OpenImageIO, which this build does not have");
  const std::string pattern = o.output.empty() ? default_output_pattern(scene.name) : o.output;
  const std::string path = expand_output_pattern(pattern, o.frame);

  std::unique_ptr<Device> device = create_device(o.backend, o.device);
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
  auto options = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene to OpenEXR (default: the built-in Cornell box)");
  cmd->add_option("scene", options->scene_path, "Scene file (JSON, see docs/scene-format.md)");
  cmd->add_option("--backend", options->backend, "auto, cuda or opencl (auto: CUDA when a CUDA device exists)")
      ->check(CLI::IsMember({"auto", "cuda", "opencl"}));
  cmd->add_option("--device", options->device, "Device index within the backend (see 'pmrender devices')");
  cmd->add_option("--resolution", options->resolution, "WIDTHxHEIGHT, overrides the scene camera's");
  cmd->add_option("-o,--output", options->output, "Output pattern; runs of # are the zero-padded frame number")
      ->default_str("out/<scene>_####.exr");
  cmd->add_flag("--float", options->full_float, "Write 32-bit float channels instead of half");
  cmd->add_option("--preview", options->preview, "Also write a tone-mapped PNG here (needs OpenImageIO)");
  cmd->add_option("--mirror-depth", options->mirror_depth, "Perfect-mirror bounces followed from the eye")
      ->check(CLI::Range(0, 16));
  cmd->add_option("--seed", options->seed, "Random seed");
  cmd->add_option("--frame", options->frame, "Frame number")->check(CLI::NonNegativeNumber);
  cmd->add_flag("-q,--quiet", options->quiet, "Print nothing on success");
  PhotonSettings& ph = options->photons;
  cmd->add_option("--photons", ph.photons, "Photons emitted per frame (0: direct light only)")->capture_default_str();
  cmd->add_option("--batch", ph.batch, "Photons per pass; memory is bounded by this, not by --photons")
      ->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--bounces", ph.bounces, "Diffuse bounces of indirect light")->capture_default_str()->check(CLI::Range(0, 16));
  cmd->add_option("--estimator", options->estimator, "pd (photon differentials), knn or radius")
      ->capture_default_str()->check(CLI::IsMember({"pd", "knn", "radius"}));
  cmd->add_option("--kernel", options->kernel, "Density estimation kernel: constant or epanechnikov")
      ->capture_default_str()->check(CLI::IsMember({"constant", "epanechnikov"}));
  cmd->add_option("--smoothing", ph.smoothing, "Footprint smoothing factor s (section 4.3)")->capture_default_str();
  cmd->add_option("--rmax", ph.rmax, "Largest footprint semiaxis, metres (default: 10% of the scene diagonal)");
  cmd->add_option("--radius", ph.radius, "Gather radius of --estimator radius, metres (default: 5% of the scene diagonal)");
  cmd->add_option("--k", ph.knn_k, "Neighbours of --estimator knn")->capture_default_str()->check(CLI::Range(1, 256));
  cmd->add_option("--leaf", options->leaf, "Photon map leaf threshold T: auto or a number")->capture_default_str();
  return [options] { return run_render(*options); };
}

}  // namespace pm::cli

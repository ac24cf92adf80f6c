// Registration and interpretation of the shared rendering options.
#include "cli/render_options.h"

#include <cmath>

#include "cli/commands.h"
#include "render/errors.h"
#include "render/footprint_scale.h"
#include "scene_io/cornell_box.h"
#include "scene_io/scene_file.h"

namespace pm::cli {

void add_render_options(CLI::App* cmd, RenderOptions& o) {
  cmd->add_option("scene", o.scene_path, "Scene file (.json, .gltf or .glb; see docs/scene-format.md); default: the Cornell box");
  cmd->add_option("--backend", o.backend, "auto, cuda or opencl (auto: CUDA when a CUDA device exists)")
      ->check(CLI::IsMember({"auto", "cuda", "opencl"}));
  cmd->add_option("--device", o.device, "Device index within the backend (see 'pmrender devices')");
  cmd->add_option("--resolution", o.resolution, "WIDTHxHEIGHT, overrides the scene camera's");
  cmd->add_option("--mirror-depth", o.mirror_depth, "Perfect-mirror bounces followed from the eye")
      ->capture_default_str()->check(CLI::Range(0, 16));
  cmd->add_option("--seed", o.seed, "Random seed")->capture_default_str();
  PhotonSettings& ph = o.photons;
  cmd->add_option("--photons", ph.photons, "Photons emitted per frame (0: direct light only)")->capture_default_str();
  cmd->add_option("--batch", ph.batch, "Photons per pass; memory is bounded by this, not by --photons")
      ->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--bounces", ph.bounces, "Diffuse bounces of indirect light")->capture_default_str()->check(CLI::Range(0, 16));
  cmd->add_option("--estimator", o.estimator, "pd (photon differentials), knn or radius")
      ->capture_default_str()->check(CLI::IsMember({"pd", "knn", "radius"}));
  cmd->add_option("--kernel", o.kernel, "Density estimation kernel: constant or epanechnikov")
      ->capture_default_str()->check(CLI::IsMember({"constant", "epanechnikov"}));
  cmd->add_option("--smoothing", o.smoothing,
                  "Diffuse footprint smoothing: auto (chosen per batch so that footprints cover the scene's surface " +
                      std::to_string(int(kAutoSmoothingOverlap)) +
                      " times on average: the same image at any scene size) or a number, the paper's factor s "
                      "(section 4.3)")
      ->capture_default_str();
  cmd->add_option("--rmax", ph.rmax, "Largest footprint semiaxis and k-NN search radius, metres "
                                     "(default: 10% of the scene diagonal)");
  cmd->add_option("--radius", ph.radius, "Gather radius of --estimator radius, metres (default: 5% of the scene diagonal)");
  cmd->add_option("--k", ph.knn_k, "Neighbours of --estimator knn")->capture_default_str()->check(CLI::Range(1, 256));
  cmd->add_option("--leaf", o.leaf, "Photon map leaf threshold T: auto or a number")->capture_default_str();
  cmd->add_option("--photon-bvh", o.photon_bvh, "Photon map builder: lbvh (device, per frame) or vvh (voxel volume "
                                                "heuristic on the host, for comparison)")
      ->capture_default_str()->check(CLI::IsMember({"lbvh", "vvh"}));
}

Scene load_scene(const RenderOptions& o) {
  return o.scene_path.empty() ? builtin_cornell_box() : load_scene_file(o.scene_path);
}

RenderSettings render_settings(const RenderOptions& o) {
  RenderSettings settings;
  settings.mirror_depth = o.mirror_depth;
  settings.seed = o.seed;
  if (!o.resolution.empty()) parse_resolution(o.resolution, &settings.width, &settings.height);
  settings.photons = o.photons;
  PhotonSettings& ph = settings.photons;
  ph.estimator = o.estimator == "knn" ? PM_ESTIMATOR_KNN : o.estimator == "radius" ? PM_ESTIMATOR_RADIUS : PM_ESTIMATOR_PD;
  ph.kernel_shape = o.kernel == "epanechnikov" ? PM_KERNEL_EPANECHNIKOV : PM_KERNEL_CONSTANT;
  ph.vvh_map = o.photon_bvh == "vvh";
  if (o.smoothing == "auto") {
    ph.smoothing = 0;
  } else {
    try {
      size_t used = 0;
      const float s = std::stof(o.smoothing, &used);
      if (used != o.smoothing.size() || !(s > 0) || !std::isfinite(s)) throw std::invalid_argument("");
      ph.smoothing = s;
    } catch (const std::exception&) {
      throw InputError("--smoothing: expected 'auto' or a positive number, got '" + o.smoothing + "'");
    }
  }
  if (o.leaf == "auto") {
    ph.leaf_threshold = 0;
  } else {
    try {
      size_t used = 0;
      int t = std::stoi(o.leaf, &used);
      if (used != o.leaf.size() || t < 1) throw std::invalid_argument("");
      ph.leaf_threshold = t;
    } catch (const std::exception&) {
      throw InputError("--leaf: expected 'auto' or a positive integer, got '" + o.leaf + "'");
    }
  }
  return settings;
}

}  // namespace pm::cli

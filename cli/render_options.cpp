// Registration and interpretation of the shared rendering options.
#include "cli/render_options.h"

#include "cli/commands.h"
#include "cli/number_parsing.h"
#include "render/errors.h"
#include "scene_io/cornell_box.h"
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
      ->capture_default_str()->transform(integer_in(0, 16));
  cmd->add_option("--seed", o.seed, "Random seed")->capture_default_str()->transform(any_unsigned32());
  PhotonSettings& ph = o.photons;
  cmd->add_option("--photons", ph.photons, "Photons emitted per frame (0: direct light only)")
      ->capture_default_str()->transform(unsigned_in(0, UINT64_MAX));
  cmd->add_option("--batch", ph.batch, "Photons per pass; memory is bounded by this, not by --photons")
      ->capture_default_str()->transform(unsigned_in(1, UINT32_MAX));
  cmd->add_option("--bounces", ph.bounces, "Diffuse bounces of indirect light")->capture_default_str()->transform(integer_in(0, 16));
  cmd->add_option("--estimator", o.estimator, "pd (photon differentials), knn or radius")
      ->capture_default_str()->check(CLI::IsMember({"pd", "knn", "radius"}));
  cmd->add_option("--kernel", o.kernel, "Density estimation kernel: constant or epanechnikov")
      ->capture_default_str()->check(CLI::IsMember({"constant", "epanechnikov"}));
  cmd->add_option("--smoothing", ph.smoothing, "Footprint smoothing factor s (section 4.3)")
      ->capture_default_str()->transform(positive_float());
  cmd->add_option("--rmax", ph.rmax, "Largest footprint semiaxis and k-NN search radius, metres "
                                     "(default: 10% of the scene diagonal)")
      ->transform(non_negative_float());
  cmd->add_option("--radius", ph.radius, "Gather radius of --estimator radius, metres (default: 5% of the scene diagonal)")
      ->transform(non_negative_float());
  cmd->add_option("--k", ph.knn_k, "Neighbours of --estimator knn")->capture_default_str()->transform(integer_in(1, 256));
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
  if (o.leaf == "auto") {
    ph.leaf_threshold = 0;
  } else {
    try {
      ph.leaf_threshold = int(parse_unsigned("--leaf", o.leaf, 1, INT32_MAX));
    } catch (const InputError&) {
      throw InputError("--leaf: expected 'auto' or a whole number from 1 to " + std::to_string(INT32_MAX) +
                       ", got '" + o.leaf + "'");
    }
  }
  return settings;
}

}  // namespace pm::cli

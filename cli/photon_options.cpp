// Options of the photon-mapping method (render/photon/photon_settings.h): registration in their
// own help group, and the settings they describe. Values are checked by
// PhotonSettings::validate (one layer); names come from the library's name tables.
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "cli/method_options.h"
#include "cli/number_parsing.h"
#include "render/errors.h"
#include "render/footprint_scale.h"
#include "render/photon/photon_settings.h"

namespace pm::cli {

namespace {

std::vector<std::string> with_auto(std::vector<std::string> names) {
  names.push_back("auto");
  return names;
}

// An option that is "auto" (0: the settings choose) or a number that `read` accepts (it throws
// InputError otherwise); any other text is refused with "expected auto or <expected>", naming the
// setting.
template <class Read>
double auto_or(const char* setting, const std::string& text, const char* expected, Read read) {
  if (text == "auto") return 0;
  try {
    return read(text);
  } catch (const InputError&) {
  }
  throw SettingError(setting, std::string("expected auto or ") + expected + ", got '" + text + "'");
}

double positive(const std::string& text) { return parse_positive("", text, std::numeric_limits<float>::max()); }

// --tile-gather: auto, off (0) or a reach in mean footprint radii.
float tile_gather_reach(const std::string& text) {
  if (text == "auto") return PhotonSettings::kTileGatherAuto;
  if (text == "off") return 0.0f;
  try {
    return float(positive(text));
  } catch (const InputError&) {
  }
  throw SettingError("tile-gather", "expected auto, off or a positive number, got '" + text + "'");
}

class PhotonOptions final : public MethodOptions {
 public:
  PhotonSettings settings_;
  std::string estimator = "pd";
  std::string kernel = "constant";
  std::string leaf = "auto";
  std::string smoothing = "auto";
  std::string photon_bvh = "lbvh";
  std::string sequence = "random";
  // auto: shrink under a budget (it converges where average keeps its bias), else average.
  std::string progressive = "auto";
  std::string footprint_clip = "on";
  std::string footprint_coverage = "on";
  std::string facet_weighting = "auto";
  std::string overlap = "auto";
  std::string alpha = "auto";
  std::string tile_gather = "auto";
  std::string photons_max = "auto";

  std::shared_ptr<const MethodSettings> settings(bool budgeted) const override {
    auto s = std::make_shared<PhotonSettings>(settings_);
    value_of(kEstimatorNames, estimator, &s->estimator);
    value_of(kKernelShapeNames, kernel, &s->kernel_shape);
    value_of(kPhotonMapBuilderNames, photon_bvh, &s->builder);
    value_of(kPhotonSequenceNames, sequence, &s->sequence);
    if (progressive == "auto") s->progressive = budgeted ? kProgressiveShrink : kProgressiveAverage;
    else value_of(kProgressiveNames, progressive, &s->progressive);
    int clip = 1;
    value_of(kFootprintClipNames, footprint_clip, &clip);
    s->footprint_clip = clip != 0;
    int coverage = 1;
    value_of(kFootprintClipNames, footprint_coverage, &coverage);
    s->footprint_coverage = coverage != 0;
    if (facet_weighting != "auto") value_of(kFootprintClipNames, facet_weighting, &s->facet_weighting);
    s->smoothing = float(auto_or("smoothing", smoothing, "a positive number", positive));
    s->overlap = auto_or("overlap", overlap, "a positive number", positive);
    s->alpha = float(auto_or("alpha", alpha, "a number between 0 and 1 (exclusive)", [](const std::string& text) {
      const double v = parse_positive("", text, 1);
      if (!(v < 1)) throw InputError("alpha: 1 is not below 1");
      return v;
    }));
    s->tile_gather = tile_gather_reach(tile_gather);
    s->photons_max = uint64_t(auto_or("photons-max", photons_max, "a whole number of photons", [](const std::string& text) {
      return double(parse_unsigned("", text, 1, uint64_t(1) << 40));
    }));
    s->leaf_threshold = int(auto_or("leaf", leaf, "a positive integer", [](const std::string& text) {
      return double(parse_unsigned("", text, 1, uint64_t(std::numeric_limits<int>::max())));
    }));
    s->validate();
    return s;
  }

  // Photon mapping as its options say, and beside it the same with final gathering (16 rays a
  // pass unless --final-gather names a count) or without it (when --final-gather asked for it).
  std::vector<RaceCandidate> candidates(const std::string& name) const override {
    return with_and_without_final_gather(name, std::static_pointer_cast<const PhotonSettings>(settings(true)),
                                         kRacedFinalGatherRays);
  }
  // Final gathering's rays per pass in the race, as over radiosity: with the map's small overlap
  // a pass of 16 rays takes about 20 ms at 960 x 540 on an H200, and 10 s of 4-ray passes read
  // 1.29-1.45 times the error of 16-ray passes on the benchmark scenes, each pass's photons then
  // the larger part of its cost (docs/method-auto.md, "Final gathering over photons in the race").
  static constexpr uint32_t kRacedFinalGatherRays = 16;
};

}  // namespace

std::shared_ptr<MethodOptions> add_photon_options(CLI::App* cmd) {
  auto o = std::make_shared<PhotonOptions>();
  PhotonSettings& ph = o->settings_;
  const std::string group = "Photon mapping (--method photon)";
  cmd->add_option("--photons", ph.photons, "Photons emitted per pass (0: direct light only)")->transform(any_unsigned64())
      ->capture_default_str()->group(group);
  cmd->add_option("--photons-max", o->photons_max,
                  "The most photons a pass grows to: passes double --photons at pass " +
                      std::to_string(kPhotonGrowthStart) +
                      " and each time the passes quadruple after it (auto: under --final-gather 4 x --photons, at "
                      "most 1048576, else --photons; --photons: every pass the same; docs/final-gathering.md)")
      ->capture_default_str()->group(group);
  cmd->add_option("--bounces", ph.bounces, "Diffuse bounces of indirect light (also --method path)")->capture_default_str()->transform(any_int32())->group(group);
  cmd->add_option("--estimator", o->estimator, "pd (photon differentials), knn or radius")
      ->capture_default_str()->check(CLI::IsMember(names_of(kEstimatorNames)))->group(group);
  cmd->add_option("--kernel", o->kernel, "Density estimation kernel: constant or epanechnikov")
      ->capture_default_str()->check(CLI::IsMember(names_of(kKernelShapeNames)))->group(group);
  cmd->add_option("--smoothing", o->smoothing,
                  "Diffuse footprint smoothing: auto (chosen per pass so that footprints cover the scene's surface " +
                      std::to_string(int(kAutoSmoothingOverlap)) +
                      " times on average: the same image at any scene size) or a number, the paper's factor s "
                      "(section 4.3)")
      ->capture_default_str()->group(group);
  cmd->add_option("--footprint-thickness", o->settings_.footprint_thickness,
                  "Half-thickness of the pd footprints along the surface normal, over their shorter semiaxis")
      ->capture_default_str()->group(group);
  cmd->add_option("--overlap", o->overlap,
                  "The automatic smoothing's target: photon footprints covering each point of the scene's "
                  "surface on average (more: smoother, blurrier); auto: " +
                      std::to_string(int(kAutoSmoothingOverlap)) + ", " + std::to_string(int(kShrinkStartOverlap)) +
                      " at the first of pd's shrinking passes, " + std::to_string(int(kFinalGatherOverlap)) +
                      " under final gathering (docs/accuracy.md)")
      ->capture_default_str()->group(group);
  cmd->add_option("--rmax", ph.rmax, "Largest footprint semiaxis and k-NN search radius, metres "
                                     "(default: 10% of the scene diagonal)")->transform(finite_float())->group(group);
  cmd->add_option("--radius", ph.radius, "Gather radius of --estimator radius, metres (default: 5% of the scene diagonal)")->transform(finite_float())
      ->group(group);
  cmd->add_option("--k", ph.knn_k, "Neighbours of --estimator knn")->capture_default_str()->transform(any_int32())->group(group);
  cmd->add_option("--leaf", o->leaf, "Photon map leaf threshold T: auto or a number")->capture_default_str()->group(group);
  cmd->add_option("--photon-bvh", o->photon_bvh, "Photon map builder: lbvh (device, per pass) or vvh (voxel volume "
                                                 "heuristic on the host, for comparison)")
      ->capture_default_str()->check(CLI::IsMember(names_of(kPhotonMapBuilderNames)))->group(group);
  cmd->add_option("--photon-sequence", o->sequence,
                  "random, or halton: emission directions from a Halton sequence, the same in every frame")
      ->capture_default_str()->check(CLI::IsMember(names_of(kPhotonSequenceNames)))->group(group);
  cmd->add_option("--footprint-clip", o->footprint_clip,
                  "on: footprints stop at the walls around their hit (no light through thin walls; one scene "
                  "query per photon hit); off: the paper's whole ellipses, faster (docs/algorithm.md)")
      ->capture_default_str()->check(CLI::IsMember(names_of(kFootprintClipNames)))->group(group);
  cmd->add_option("--footprint-coverage", o->footprint_coverage,
                  "on: a footprint's flux is spread over the part of it that lies on a surface (no light "
                  "lost where a footprint hangs over an edge; a few short rays per photon hit); off: over "
                  "the whole (clipped) ellipse")
      ->capture_default_str()->check(CLI::IsMember(names_of(kFootprintClipNames)))->group(group);
  cmd->add_option("--facet-weighting", o->facet_weighting,
                  "on: a photon counts on a facet tilted from its own surface by what its light delivers "
                  "there, over the lit surface area; off: in full on every facet within 60 degrees; auto: on "
                  "for --estimator radius and pd's shrinking passes, off for pd's averaged ones (docs/accuracy.md)")
      ->capture_default_str()->check(CLI::IsMember(with_auto(names_of(kFootprintClipNames))))->group(group);
  cmd->add_option("--progressive", o->progressive,
                  "How passes combine: average (the same footprints every pass; noise falls, bias stays), "
                  "shrink (footprints and radii shrink from pass to pass: bias and noise both vanish; "
                  "docs/progressive.md) or auto: shrink under --time or --target-error, else average")
      ->capture_default_str()->check(CLI::IsMember(with_auto(names_of(kProgressiveNames))))->group(group);
  cmd->add_option("--final-gather", ph.final_gather,
                  "Final gathering: N rays per shading point and pass, the photon map (--method radiosity: "
                  "its solution) read at their hits (less blur, more time; 0: off; docs/final-gathering.md)")
      ->transform(any_unsigned32())->capture_default_str()->group(group);
  cmd->add_option("--alpha", o->alpha,
                  "shrink: r_i^2 = r_(i-1)^2 (i + alpha) / (i + 1), 0 < alpha < 1; auto: 0.2 for pd, 2/3 for "
                  "knn, radius and final gathering (docs/progressive.md)")
      ->capture_default_str()->group(group);
  cmd->add_option("--tile-gather", o->tile_gather,
                  "The gather's 8 x 4 pixel tiles walk the photon map together where their first shading "
                  "points lie within N mean footprint radii (faster on GPUs, the same image): auto (" +
                      std::to_string(kTileGatherReach).substr(0, 3) +
                      " on GPUs, off on CPUs), off, or N (docs/benchmarks.md)")
      ->capture_default_str()->group(group);
  return o;
}

}  // namespace pm::cli

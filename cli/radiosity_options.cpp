// Options of the vertex link radiosity method (render/radiosity/radiosity_settings.h):
// registration in their own help group, and the settings they describe. --bounces and
// --final-gather are shared with photon mapping (the same meanings): registered once, read by both. Values are checked
// by RadiositySettings::validate; names come from the library's name tables.
#include <memory>
#include <string>
#include <vector>

#include "cli/method_options.h"
#include "cli/number_parsing.h"
#include "render/errors.h"
#include "render/radiosity/radiosity_settings.h"

namespace pm::cli {

namespace {

class RadiosityOptions final : public MethodOptions {
 public:
  RadiositySettings settings_;
  std::string sides = "two";
  std::string light_samples = "one-ring";
  std::string link_origins = "one-ring";
  std::string directions = "auto";
  CLI::Option* bounces = nullptr;       // --bounces, whoever registered it
  CLI::Option* final_gather = nullptr;  // --final-gather, whoever registered it

  std::shared_ptr<const MethodSettings> settings(bool /*budgeted*/) const override {
    auto s = std::make_shared<RadiositySettings>(settings_);
    value_of(kRadiositySidesNames, sides, &s->sides);
    value_of(kRadiosityLightSamplesNames, light_samples, &s->light_samples);
    value_of(kRadiosityLinkOriginsNames, link_origins, &s->link_origins);
    if (directions != "auto") {
      try {
        s->directions = uint32_t(parse_unsigned("--directions", directions, 1, 16384));
      } catch (const InputError&) {
        throw SettingError("directions", "expected auto or 1 to 16384 directions per element, got '" + directions + "'");
      }
    }
    if (bounces && bounces->count() > 0) s->bounces = bounces->as<int>();
    if (final_gather && final_gather->count() > 0) s->final_gather = final_gather->as<uint32_t>();
    s->validate();
    return s;
  }
  // Radiosity as its options say, and beside it the same with final gathering over its solution
  // (or without, when --final-gather asked for it). 16 rays a pass: a pass over the solution
  // costs a few tens of milliseconds at 960 x 540 on the GPU (docs/final-gathering.md). Without
  // --directions both trace final gathering's directions (kFinalGatherDirections), so that one
  // mesh and one set of links serve the two (the race copies them: VertexLinkRadiosity::adopt_setup)
  // at the cost final gathering alone pays. Plain radiosity's own 256 would make its error 4.3-5.2 %
  // where 64 make it 5.4-6.2 % (H200, 960 x 540), which final gathering over the same solution
  // reaches within a few passes of 16 rays, and cost the race's first round 94-430 ms more on the
  // benchmark scenes (docs/method-auto.md, "The race's first round").
  std::vector<RaceCandidate> candidates(const std::string& name) const override {
    auto given = std::static_pointer_cast<const RadiositySettings>(settings(true));
    if (directions == "auto") {
      auto shared = std::make_shared<RadiositySettings>(*given);
      shared->directions = RadiositySettings::kFinalGatherDirections;
      given = shared;
    }
    return with_and_without_final_gather(name, given, kRacedFinalGatherRays);
  }
  static constexpr uint32_t kRacedFinalGatherRays = 16;
};

}  // namespace

std::shared_ptr<MethodOptions> add_radiosity_options(CLI::App* cmd) {
  auto o = std::make_shared<RadiosityOptions>();
  RadiositySettings& r = o->settings_;
  const std::string group = "Vertex link radiosity (--method radiosity)";
  o->bounces = cmd->get_option_no_throw("--bounces");
  if (!o->bounces)
    o->bounces = cmd->add_option("--bounces", r.bounces, "Diffuse bounces of indirect light")->capture_default_str()->transform(any_int32())->group(group);
  o->final_gather = cmd->get_option_no_throw("--final-gather");
  if (!o->final_gather)
    o->final_gather = cmd->add_option("--final-gather", r.final_gather,
                                      "Final gathering: N rays per shading point and pass, the solution read at their hits "
                                      "(0: off; docs/final-gathering.md)")
                          ->transform(any_unsigned32())->capture_default_str()->group(group);
  cmd->add_option("--directions", o->directions, "Hemisphere directions nC shot per element (link rays): auto (" +
                                                      std::to_string(RadiositySettings::kDirections) + "; " +
                                                      std::to_string(RadiositySettings::kFinalGatherDirections) +
                                                      " with --final-gather) or a number")
      ->capture_default_str()->group(group);
  cmd->add_option("--max-edge", r.max_edge, "Longest triangle edge after refinement, metres (default: the scene "
                                            "diagonal / 50)")->transform(finite_float())->group(group);
  cmd->add_option("--feature-angle", r.feature_angle, "Feature angle alpha_f, degrees: vertices split and smoothing "
                                                      "stops where normals differ more")
      ->capture_default_str()->transform(finite_float())->group(group);
  cmd->add_option("--smooth-passes", r.smooth_passes, "One-ring smoothing passes over the gathered light (0: none)")
      ->capture_default_str()->transform(any_int32())->group(group);
  cmd->add_option("--sides", o->sides, "Elements on both sides of every surface (two) or on the winding's side (one)")
      ->capture_default_str()->check(CLI::IsMember(names_of(kRadiositySidesNames)))->group(group);
  cmd->add_option("--light-samples", o->light_samples, "Light links at the vertex only, or over its one-ring (1:4)")
      ->capture_default_str()->check(CLI::IsMember(names_of(kRadiosityLightSamplesNames)))->group(group);
  cmd->add_option("--link-origins", o->link_origins, "Link rays from the vertex only, or from points over its "
                                                     "one-ring drawn by its hat function")
      ->capture_default_str()->check(CLI::IsMember(names_of(kRadiosityLinkOriginsNames)))->group(group);
  cmd->add_option("--hidden-origins", r.hidden_origins, "Link rays that meet a back face nearer than this many "
                                                       "max edges started inside geometry and are left out (0: none)")
      ->capture_default_str()->transform(finite_float())->group(group);
  cmd->add_option("--link-batch", r.link_batch, "Elements per link-build batch (0: as many as 256 MiB of scratch hold)")
      ->capture_default_str()->transform(any_unsigned32())->group(group);
  return o;
}

}  // namespace pm::cli

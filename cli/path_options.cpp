// Options of the reference path tracer (render/path/path_settings.h) in their own help group.
// --bounces is the photon mapper's option, registered once for both methods: the path tracer
// reads the same value, so `--method path` and `--method photon` render the same light paths.
#include <memory>

#include "cli/method_options.h"
#include "cli/number_parsing.h"
#include "render/path/path_settings.h"

namespace pm::cli {

namespace {

class PathOptions final : public MethodOptions {
 public:
  PathSettings settings_;
  CLI::Option* bounces = nullptr;  // shared with photon mapping
  std::string mis = "on";

  std::shared_ptr<const MethodSettings> settings(bool /*budgeted*/) const override {
    auto s = std::make_shared<PathSettings>(settings_);
    if (bounces && bounces->count() > 0) s->bounces = bounces->as<int>();
    s->mis = mis == "on";
    s->validate();
    return s;
  }
};

}  // namespace

std::shared_ptr<MethodOptions> add_path_options(CLI::App* cmd) {
  auto o = std::make_shared<PathOptions>();
  const std::string group = "Path tracing (--method path)";
  cmd->add_option("--spp", o->settings_.samples, "Paths per pixel and pass (the image averages --passes of them)")
      ->capture_default_str()->transform(any_unsigned32())->group(group);
  cmd->add_option("--path-mis", o->mis, "Area lights and the environment: on (multiple importance sampling of light "
                                       "samples and sampled directions) or off (light samples only)")
      ->capture_default_str()->check(CLI::IsMember({"on", "off"}))->group(group);
  o->bounces = cmd->get_option_no_throw("--bounces");
  if (!o->bounces)
    o->bounces = cmd->add_option("--bounces", o->settings_.bounces, "Diffuse bounces of indirect light")
                     ->capture_default_str()->transform(any_int32())->group(group);
  return o;
}

}  // namespace pm::cli

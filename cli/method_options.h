// The indirect-light methods the command line offers (--method NAME): each registers its own
// options on a rendering command and turns them into its MethodSettings. Adding a method to the
// command line is one entry in kMethods (cli/method_options.cpp) and its options file.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

#include "render/errors.h"
#include "render/indirect_method.h"
#include "render/method_race.h"

namespace pm::cli {

// A method's options as parsed; settings() turns them into validated MethodSettings. budgeted:
// the frame's passes run until --time or --target-error stops them, so a method whose passes may
// or may not converge chooses by default the way that converges.
class MethodOptions {
 public:
  virtual ~MethodOptions() = default;
  virtual std::shared_ptr<const MethodSettings> settings(bool budgeted) const = 0;
  // What --method auto races of this method under a budget (render/method_race.h), each named:
  // by default the method as its options describe it; a method with variants worth racing
  // (photon mapping with and without final gathering) offers each.
  virtual std::vector<RaceCandidate> candidates(const std::string& name) const { return {{name, settings(true)}}; }
};

// A method's race candidates with and without final gathering: the settings as given, and beside
// them the same with `rays` gather rays a pass (or, when final gathering was asked for, without
// it); the settings alone where final gathering does not apply to them. Settings: a MethodSettings
// with a final_gather member (rays per pass, 0: off).
template <class Settings>
std::vector<RaceCandidate> with_and_without_final_gather(const std::string& name, std::shared_ptr<const Settings> given,
                                                         uint32_t rays) {
  auto other = std::make_shared<Settings>(*given);
  other->final_gather = given->final_gather > 0 ? 0 : rays;
  try {
    other->validate();
  } catch (const SettingError&) {
    return {{name, given}};
  }
  const bool asked = given->final_gather > 0;
  return {{name, asked ? std::shared_ptr<const Settings>(other) : given},
          {name + " --final-gather " + std::to_string(asked ? given->final_gather : rays),
           asked ? given : std::shared_ptr<const Settings>(other)}};
}

struct MethodEntry {
  const char* name;
  const char* summary;
  // Registers the method's options (in their own help group) and returns where they land.
  std::shared_ptr<MethodOptions> (*add_options)(CLI::App* cmd);
};

const std::vector<MethodEntry>& methods();
// The methods' names, and (with_auto) "auto": the race of them all (render/method_race.h).
std::vector<std::string> method_names(bool with_auto = false);
constexpr const char* kAutoMethod = "auto";

// Each method's options file.
std::shared_ptr<MethodOptions> add_photon_options(CLI::App* cmd);
std::shared_ptr<MethodOptions> add_path_options(CLI::App* cmd);
std::shared_ptr<MethodOptions> add_radiosity_options(CLI::App* cmd);

}  // namespace pm::cli

// The table of indirect-light methods on the command line.
#include "cli/method_options.h"

namespace pm::cli {

const std::vector<MethodEntry>& methods() {
  static const std::vector<MethodEntry> table = {
      {"photon", "photon mapping with photon-differential footprints (Fabianowski & Dingliana 2009)",
       &add_photon_options},
      {"path", "reference path tracer with next-event estimation, the same BRDFs and bounces", &add_path_options},
      {"radiosity", "vertex link radiosity over explicit visibility links (2008; docs/radiosity.md)",
       &add_radiosity_options},
  };
  return table;
}

std::vector<std::string> method_names(bool with_auto) {
  std::vector<std::string> names;
  for (const MethodEntry& m : methods()) names.push_back(m.name);
  if (with_auto) names.push_back(kAutoMethod);
  return names;
}

}  // namespace pm::cli

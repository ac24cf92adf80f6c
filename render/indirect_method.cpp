// Method statistics: the small shared piece of the method interface.
#include "render/indirect_method.h"

#include <algorithm>

namespace pm {

void MethodStats::set(const std::string& name, double value) {
  for (Entry& e : entries)
    if (e.name == name) {
      e.value = value;
      return;
    }
  entries.push_back({name, value});
}

bool MethodStats::has(const std::string& name) const {
  return std::any_of(entries.begin(), entries.end(), [&](const Entry& e) { return e.name == name; });
}

double MethodStats::get(const std::string& name, double fallback) const {
  for (const Entry& e : entries)
    if (e.name == name) return e.value;
  return fallback;
}

}  // namespace pm

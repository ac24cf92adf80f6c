// Lookups in the settings' name tables.
#include "render/named_values.h"

namespace pm {

const char* name_of(const NameTable& table, int value) {
  for (const NamedValue& entry : table)
    if (entry.value == value) return entry.name;
  return "?";
}

bool value_of(const NameTable& table, const std::string& name, int* value) {
  for (const NamedValue& entry : table)
    if (name == entry.name) {
      *value = entry.value;
      return true;
    }
  return false;
}

std::vector<std::string> names_of(const NameTable& table) {
  std::vector<std::string> names;
  for (const NamedValue& entry : table) names.push_back(entry.name);
  return names;
}

std::string names_list(const NameTable& table) {
  std::string list;
  for (size_t i = 0; i < table.size(); ++i) {
    if (i > 0) list += i + 1 == table.size() ? " or " : ", ";
    list += table[i].name;
  }
  return list;
}

}  // namespace pm

// Name tables for the settings that are enumerations (estimator, kernel, ...): one table per
// enumeration, read by the library (descriptions, JSON) and by the command line (accepted
// option values), so a name is spelt in one place.
#pragma once

#include <string>
#include <vector>

namespace pm {

struct NamedValue {
  const char* name;
  int value;
};
using NameTable = std::vector<NamedValue>;

// The name of value in table, or "?" for a value the table does not have.
const char* name_of(const NameTable& table, int value);
// The value named name; false when the table has no such name.
bool value_of(const NameTable& table, const std::string& name, int* value);
// Every name, in table order (for help texts and option checks).
std::vector<std::string> names_of(const NameTable& table);
// "a, b or c", for messages.
std::string names_list(const NameTable& table);

}  // namespace pm

// Owns strict JSON reading for scene files: parsing that reports syntax errors by line and rejects
// duplicate keys, and JsonField, a value that knows its file and field path so every typed read
// ("expected a finite number, got null") can throw an InputError naming both.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "render/scene.h"

namespace pm {

// Deepest nesting of arrays and objects a JSON document read by pmrender may have. Scene files
// use 5 levels, glTF files about 6 (plus whatever their extras hold); without a limit a hostile
// file of 100,000 '[' costs memory quadratic in the depth while its field paths are built.
constexpr int kMaxJsonNesting = 100;

// Throws InputError "<file>: line N: JSON nested deeper than 100 levels" for text nesting deeper
// than kMaxJsonNesting. A linear scan that skips strings; it does not otherwise check the syntax.
void check_json_nesting(const std::string& file, const std::string& text);

// Reads and parses the whole file (nesting checked first). Throws InputError:
//   "<file>: cannot open (<reason>)"
//   "<file>: line N: JSON parse error: <detail>"
//   "<file>: line N: <path>: expected a finite number, got 1e999"   (numbers beyond double range)
//   "<file>: <path>: duplicate key"                                   (nlohmann would keep the last)
nlohmann::json parse_json_file_strict(const std::string& path);

// "null", "true", "a string", "an array", "an object", or the number itself (inf/-inf/nan spelled
// out, since nlohmann dumps those as null and "got null" would mislead).
std::string describe_json_value(const nlohmann::json& value);

// A value in a parsed document plus where it is, for messages. Cheap to copy (holds a pointer to
// the value, which must outlive it).
class JsonField {
 public:
  JsonField(std::string file, const nlohmann::json& value, std::string path);

  const nlohmann::json& value() const { return *value_; }
  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }

  // Throws InputError "<file>: <path>: <message>" (just "<file>: <message>" at the root).
  [[noreturn]] void fail(const std::string& message) const;

  // --- objects -------------------------------------------------------------------------------
  // Fails unless this is an object whose keys are all in allowed_keys; the message lists them.
  void expect_object_with_keys(const std::vector<std::string>& allowed_keys) const;
  bool has(const std::string& key) const;
  // The member; fails with "<path>.<key>: missing required key" when absent.
  JsonField member(const std::string& key) const;

  // --- arrays --------------------------------------------------------------------------------
  // Fails unless this is an array (of exactly `size` elements unless size is kAnySize).
  static constexpr size_t kAnySize = static_cast<size_t>(-1);
  size_t expect_array(size_t size = kAnySize) const;
  JsonField element(size_t index) const;

  // --- scalars -------------------------------------------------------------------------------
  double finite_number() const;
  // An integer (integral floats such as 512.0 accepted) in [lo, hi].
  long long integer_in(long long lo, long long hi) const;
  std::string non_empty_string() const;
  // [x, y, z] of finite numbers, each representable as a float.
  Float3 float3() const;

 private:
  std::string child_path(const std::string& key) const;

  std::string file_;
  const nlohmann::json* value_;
  std::string path_;
};

}  // namespace pm

// Output file name patterns: expanding runs of '#' into zero-padded frame numbers, and the
// default pattern derived from the scene name.
#include "render/output_pattern.h"

#include "render/errors.h"

namespace pm {

std::string expand_output_pattern(const std::string& pattern, int frame) {
  if (frame < 0) {
    throw InputError("frame " + std::to_string(frame) + " is negative; output pattern '" +
                     pattern + "' needs a frame number of 0 or more");
  }
  const std::string digits = std::to_string(frame);
  std::string expanded;
  expanded.reserve(pattern.size() + digits.size());
  size_t i = 0;
  while (i < pattern.size()) {
    if (pattern[i] != '#') {
      expanded += pattern[i++];
      continue;
    }
    size_t run_length = 0;
    while (i < pattern.size() && pattern[i] == '#') {
      ++run_length;
      ++i;
    }
    if (digits.size() < run_length) expanded.append(run_length - digits.size(), '0');
    expanded += digits;
  }
  return expanded;
}

bool pattern_has_frame_field(const std::string& pattern) {
  return pattern.find('#') != std::string::npos;
}

std::string default_output_pattern(const std::string& scene_name) {
  std::string safe_name = scene_name.empty() ? "frame" : scene_name;
  for (char& c : safe_name) {
    if (c == '#' || c == '/' || c == '\\') c = '_';
  }
  return "out/" + safe_name + "_####.exr";
}

}  // namespace pm

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
  // The name comes from the scene file: anything there must not make folders ('/', '\\', ".."),
  // hide the file (a leading '.'), cut the path (NUL), break a line, or become a frame field.
  std::string safe_name = scene_name.empty() ? "frame" : scene_name;
  for (char& c : safe_name) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f || c == '#' || c == '/' || c == '\\' || c == '.') c = '_';
  }
  // Short enough that the file name and its writer's temporary name fit any folder (255 bytes);
  // cut before a UTF-8 continuation byte, never inside a character.
  const size_t kMaxNameBytes = 119;
  if (safe_name.size() > kMaxNameBytes) {
    size_t cut = kMaxNameBytes;
    while (cut > 0 && (static_cast<unsigned char>(safe_name[cut]) & 0xC0) == 0x80) --cut;
    safe_name.resize(cut);
  }
  return "out/" + safe_name + "_####.exr";
}

}  // namespace pm

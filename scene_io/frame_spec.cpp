// Parser and writer of frame specifications: comma-separated items, each N, A-B or A-B:STEP.
#include "scene_io/frame_spec.h"

#include <cctype>
#include <set>

#include "scene_io/load_error.h"

namespace pm {

namespace {

// The item is the user's text: a line break or control character in it is escaped (one-line messages).
[[noreturn]] void bad(const std::string& item, const std::string& why) { throw_input_error("'" + item + "'", why); }

int parse_number(const std::string& item, const std::string& text) {
  if (text.empty() || text.size() > 9) bad(item, "expected a frame number");
  for (char c : text)
    if (!std::isdigit(static_cast<unsigned char>(c))) bad(item, "expected a frame number, got '" + text + "'");
  return std::stoi(text);
}

}  // namespace

std::vector<int> parse_frame_spec(const std::string& spec, int first, int last) {
  if (spec.empty()) throw InputError("empty frame specification");
  std::vector<int> frames;
  std::set<int> seen;
  size_t start = 0;
  while (start <= spec.size()) {
    size_t comma = spec.find(',', start);
    std::string item = spec.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    start = comma == std::string::npos ? spec.size() + 1 : comma + 1;
    if (item.empty()) bad(spec, "empty item between commas");

    int step = 1;
    std::string range = item;
    size_t colon = item.find(':');
    if (colon != std::string::npos) {
      step = parse_number(item, item.substr(colon + 1));
      if (step < 1) bad(item, "step must be at least 1");
      range = item.substr(0, colon);
    }
    int a, b;
    size_t dash = range.find('-');
    if (dash == std::string::npos) {
      if (colon != std::string::npos) bad(item, "a step needs a range A-B");
      a = b = parse_number(item, range);
    } else {
      a = parse_number(item, range.substr(0, dash));
      b = parse_number(item, range.substr(dash + 1));
      if (b < a) bad(item, "range end is before its start");
    }
    if (a < first || b > last)
      bad(item, "outside the scene's frames " + std::to_string(first) + "-" + std::to_string(last));
    for (long long f = a; f <= b; f += step) {
      if (seen.insert(int(f)).second) frames.push_back(int(f));
      if (frames.size() > kMaxFrameSpecFrames)
        bad(item, "selects more than " + std::to_string(kMaxFrameSpecFrames) + " frames");
    }
  }
  return frames;
}

std::string format_frame_spec(const std::vector<int>& frames) {
  std::string spec;
  auto item = [&](const std::string& text) { spec += (spec.empty() ? "" : ",") + text; };
  size_t i = 0;
  while (i < frames.size()) {
    // The longest run from i with one positive step; two frames with a step above 1 read more
    // simply as two items ("4,9" rather than "4-9:5").
    size_t end = i + 1;
    const long long step = end < frames.size() ? (long long)frames[end] - frames[i] : 0;
    if (step > 0)
      while (end < frames.size() && (long long)frames[end] - frames[end - 1] == step) ++end;
    const size_t length = end - i;
    if (length == 1 || (length == 2 && step > 1)) {
      item(std::to_string(frames[i]));
      i += 1;
      continue;
    }
    std::string run = std::to_string(frames[i]) + "-" + std::to_string(frames[end - 1]);
    if (step > 1) run += ":" + std::to_string(step);
    item(run);
    i = end;
  }
  return spec;
}

}  // namespace pm

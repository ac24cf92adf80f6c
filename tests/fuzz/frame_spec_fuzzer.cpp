// libFuzzer target for --frames specifications (scene_io/frame_spec.h). The first four bytes
// choose the sequence's frame range [first, last] (first in -128..127, up to 65535 frames, and
// sometimes last < first); the rest is the specification. The contract checked: every problem is
// a pm::InputError with a one-line message that names no option (the command line adds
// "--frames: "), and an accepted list is non-empty, duplicate-free and inside
// the range.
#include <cstdint>
#include <cstdio>
#include <set>
#include <string>

#include "scene_io/frame_spec.h"
#include "render/errors.h"

namespace {

void require(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "frame spec fuzzer: %s\n", what);
    __builtin_trap();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 4) return 0;
  const int first = int(int8_t(data[0]));
  const int span = int(data[1]) | int(data[2]) << 8;
  const int last = (data[3] & 1) ? first + span : first - span % 16;
  const std::string spec(reinterpret_cast<const char*>(data + 4), size - 4);
  try {
    const std::vector<int> frames = pm::parse_frame_spec(spec, first, last);
    require(!frames.empty(), "accepted an empty list");
    std::set<int> seen;
    for (int f : frames) {
      require(f >= first && f <= last, "frame outside the range");
      require(seen.insert(f).second, "duplicate frame");
    }
  } catch (const pm::InputError& e) {
    const std::string message = e.what();
    require(!message.empty() && message.find('\n') == std::string::npos, "empty or multi-line message");
    // (The message quotes the offending item, which may itself spell the option.)
    require(spec.find("--frames") != std::string::npos || message.find("--frames") == std::string::npos,
            "the library names the option");
  }
  return 0;
}

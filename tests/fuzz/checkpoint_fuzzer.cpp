// libFuzzer target for the checkpoint state reader of `render --resume` (render/checkpoint.h:
// read_checkpoint_header, read_checkpoint), on the input written as a .pmstate file. The
// contract checked: neither ever throws (any exception fails); a failure says why; an accepted
// header has a positive size, at least one pass with n / 2 of n passes odd-numbered, and finite,
// non-negative seconds; an accepted checkpoint is the one the caller asked for (frame, size,
// fingerprint), with that header's guarantees and three film sums of width x height finite values.
// The caller's expectations are the header's own where it has one, so the search reaches the
// film sums; otherwise those of a 4 x 3 frame 0.
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "render/checkpoint.h"

namespace {

void check_header(const pm::FrameCheckpoint& c) {
  pm::fuzz::require(c.width > 0 && c.height > 0, "positive size");
  pm::fuzz::require(c.sums.passes >= 1, "at least one pass");
  pm::fuzz::require(c.sums.odd_passes == c.sums.passes / 2, "odd passes are half the passes");
  pm::fuzz::require(std::isfinite(c.seconds) && c.seconds >= 0, "finite seconds");
}

void check_sums(const std::vector<float4>& sum, size_t pixels) {
  pm::fuzz::require(sum.size() == pixels, "film sums of width x height");
  for (const float4& v : sum)
    pm::fuzz::require(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z), "finite film sums");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = pm::fuzz::write("frame.exr.pmstate", data, size);
  std::string why;
  const std::optional<pm::FrameCheckpoint> header = pm::read_checkpoint_header(path, &why);
  pm::fuzz::require(header.has_value() || !why.empty(), "a refused header says why");
  if (header) check_header(*header);

  int frame = 0, width = 4, height = 3;
  std::string fingerprint = "cornell-box (built-in)";
  if (header) {
    frame = header->frame;
    width = header->width;
    height = header->height;
    fingerprint = header->fingerprint;
  }
  why.clear();
  const std::optional<pm::FrameCheckpoint> c = pm::read_checkpoint(path, frame, width, height, fingerprint, &why);
  pm::fuzz::require(c.has_value() || !why.empty(), "a refused checkpoint says why");
  if (!c) return 0;
  pm::fuzz::require(header.has_value(), "a checkpoint is accepted only with a valid header");
  pm::fuzz::require(c->frame == frame && c->width == width && c->height == height && c->fingerprint == fingerprint,
                    "the checkpoint asked for");
  check_header(*c);
  const size_t pixels = size_t(width) * size_t(height);
  for (const std::vector<float4>* sum : {&c->sums.indirect, &c->sums.caustic, &c->sums.odd})
    check_sums(*sum, pixels);
  return 0;
}

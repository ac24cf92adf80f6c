// The state of an unfinished frame, beside its checkpoint image: the film sums after some passes,
// the pass count, the render time so far, and what they were rendered with, so `render --resume`
// continues the frame with its next pass and ends exactly where an uninterrupted run would
// (docs/progressive.md). One binary file per frame, written atomically: "<image>.pmstate".
#pragma once

#include <optional>
#include <string>

#include "render/renderer.h"

namespace pm {

struct FrameCheckpoint {
  int frame = 0;
  int width = 0, height = 0;
  double seconds = 0;       // render time of the passes so far, all runs together
  std::string fingerprint;  // scene and resolved settings: a checkpoint continues only these
  FilmSums sums;
};

// "<image path>.pmstate".
std::string checkpoint_state_path(const std::string& image_path);

void write_checkpoint(const std::string& path, const FrameCheckpoint& checkpoint);

// What the checkpoint in path says it is, without its film sums: frame, size (both positive),
// pass counts (at least one pass; of n passes, n / 2 odd-numbered, as the pass loop numbers them
// from 0), seconds (finite, not negative) and fingerprint, each header line once, numbers plain
// decimal. Otherwise nullopt with *why set. Never throws for a bad file.
std::optional<FrameCheckpoint> read_checkpoint_header(const std::string& path, std::string* why);

// The checkpoint in path, or nullopt with *why set when there is none, its header is not as
// read_checkpoint_header requires, it belongs to another frame, size or fingerprint, or its film
// sums are not exactly width x height float4 each (the file's length is checked before anything
// is allocated) or not finite. Never throws for a bad file: a frame without a usable checkpoint
// is simply rendered from its first pass.
std::optional<FrameCheckpoint> read_checkpoint(const std::string& path, int frame, int width, int height,
                                               const std::string& fingerprint, std::string* why);

}  // namespace pm

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

// The checkpoint in path, or nullopt with *why set when there is none, it is unreadable or
// truncated, or it belongs to another frame, size or fingerprint. Never throws for a bad file:
// a frame without a usable checkpoint is simply rendered from its first pass.
std::optional<FrameCheckpoint> read_checkpoint(const std::string& path, int frame, int width, int height,
                                               const std::string& fingerprint, std::string* why);

}  // namespace pm

// Warnings about a rendered frame that is written but not as rendered: non-finite pixels written
// as black, and values that half channels cannot hold (clamped at 65504 or rounded to 0, which
// --float avoids). Each kind is reported for the first frame it happens in, so a long sequence
// gives one line, not one per frame.
#pragma once

#include "render/exr_io.h"
#include "render/image.h"

namespace pm::cli {

class FrameWarnings {
 public:
  explicit FrameWarnings(bool full_float) : full_float_(full_float) {}

  // What a frame's file loses to half floats: a scan of every value, which needs no lock (nothing
  // when the file is float).
  HalfRangeLoss measure(const FrameImage& image) const;
  // Prints "pmrender: warning: frame F: ..." lines to stderr for what this frame loses.
  void report(int frame, const HalfRangeLoss& loss, int repaired_pixels);

 private:
  bool full_float_;
  bool repaired_reported_ = false, clamped_reported_ = false, flushed_reported_ = false;
};

}  // namespace pm::cli

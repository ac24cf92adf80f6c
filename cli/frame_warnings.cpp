// FrameWarnings (frame_warnings.h): repaired pixels and half-float range losses, first frame only.
#include "cli/frame_warnings.h"

#include <cstdio>

#include "render/exr_io.h"

namespace pm::cli {

HalfRangeLoss FrameWarnings::measure(const FrameImage& image) const {
  return full_float_ ? HalfRangeLoss{} : half_range_loss(image);
}

void FrameWarnings::report(int frame, const HalfRangeLoss& loss, int repaired_pixels) {
  const char* later = " (later frames are not reported)";
  if (repaired_pixels > 0 && !repaired_reported_) {
    std::fprintf(stderr, "pmrender: warning: frame %d: %d pixel(s) were not finite and were written as black%s\n", frame,
                 repaired_pixels, later);
    repaired_reported_ = true;
  }
  if (full_float_) return;
  if (loss.clamped > 0 && !clamped_reported_) {
    std::fprintf(stderr,
                 "pmrender: warning: frame %d: %zu of %zu values exceed the half-float range and were clamped to "
                 "65504; use --float (or lower the light power)%s\n",
                 frame, loss.clamped, loss.values, later);
    clamped_reported_ = true;
  }
  // Deep shadows may hold a few such values; a light far too weak for half floats loses most.
  if (loss.flushed_to_zero > 0 && loss.flushed_to_zero * 100 >= loss.nonzero && !flushed_reported_) {
    std::fprintf(stderr,
                 "pmrender: warning: frame %d: %zu of %zu non-zero values are below the half-float range and were "
                 "written as 0; use --float (or raise the light power)%s\n",
                 frame, loss.flushed_to_zero, loss.nonzero, later);
    flushed_reported_ = true;
  }
}

}  // namespace pm::cli

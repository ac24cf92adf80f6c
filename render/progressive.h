// A frame's pass loop under the user's budgets (docs/progressive.md): passes until the cap, a time
// budget (stop after the pass that reaches it) or a target error (stop when the estimate from the
// even and odd passes falls to it), with a report after every pass for progress lines and
// checkpoints. Method-independent: it drives Renderer::run_pass only.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "render/renderer.h"

namespace pm {

struct PassBudget {
  uint32_t max_passes = 1;   // the cap
  double seconds = 0;        // > 0: stop after the pass that reaches this render time
  double target_error = 0;   // > 0: stop once estimate_error() <= it (from kMinPassesForError on)
  uint32_t checkpoint_every = 0;  // > 0: report a checkpoint every N passes (not after the last)

  bool open_ended() const { return seconds > 0 || target_error > 0; }
};

// Passes needed before the error estimate may stop a frame: with fewer, a lucky low estimate
// would end it early.
constexpr uint32_t kMinPassesForError = 4;

struct PassReport {
  uint32_t passes = 0;   // summed in the film
  double seconds = 0;    // render time so far (all runs of the frame)
  double error = -1;     // estimated relative error of the indirect light; < 0: not known
};

struct ProgressiveResult : PassReport {
  std::string stopped_by;  // "passes", "time" or "error"
};

struct ProgressiveCallbacks {
  std::function<void(const PassReport&)> after_pass;  // every pass (progress display)
  std::function<void(const PassReport&)> checkpoint;  // every checkpoint_every passes
};

// Renders frame with renderer's method under budget, continuing from resume (a checkpoint's sums
// and seconds) when given; leaves the film resolved. The error is estimated after every pass when
// target_error is set, and once at the end otherwise.
ProgressiveResult render_progressive(Renderer& renderer, int frame, const PassBudget& budget,
                                     const FilmSums* resume, double resumed_seconds,
                                     const ProgressiveCallbacks& callbacks = {});

}  // namespace pm

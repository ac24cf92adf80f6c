// A frame's pass loop under the user's budgets (docs/progressive.md): passes until the cap, a time
// budget (stop after the pass that reaches it) or a target error (stop when the estimate from the
// even and odd passes falls to it), with a report after every pass for progress lines and
// checkpoints. Method-independent: it drives Renderer::run_pass only.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

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
  std::string stopped_by;  // "passes", "time", "error" or "levelled" (LevelledErrorWatch)
};

// A target error below what the method can reach: passes of a method whose bias they do not
// remove (final gathering over a radiosity solution, averaged photon passes) bring its error
// estimate down to its bias and no further, and the frame would run to the pass cap (a million
// passes). The watch keeps the frame's readings and says when the estimate has fallen by less than
// kLevelledFall over each of the last two doublings of render time, at least kLevelledPasses
// passes in, while it stands above the target by more than two standard errors: then the frame
// stops, "levelled".
// An unbiased method's error falls by 29 % a doubling (t^-1/2), shrinking photon passes' by 10 to
// 17 % (t^-0.15 to t^-0.27 on the benchmark scenes, method_race.h), so falls under 5 % twice over
// are the bias showing, not noise.
constexpr double kLevelledFall = 1.05;
constexpr uint32_t kLevelledPasses = 16;
class LevelledErrorWatch {
 public:
  // Records a reading after `passes` passes and `seconds` of render time; error_upper is the
  // estimate plus two standard errors (Renderer::last_error_upper).
  bool levelled(uint32_t passes, double seconds, double error, double error_upper, double target);

 private:
  struct Reading {
    double seconds, error;
  };
  std::vector<Reading> readings_;
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

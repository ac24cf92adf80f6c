// The budgeted pass loop.
#include "render/progressive.h"

#include <algorithm>
#include <chrono>

#include "render/interruption.h"

namespace pm {

bool LevelledErrorWatch::levelled(uint32_t passes, double seconds, double error, double error_upper, double target) {
  if (!(error >= 0) || !(seconds > 0)) return false;
  readings_.push_back({seconds, error});
  if (passes < kLevelledPasses || target <= 0) return false;
  // The latest readings at half and at a quarter of the time or earlier: the error's fall over
  // each of the last two doublings, both under kLevelledFall (one alone can be the estimate's
  // noise, or its control sharpening).
  // The readings are in time order: each is found by bisection, so a frame of many passes pays
  // a logarithm a pass.
  auto latest_by = [&](double t) -> const Reading* {
    auto after = std::upper_bound(readings_.begin(), readings_.end(), t,
                                  [](double time, const Reading& r) { return time < r.seconds; });
    return after == readings_.begin() ? nullptr : &*(after - 1);
  };
  const Reading *half = latest_by(0.5 * seconds), *quarter = latest_by(0.25 * seconds);
  if (!half || !quarter || !(half->error > 0)) return false;
  const double lower = 2.0 * error - error_upper;  // the estimate less two standard errors
  return half->error < kLevelledFall * error && quarter->error < kLevelledFall * half->error && lower > target;
}

ProgressiveResult render_progressive(Renderer& renderer, int frame, const PassBudget& budget,
                                     const FilmSums* resume, double resumed_seconds,
                                     const ProgressiveCallbacks& callbacks) {
  const auto start = std::chrono::steady_clock::now();
  auto seconds = [&] {
    return resumed_seconds + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  renderer.begin_frame(frame);
  if (resume) renderer.set_film_sums(*resume);
  ProgressiveResult result;
  result.stopped_by = "passes";
  uint32_t cap = budget.max_passes;
  if (renderer.method() && renderer.method()->max_passes() > 0 && renderer.method()->max_passes() < cap)
    cap = renderer.method()->max_passes();
  if (!renderer.method()) cap = 0;

  LevelledErrorWatch watch;
  while (renderer.passes_done() < cap) {
    throw_if_interrupted();  // between passes: a long frame stops at once (its checkpoint stays)
    renderer.run_pass();
    PassReport report;
    report.passes = renderer.passes_done();
    if (budget.target_error > 0 && report.passes >= 2) report.error = renderer.estimate_error();
    if (budget.open_ended()) renderer.wait();  // a budget counts finished passes, not launched ones
    report.seconds = seconds();
    if (callbacks.after_pass) callbacks.after_pass(report);
    result.PassReport::operator=(report);
    // The pass's reading adds a few control paths at a time; it stops the frame only once the
    // control, topped up as the frame's final estimate tops it up, agrees: an estimate read
    // through a control noisier than the film can dip under the target and rise over it again
    // when the control sharpens (Conference at 1 % after a short race: 1.17 %, true 1.19 %, where
    // the pass's reading had let it stop; docs/progressive.md, `--target-error`).
    if (budget.target_error > 0 && report.passes >= kMinPassesForError && report.error >= 0 &&
        renderer.last_error_upper() <= budget.target_error) {
      report.error = renderer.estimate_error(true);
      result.PassReport::operator=(report);
      if (renderer.last_error_upper() <= budget.target_error) {
        result.stopped_by = "error";
        break;
      }
    }
    if (budget.target_error > 0 && watch.levelled(report.passes, report.seconds, report.error,
                                                  renderer.last_error_upper(), budget.target_error)) {
      result.stopped_by = "levelled";
      break;
    }
    if (budget.seconds > 0 && report.seconds >= budget.seconds) {
      result.stopped_by = "time";
      break;
    }
    if (budget.checkpoint_every > 0 && report.passes % budget.checkpoint_every == 0 && report.passes < cap &&
        callbacks.checkpoint) {
      renderer.wait();
      callbacks.checkpoint(report);
    }
  }
  renderer.wait();
  result.passes = renderer.passes_done();
  // The control topped up to its paths (done where the error stopped the frame).
  if (result.stopped_by != "error") result.error = renderer.estimate_error(true);
  result.seconds = seconds();
  return result;
}

}  // namespace pm

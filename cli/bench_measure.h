// The measuring half of `pmrender bench` (and of `tradeoff`): frame plans, one timed run of a
// renderer over a plan with per-stage device times (StageTimer), host wall times and the
// method's statistics per frame, and medians over the measured frames. Method-independent.
#pragma once

#include <string>
#include <vector>

#include "render/renderer.h"
#include "render/stage_timer.h"

namespace pm::cli {

struct Spread {
  double median = 0, min = 0, max = 0;
};
Spread spread(std::vector<double> values);

// Frames rendered first and not measured, then the measured ones.
struct FramePlan {
  std::vector<int> warmup, measured;
};

struct Measurement {
  std::vector<int> frames;                      // measured frames
  std::vector<std::vector<StageTime>> stages;   // per measured frame, in stage order
  std::vector<double> stages_total_ms, wall_ms;  // per measured frame
  std::vector<FrameStats> stats;                // per measured frame
  double first_frame_wall_ms = -1;              // the plan's first frame, warmup or measured

  // Over the measured frames: a stage's device time, the sum of all stages, host wall time.
  Spread stage(const std::string& name) const;
  Spread total() const { return spread(stages_total_ms); }
  Spread wall() const { return spread(wall_ms); }
  // A method statistic over the measured frames.
  Spread stat(const std::string& name) const;
  double fps() const;         // 1000 / median host wall ms
  double fps_stages() const;  // 1000 / median sum of stages
};

// Renders the plan's frames with renderer and timer attached; shows progress as "what".
Measurement measure(Renderer& renderer, StageTimer& timer, const FramePlan& plan, const std::string& what);

// The same with a fresh Renderer that is gone on return.
Measurement measure_with(Device& device, const Scene& scene, const RenderSettings& settings, const FramePlan& plan,
                         const std::string& what);

}  // namespace pm::cli

// One frame of `pmrender render`, from the first pass to its file: the budgeted pass loop
// (render/progressive.h), checkpoints and their resume, the progress line inside the frame, and
// the EXR (and preview) with the header attributes that say how it was made.
#pragma once

#include <string>

#include "cli/progress_line.h"
#include "render/progressive.h"
#include "render/renderer.h"

namespace pm::cli {

struct FrameJobOptions {
  PassBudget budget;
  bool full_float = false;
  bool resume = false;   // continue from a checkpoint where one fits
  bool quiet = false;
};

struct FrameOutcome {
  ProgressiveResult result;
  int repaired_pixels = 0;
  bool photons_reused = false;
  double render_ms = 0;
  bool resumed = false;  // continued from a checkpoint
};

class FrameJob {
 public:
  FrameJob(Renderer& renderer, const Scene& scene, const DeviceInfo& device, const FrameJobOptions& options);

  // Renders frame into path (and preview, when not empty) and returns what happened.
  FrameOutcome run(int frame, const std::string& path, const std::string& preview, ProgressLine& progress);

 private:
  std::vector<std::pair<std::string, std::string>> attributes(int frame, const PassReport& report,
                                                               const std::string& stopped_by) const;

  Renderer& renderer_;
  const Scene& scene_;
  DeviceInfo device_;
  FrameJobOptions options_;
  std::string fingerprint_;
};

}  // namespace pm::cli

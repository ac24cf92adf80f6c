// The frames of `pmrender render` once their input is checked and their devices are open: each
// frame is claimed (render/frame_claim.h), rendered on its job's devices and written on the job's
// writing thread while the next frame renders; with several jobs (--devices) each takes a
// contiguous run of frames and then half of the longest run left (render/frame_runs.h).
// --wait-for-claimed-frames then waits on the frames other processes hold. A frame that fails is
// reported and counted while the others go on (a run of one frame throws it to main() instead);
// SIGINT and SIGTERM stop between frames. The loop keeps the tallies of the run's summary line.
#pragma once

#include <chrono>
#include <cstddef>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "cli/frame_job.h"
#include "cli/frame_warnings.h"
#include "cli/memory.h"
#include "cli/progress_line.h"
#include "render/device.h"
#include "render/frame_claim.h"
#include "render/progressive.h"

namespace pm::cli {

struct FrameLoopOptions {
  std::string pattern;          // -o, with # for the frame number
  std::string preview;          // --preview's pattern; empty: none
  ClaimRules claims;
  PassBudget budget;            // the frames' budget: what the "wrote" line and its warnings say
  size_t selected_frames = 0;   // every frame selected, complete ones included
  bool resume = false;
  bool wait_for_claimed = false;
  bool full_float = false;      // --float: no half-float range warnings
  bool quiet = false;
  bool verbose = false;
};

// What the run did, for its summary.
struct FrameTallies {
  size_t rendered = 0;            // frames written by this process
  size_t reused = 0;              // of those, frames that reused the photons before them
  size_t finished_elsewhere = 0;  // found complete once claimed (another process wrote them)
  std::vector<int> failed;        // in the order they failed; sorted with several jobs
  std::vector<int> held_elsewhere;  // claimed by other live processes when last looked at
  std::vector<size_t> frames_per_job;
  MemorySnapshot first_frame_memory;
  double first_frame_ms = -1;     // the first written frame's render time
};

// "1, 4, 7".
std::string frame_list(const std::vector<int>& frames);

class FrameLoop {
 public:
  // jobs: one per device group (frame_devices.h), all rendering the same scene; first_device:
  // the device whose memory the summary reports.
  FrameLoop(const FrameLoopOptions& options, std::vector<std::unique_ptr<FrameJob>>& jobs, const Device* first_device);

  // Renders and writes `todo`, then waits on the frames other processes held if asked to;
  // returns early when a signal arrives.
  void run(const std::vector<int>& todo);

  const FrameTallies& tallies() const { return tallies_; }
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  void clear_progress() { progress_.clear(); }

 private:
  // A frame this process claimed and rendered, waiting for its file.
  struct PendingFrame {
    FrameJob* job = nullptr;
    RenderedFrame rendered;
    FrameClaim claim;
  };

  // Claims frame f and renders it; returns the frame to write, or nothing where it was not
  // rendered here. waited: f was held by another process before (and said so), so a complete
  // file now is that process's work, with or without --resume.
  std::shared_ptr<PendingFrame> render_frame(FrameJob& job, int f, bool waited);
  // Writes a rendered frame's file, then releases its claim (the file is in place).
  void write_frame(PendingFrame& pending);
  // The frames next_frame() hands out, on one job: each frame's file is written on the job's
  // writing thread while the job's devices render the next frame (at most one frame waits per
  // job). A single frame is written at once.
  void render_frames(FrameJob& job, const std::function<std::optional<int>()>& next_frame);
  // One thread per job, each on its own run of frames.
  void render_on_every_job();
  // --wait-for-claimed-frames: the frames other processes held, until each is complete, here
  // (its claim was released without a file, or went stale) or there.
  void wait_for_claimed_frames();
  // The "wrote" line of a frame this process rendered; called with output_ locked.
  void report_written(const FrameJob& job, int f, const std::string& path, const FrameOutcome& outcome);
  // Called from a catch block: reports frame f's failure and goes on, or rethrows it for a run
  // of a single frame (main() reports it as before).
  void report_failure(int f, const std::exception& e);
  void count_done(int f);

  FrameLoopOptions options_;
  std::vector<std::unique_ptr<FrameJob>>& jobs_;
  const Device* first_device_;
  std::vector<int> todo_;
  ProgressLine progress_;
  std::mutex output_;  // progress, messages and the tallies, across the jobs' threads
  FrameWarnings warnings_;
  FrameTallies tallies_;
  size_t done_ = 0;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace pm::cli

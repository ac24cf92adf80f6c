// A sequence's frames shared between devices as contiguous runs with work stealing: each device
// starts on its own run (consecutive frames keep what a camera-only run reuses from frame to
// frame), and a device whose run is spent takes the back half of the longest run left. So a faster
// device renders more frames, and no device idles while another still has two frames to go.
#pragma once

#include <cstddef>
#include <mutex>
#include <optional>
#include <vector>

namespace pm {

class FrameRuns {
 public:
  // Items 0..count-1 split into `workers` contiguous runs of (nearly) equal length.
  FrameRuns(size_t count, size_t workers);

  // The next item for worker w: the next of its own run, else the first of the back half it
  // took from the longest run left. Empty when every item is taken. Thread-safe.
  std::optional<size_t> next(size_t worker);

  // Items a worker took from other runs so far (for the log).
  size_t stolen(size_t worker) const;

 private:
  struct Run {
    size_t begin = 0, end = 0;  // [begin, end): not yet taken
    size_t stolen = 0;
  };
  mutable std::mutex mutex_;
  std::vector<Run> runs_;
};

}  // namespace pm

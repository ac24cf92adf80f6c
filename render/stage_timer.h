// Per-stage device timing for benchmarks: records device timer events around each stage of a
// frame and sums them per stage. Attached only by `pmrender bench`; a render without a timer
// records no events and adds no synchronisation.
#pragma once

#include <array>
#include <vector>

#include "render/device.h"

namespace pm {

enum class Stage : int {
  camera,          // S5: primary rays, mirror recursion, direct light + shadow rays
  photon_trace,    // S1+S2: emission and tracing
  footprints,      // S3: footprint ellipsoids and the bounds/area/count reduction
  map_morton,      // S4: Morton codes
  map_sort,        // S4: radix sort of (code, index)
  map_tree,        // S4: radix tree, bottom-up boxes, reorder into sorted order
  gather,          // S6
  film,            // S7: resolve (the read-back to the host is not a device stage)
  count
};
constexpr size_t kStageCount = static_cast<size_t>(Stage::count);
const char* stage_name(Stage stage);

class StageTimer {
 public:
  explicit StageTimer(Device& device) : device_(device) {}

  void begin(Stage stage);
  void end(Stage stage);
  // Waits for the device, then returns each stage's summed milliseconds since the last call.
  std::array<double, kStageCount> collect();

 private:
  struct Interval {
    Stage stage;
    TimerEvent start, stop;
  };
  Device& device_;
  std::vector<Interval> intervals_;
};

// RAII helper: times a scope when a timer is attached, does nothing otherwise.
class StageScope {
 public:
  StageScope(StageTimer* timer, Stage stage) : timer_(timer), stage_(stage) {
    if (timer_) timer_->begin(stage_);
  }
  ~StageScope() {
    if (timer_) timer_->end(stage_);
  }
  StageScope(const StageScope&) = delete;
  StageScope& operator=(const StageScope&) = delete;

 private:
  StageTimer* timer_;
  Stage stage_;
};

}  // namespace pm

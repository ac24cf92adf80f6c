// Per-stage device timing for benchmarks: records device timer events around each named stage
// of a frame and sums them per stage. Stage names are the renderer's ("camera") and the
// method's own; nothing here knows which method runs. Attached only by `pmrender bench` and
// `tradeoff`: a render without a timer records no events and adds no synchronisation.
#pragma once

#include <string>
#include <vector>

#include "render/device.h"

namespace pm {

// What one stage processes per frame, for throughput columns: work units per frame and their name.
struct StageInfo {
  std::string name;
  double work_per_frame = 0;  // 0: no throughput
  std::string unit;           // e.g. "rays/s"
  std::string counts;         // what the work counts, in words
};

struct StageTime {
  std::string stage;
  double ms = 0;
};

class StageTimer {
 public:
  explicit StageTimer(Device& device) : device_(device) {}

  void begin(const std::string& stage);
  void end(const std::string& stage);
  // Waits for the device, then returns each stage's summed milliseconds since the last call, in
  // the order the stages first ran.
  std::vector<StageTime> collect();

 private:
  struct Interval {
    std::string stage;
    TimerEvent start, stop;
  };
  Device& device_;
  std::vector<Interval> intervals_;
};

// RAII helper: times a scope when a timer is attached, does nothing otherwise.
class StageScope {
 public:
  StageScope(StageTimer* timer, const char* stage) : timer_(timer), stage_(stage) {
    if (timer_) timer_->begin(stage_);
  }
  ~StageScope() {
    if (timer_) timer_->end(stage_);
  }
  StageScope(const StageScope&) = delete;
  StageScope& operator=(const StageScope&) = delete;

 private:
  StageTimer* timer_;
  const char* stage_;
};

}  // namespace pm

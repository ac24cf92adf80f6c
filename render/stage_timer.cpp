// Device-event stage timing (CUDA events, OpenCL profiling markers via Device::record_timer).
#include "render/stage_timer.h"

#include "render/errors.h"

namespace pm {

void StageTimer::begin(const std::string& stage) { intervals_.push_back({stage, device_.record_timer(), nullptr}); }

void StageTimer::end(const std::string& stage) {
  for (auto it = intervals_.rbegin(); it != intervals_.rend(); ++it)
    if (it->stage == stage && !it->stop) {
      it->stop = device_.record_timer();
      return;
    }
  throw DeviceError("stage timer: end of " + stage + " without a begin");
}

std::vector<StageTime> StageTimer::collect() {
  device_.synchronize();
  std::vector<StageTime> sums;
  for (const Interval& i : intervals_) {
    if (!i.stop) continue;
    const double ms = device_.elapsed_ms(i.start, i.stop);
    auto it = sums.begin();
    while (it != sums.end() && it->stage != i.stage) ++it;
    if (it == sums.end()) sums.push_back({i.stage, ms});
    else it->ms += ms;
  }
  intervals_.clear();
  return sums;
}

}  // namespace pm

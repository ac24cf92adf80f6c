// Device-event stage timing (CUDA events, OpenCL profiling markers via Device::record_timer).
#include "render/stage_timer.h"

#include "render/errors.h"

namespace pm {

const char* stage_name(Stage stage) {
  static const char* const names[] = {"camera", "photon trace", "footprints", "map: morton",
                                      "map: sort", "map: tree", "gather", "film"};
  return names[static_cast<int>(stage)];
}

void StageTimer::begin(Stage stage) { intervals_.push_back({stage, device_.record_timer(), nullptr}); }

void StageTimer::end(Stage stage) {
  for (auto it = intervals_.rbegin(); it != intervals_.rend(); ++it)
    if (it->stage == stage && !it->stop) {
      it->stop = device_.record_timer();
      return;
    }
  throw DeviceError(std::string("stage timer: end of ") + stage_name(stage) + " without a begin");
}

std::array<double, kStageCount> StageTimer::collect() {
  device_.synchronize();
  std::array<double, kStageCount> ms{};
  for (const Interval& i : intervals_)
    if (i.stop) ms[static_cast<size_t>(i.stage)] += device_.elapsed_ms(i.start, i.stop);
  intervals_.clear();
  return ms;
}

}  // namespace pm

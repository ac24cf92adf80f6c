// The reference path tracer as an indirect-light method: each pass traces `samples` paths from
// every shading point of the camera pass (kernels/common/path_trace.h) and adds their mean into
// the film's indirect sum, so passes are the unit of progress (--passes, --time, checkpoints) and
// the film resolve averages them. It owns no buffers: paths live in registers.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "render/indirect_method.h"
#include "render/path/path_settings.h"

namespace pm {

class PathTracing final : public IndirectMethod {
 public:
  PathTracing(const MethodContext& context, const PathSettings& settings);

  std::string describe() const override { return settings_.describe(); }
  uint32_t max_passes() const override { return 0; }
  uint32_t light_bounces() const override { return uint32_t(settings_.bounces); }
  bool may_be_biased() const override { return false; }
  void begin_frame(const FrameContext& frame, const FrameChange& change) override;
  void run_pass(const FrameContext& frame, uint32_t pass) override;
  MethodStats stats() const override { return stats_; }
  std::vector<StageInfo> stages(const FrameContext& frame) const override;
  MethodWork work(uint32_t passes) const override { return {"path", paths_per_pass() * passes, paths_per_pass()}; }

 private:
  // Paths per pass over all shading points of a primary pixel (mirror depth 0).
  double paths_per_pass() const { return double(pixels_) * settings_.samples; }

  Device& device_;
  PathSettings settings_;
  uint32_t pixels_ = 0;
  uint32_t planned_passes_ = 1;
  uint32_t path_frame_ = 0;
  MethodStats stats_;
};

}  // namespace pm

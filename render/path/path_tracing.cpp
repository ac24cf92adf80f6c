// Orchestration of the path tracer: one launch per pass over the Device interface.
#include "render/path/path_tracing.h"

#include "kernels/common/pixel_order.h"

#include "render/errors.h"

namespace pm {

PathTracing::PathTracing(const MethodContext& context, const PathSettings& settings)
    : device_(context.device), settings_(settings) {
  settings_.validate();
  pixels_ = uint32_t(context.width) * uint32_t(context.height);
  planned_passes_ = context.planned_passes > 0 ? context.planned_passes : 1;
  // Path k of a frame draws random stream k, a 32-bit number.
  if (context.planned_passes > 0 && uint64_t(settings_.samples) * context.planned_passes > 0xffffffffull)
    throw SettingError("passes", std::to_string(context.planned_passes) + " passes of " +
                                     std::to_string(settings_.samples) + " paths exceed 2^32 - 1 paths per pixel");
}

std::vector<StageInfo> PathTracing::stages(const FrameContext& frame) const {
  return {{"path trace", paths_per_pass() * planned_passes_, "paths/s",
           "paths per frame from the primary shading points (paths seen in mirrors not counted)"}};
}

void PathTracing::begin_frame(const FrameContext& frame, const FrameChange& change) {
  // As the photon mapper's photons: camera-only runs of a sequence draw the random numbers of
  // their first frame unless every frame is to be keyed by its own number.
  path_frame_ = uint32_t(frame.reuse_lighting ? frame.light_run_start : frame.frame);
  stats_ = MethodStats{};
  stats_.set("path_frame", path_frame_);
  stats_.set("samples_per_pixel", 0);
}

void PathTracing::run_pass(const FrameContext& frame, uint32_t pass) {
  if (uint64_t(pass) * settings_.samples + settings_.samples > 0xffffffffull)
    throw SettingError("passes", "pass " + std::to_string(pass) + " of " + std::to_string(settings_.samples) +
                                     " paths would exceed 2^32 - 1 paths per pixel");
  LaunchParams params = frame.params;
  params.max_bounces = uint32_t(settings_.bounces);
  params.path_samples = settings_.samples;
  params.path_mis = settings_.mis ? 1u : 0u;
  params.path_first_sample = pass * settings_.samples;
  params.path_frame = path_frame_;
  {
    StageScope scope(frame.timer, "path trace");
    device_.launch(KernelId::path_trace, pixel_work_items(params.width, params.height), params);
  }
  stats_.set("samples_per_pixel", double(pass + 1) * settings_.samples);
}

}  // namespace pm

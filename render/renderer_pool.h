// Several devices on one frame: one Renderer per device over the same scene, sharing the frame's
// passes (the multi-pass GPU photon map paper: "part of the passes on one GPU, part on the other;
// the illumination at each point simply adds up"). Each device takes the next pass number as it
// becomes free, so faster devices run more passes; the film sums of every device are then added
// into the first device's film and resolved there. The result is the same K passes a single device
// would sum, added in another order (float rounding differs, nothing else). Memory per device is
// one pass's, as on one device.
#pragma once

#include <memory>
#include <vector>

#include "render/progressive.h"
#include "render/renderer.h"

namespace pm {

class RendererPool {
 public:
  RendererPool(const std::vector<Device*>& devices, const Scene& scene, const RenderSettings& settings);
  // The same, with first (already made on devices[0] with these settings, e.g. mid-frame from
  // --method auto's race: render/method_race.h) as the first device's renderer.
  RendererPool(const std::vector<Device*>& devices, const Scene& scene, const RenderSettings& settings,
               std::unique_ptr<Renderer> first);

  size_t size() const { return renderers_.size(); }
  Renderer& renderer(size_t i) { return *renderers_[i]; }
  // The renderer whose film holds the whole frame after render_progressive.
  Renderer& first() { return *renderers_.front(); }

  // render_progressive over every device: the budget (cap, time, error) applies to the frame, the
  // passes are shared. The error estimate comes from the first device's own passes, scaled to
  // the frame's pass count (its passes are a random half, third, ... of the frame's). Callbacks
  // run on the calling thread's device only (the first); checkpoints are not supported here.
  ProgressiveResult render_progressive(int frame, const PassBudget& budget, const FilmSums* resume,
                                       double resumed_seconds, const ProgressiveCallbacks& callbacks = {});
  // Passes each device ran in the last frame.
  const std::vector<uint32_t>& passes_per_device() const { return passes_per_device_; }

 private:
  std::vector<std::unique_ptr<Renderer>> renderers_;
  std::vector<uint32_t> passes_per_device_;
};

}  // namespace pm

// The vertex link radiosity method (the 2008 explicit-visibility link radiosity paper, sections
// 3-4; docs/radiosity.md) behind the IndirectMethod interface. Geometry is static, so the work
// splits by what a frame changes:
//   first frame   refine the mesh, build the elements (host), then trace the links on the
//                 device in batches of elements with bounded scratch ("prepare");
//   lights moved  light links (eq. 2), nB gathering bounces (eq. 3, 4), smoothing (eq. 5, 6);
//   camera moved  nothing: the vertex irradiance stays on the device (--no-reuse: relight anyway);
// and every frame's single pass interpolates the vertex irradiance at the camera pass's
// shading points into the indirect layer: deterministic, one pass per frame. With final
// gathering the solution has one bounce fewer and is read at the hits of gather rays from the
// shading points instead, pass after pass (progressive, like the photon method's).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "render/indirect_method.h"
#include "render/radiosity/radiosity_settings.h"

namespace pm {

struct RadiosityHostMesh;  // the first frame's host work (vertex_link_radiosity.cpp)
class RadiosityHostWork;   // that work begun on a thread of its own (RadiositySettings::begin_host_work)

// Begins the host mesh of `resolved` (settings resolved for the scene) on a thread of its own;
// null where the solution has no bounces or the mesh would be refused (the method refuses it).
std::shared_ptr<const HostWorkAhead> begin_radiosity_host_mesh(const Scene& scene, const RadiositySettings& resolved);

class VertexLinkRadiosity final : public IndirectMethod {
 public:
  VertexLinkRadiosity(const MethodContext& context, const RadiositySettings& settings);

  std::string describe() const override { return settings_.describe(); }
  uint32_t max_passes() const override { return settings_.final_gather > 0 ? 0 : 1; }
  uint32_t light_bounces() const override { return uint32_t(settings_.bounces); }
  bool may_be_biased() const override { return true; }
  double noise_rate() const override { return settings_.final_gather > 0 ? kScrambledNetRate : kIndependentNoiseRate; }
  bool adopt_setup(const IndirectMethod& other) override;
  bool shares_setup_with(const IndirectMethod& other) const override;
  void begin_frame(const FrameContext& frame, const FrameChange& change) override;
  void run_pass(const FrameContext& frame, uint32_t pass) override;
  // Final gathering's bias along the control's paths (kernels/common/radiosity_bias_probe.h).
  bool has_bias_probe() const override { return settings_.final_gather > 0; }
  void launch_bias_probe(const FrameContext& frame, const LaunchParams& control, uint64_t work_items) override;
  MethodStats stats() const override { return stats_; }
  std::vector<StageInfo> stages(const FrameContext& frame) const override;
  MethodWork work(uint32_t passes) const override {
    return {"element", double(element_count_) * passes, double(element_count_)};
  }

  // The settings as resolved for the scene (max_edge filled in).
  const RadiositySettings& settings() const { return settings_; }
  uint32_t element_count() const { return element_count_; }
  // Merged links and how many times links were built / light links run on this renderer.
  uint64_t link_count() const { return links_; }
  uint64_t link_builds() const { return link_builds_; }
  uint64_t light_link_runs() const { return light_link_runs_; }

 private:
  LaunchParams launch_params(const FrameContext& frame) const;
  LaunchParams with_solution(LaunchParams p) const;  // p with the solution's fields
  void prepare(StageTimer* timer);
  void count_light_samples();
  void build_links(LaunchParams params, StageTimer* timer);
  void resize_links(uint64_t words, uint64_t used);
  void solve(LaunchParams params, StageTimer* timer);
  void update_stats(bool built, bool lit);

  Device& device_;
  BufferTable& buffers_;
  const Scene& scene_;
  RadiositySettings settings_;
  uint32_t pixels_ = 0;
  uint32_t planned_passes_ = 1;  // a frame's passes as the renderer plans them: the stages' work per frame
  int ray_frame_ = 0;               // the key of the gather rays of the frame begun last

  bool prepared_ = false;
  std::shared_ptr<const RadiosityHostWork> host_work_;  // begun before the renderer's upload, until prepare takes it
  bool adopted_ = false;            // the mesh and links are copies of another renderer's (adopt_setup)
  bool solved_ = false;
  uint32_t element_count_ = 0;
  uint32_t final_source_ = 0;       // the half of rad_irradiance the interpolation reads
  std::vector<uint4> ranges_;       // host copy of rad_element_ranges (link offsets filled by the build)
  uint64_t link_capacity_ = 0;      // words rad_links holds
  uint64_t links_ = 0, link_words_ = 0, raw_links_ = 0;
  uint32_t link_batches_ = 0, batch_elements_ = 0;
  uint64_t light_samples_ = 0;      // light-link shadow rays per light and run
  uint64_t link_builds_ = 0, light_link_runs_ = 0;
  MethodStats mesh_stats_;          // the refinement's and elements' figures, fixed after prepare
  MethodStats stats_;
};

}  // namespace pm

// The photon-mapping method (Fabianowski & Dingliana 2009): per pass, emit and trace a batch of
// photons (S1, S2), build their footprint ellipsoids (S3) and the photon map over them (S4),
// and gather at the camera pass's shading points into the film sums (S6). Memory is sized by
// one pass, never by the pass count (the multi-pass GPU photon map paper's batches), so any
// number of photons renders in bounded memory. The photon map of the last pass stays on the
// device: a camera-only frame whose first pass would trace the very same photons gathers from
// it again instead (docs/animation.md).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "render/indirect_method.h"
#include "render/photon/photon_settings.h"

namespace pm {

// The room the photon map and the hit records take for a pass of `hits` valid hits, so that the
// passes and frames after it do not reallocate: 8 standard deviations of a pass's count for its
// photons' noise (the count is a sum of many photons' hits: about its square root; small passes
// vary by several percent), and, when `changing` (a pass has recorded more hits than a room
// already measured held: the scene or its lights move), 1/16 more for what the animation changes
// next.
uint64_t hit_room(uint64_t hits, bool changing);

class PhotonMapping final : public IndirectMethod {
 public:
  PhotonMapping(const MethodContext& context, const PhotonSettings& settings);

  std::string describe() const override { return settings_.describe(); }
  uint32_t max_passes() const override { return 0; }
  uint32_t light_bounces() const override { return uint32_t(settings_.bounces); }
  bool may_be_biased() const override { return true; }
  bool passes_are_samples() const override { return false; }
  double noise_rate() const override { return settings_.final_gather > 0 ? kScrambledNetRate : kIndependentNoiseRate; }
  void begin_frame(const FrameContext& frame, const FrameChange& change) override;
  void run_pass(const FrameContext& frame, uint32_t pass) override;
  MethodStats stats() const override { return stats_; }
  std::vector<StageInfo> stages(const FrameContext& frame) const override;
  MethodWork work(uint32_t passes) const override;

  // The settings as resolved for the scene (rmax and radius defaults filled in).
  const PhotonSettings& settings() const { return settings_; }
  // Valid hits of the last pass: the sorted prefix the photon map covers.
  uint32_t last_hit_count() const { return map_params_.hit_count; }
  // The parameters the last pass's gather ran with.
  const LaunchParams& last_gather_params() const { return map_params_; }
  // Hit records of the largest pass (its photons * records per photon).
  uint32_t hit_slots() const { return photons_most_ * slots_per_photon_; }

 private:
  LaunchParams pass_params(const FrameContext& frame, uint32_t pass) const;
  // The lights' shares of `photons` (share_photons_by_power) into photon_emitters; kept until
  // the lights or the pass's count change.
  void share_photons(const std::vector<LightDesc>& lights, uint32_t photons);
  double area_power_ = 0;  // the area lights' summed RGB power (render/scene_emitters.h), fixed per scene
  double environment_power_ = 0;  // the environment's (render/scene_environment.h), fixed per scene
  void trace_and_build(LaunchParams params, StageTimer* timer);
  void build_vvh_map(const LaunchParams& params);
  // The buffers sized by the valid hits of a pass, not its photons: the hit records and the
  // photon map (sorted hits, footprints, nodes), each grown to room_for the hits of a pass that
  // needs more room. Allocates extents_ and sets the promise of the growth still possible.
  void reserve_map(uint32_t hits);
  void reserve_hit_records(uint32_t hits);
  void resize_growing_buffers();
  uint32_t room_for(uint32_t hits) const;
  bool hits_measured_ = false;  // a pass has sized the rooms by its hits: growth from then on means change
  // Bytes of the map and of the hit records with room for these many valid hits.
  uint64_t growing_bytes(uint64_t map_hits, uint64_t hit_records) const;
  // The most valid hits a pass is expected to record: the room the memory checks count.
  uint32_t expected_most_hits() const;
  void gather(const LaunchParams& params, StageTimer* timer);
  // The gather's tiles walk the map together when their first shading points lie within this
  // many mean footprint radii (PhotonSettings::tile_gather resolved for the device; 0: never).
  float tile_gather_ = 0;
  // T_auto's bounds for how this device walks the map (photon_map_leaf_size_within).
  uint32_t leaf_least_ = 1, leaf_most_ = 1u << 30;
  uint32_t gather_tiles_ = 0;  // pixel tiles of the film (pixel_order.h)

  Device& device_;
  BufferTable& buffers_;
  PhotonSettings settings_;
  double scene_area_ = 0;
  uint32_t photons_first_ = 0;   // a frame's first pass's (PhotonSettings::photons_in_pass)
  uint32_t photons_most_ = 0;    // the largest pass's: the buffers' photon extents
  uint32_t photons_shared_ = 0;  // the count photon_emitters holds the lights' shares of
  // Hit records the last trace took, of how many photons: a pass with more photons reserves
  // the records in proportion before it traces, instead of tracing twice.
  uint32_t last_records_ = 0;
  uint32_t last_traced_photons_ = 0;
  uint32_t slots_per_photon_ = 0;  // hit records per photon, for this scene's materials
  uint32_t shading_points_ = 0;
  uint32_t planned_passes_ = 1;  // a frame's passes as the renderer plans them: the stages' work per frame
  BufferExtents extents_;  // the photon group's sizes; map_hits and hit_records grow with the hits
  // The map and the records at the most hits a pass is expected to record, less what they hold.
  DeviceMemoryPromise growth_promise_;

  int photon_frame_ = 0;  // the frame number keying this frame's photons
  // The photon map on the device: valid after a pass went through, for the photons of
  // (map_photon_frame_, map_pass_) and the lights it was traced for.
  bool map_intact_ = false;
  int map_photon_frame_ = -1;
  uint32_t map_pass_ = 0;
  LaunchParams map_params_{};  // its fields: hit bounds and count, T
  double map_footprint_area_ = 0;
  float map_smoothing_ = 0;  // the s of its diffuse footprints (automatic or set)
  MethodStats stats_;
};

// Largest-remainder share of `total` photons by the lights' emitted power (summed over RGB; a
// spot's is its power times light_emitted_fraction), in light order, then one more share for
// the area lights together when area_power (their summed RGB power) is above zero, then one for
// the environment when environment_power (its flux through the scene's bounding sphere, summed
// over RGB) is above zero: the order of photon_emitters (kernels/common/photon_trace.h).
std::vector<uint32_t> share_photons_by_power(const std::vector<LightDesc>& lights, uint32_t total, double area_power = 0,
                                             double environment_power = 0);

}  // namespace pm

// The photon half of a frame (stages S1-S4 and S6): per batch of photons, trace them, build the
// footprint ellipsoids and the photon map, and gather into the film's indirect and caustic
// layers. Memory is sized by the batch, never by the total photon count (multi-pass photon
// batches), so any number of photons renders in bounded memory.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "render/device.h"
#include "render/scene.h"
#include "render/stage_timer.h"

namespace pm {

struct PhotonSettings {
  uint64_t photons = 262144;  // emitted per frame, all lights and batches together; 0: no photons
  uint32_t batch = 1u << 20;  // photons per pass (bounded memory); more passes = more photons
  int bounces = 2;            // diffuse bounces of indirect light
  float smoothing = 0.0f;     // s of section 4.3, diffusely reflected photons; 0: automatic per batch
                              // (render/footprint_scale.h)
  float rmax = 0.0f;          // footprint semiaxis clamp (knn: search radius), metres; 0: 10 % of the scene diagonal
  int estimator = PM_ESTIMATOR_PD;
  int kernel_shape = PM_KERNEL_CONSTANT;
  float radius = 0.0f;        // radius estimator, metres; 0: 5 % of the scene diagonal
  int knn_k = 64;             // knn estimator
  int leaf_threshold = 0;     // T; 0: T_auto
  float leaf_c = 0.5f;        // c of T_auto = c * footprint area / scene area, calibrated on the H200 (docs/algorithm.md)
  int sequence = PM_PHOTON_SEQUENCE_RANDOM;  // emission: random, or Halton (the same every frame)
  bool vvh_map = false;       // build the photon map with the voxel volume heuristic on the host
                              // (section 5.1, for the paper's Table 1 comparison) instead of the LBVH

  std::string describe() const;
};

// What one frame's photon work produced, for logs, EXR headers and benchmarks.
struct PhotonStats {
  int batches = 0;
  uint64_t hits = 0;                  // recorded hits, all batches
  double footprint_area = 0;          // total footprint area of the last batch, m^2
  uint32_t leaf_threshold = 0;        // T used for the last batch
  float smoothing = 0;                // s of the last batch's diffuse footprints (automatic or set)
  uint64_t gathered = 0;              // hits accepted by the gather (with collect_stats)
  uint64_t shading_points = 0;
};

class PhotonPass {
 public:
  PhotonPass(Device& device, const Scene& scene, const PhotonSettings& settings);

  // Photons per batch each light emits (shared out by power), in scene light order.
  const std::vector<uint32_t>& photons_per_light() const { return per_light_; }
  uint32_t photons_per_batch() const { return batch_size_; }
  const PhotonSettings& settings() const { return settings_; }

  // Shares the photons of a batch out among these lights by power (an animated scene's lights at
  // the frame about to be rendered; same count as the scene's). Invalidates the photon map.
  void set_lights(const std::vector<LightDesc>& lights);

  // Runs every batch for a frame whose camera pass has filled the shading points; adds into the
  // film_indirect and film_caustic buffers bound on the device (the caller zeroes them).
  // frame.photon_frame keys the photons' random numbers.
  void run(const LaunchParams& frame, PhotonStats* stats, StageTimer* timer = nullptr);

  // True when the device still holds the complete photon map of the last run: it had a single
  // batch (with several, each batch's map overwrites the previous one) and nothing failed since.
  bool map_intact() const { return map_intact_; }
  // Gathers again from that map for a new camera (the shading points of frame), without tracing:
  // the same result as run() with the lights and photon_frame of the last run. Requires
  // map_intact(). stats gets the last run's photon figures and this gather's counts.
  void gather_again(const LaunchParams& frame, PhotonStats* stats, StageTimer* timer = nullptr);

  // The buffer this pass binds to slot, or null (sort keys/values: the sorted pairs).
  const DeviceBuffer* buffer(BufferSlot slot) const;
  // Valid hits of the last batch: the sorted prefix the photon map covers.
  uint32_t last_hit_count() const { return last_hit_count_; }

 private:
  void allocate();
  void bind();  // this pass's buffers into the device's slots (another pass may have used them)
  LaunchParams pass_params(const LaunchParams& frame) const;
  void run_batch(LaunchParams params, PhotonStats* stats, StageTimer* timer);
  void build_vvh_map(const LaunchParams& params);
  void gather(const LaunchParams& params, StageTimer* timer);
  void finish_stats(const LaunchParams& params, PhotonStats* stats);
  DeviceBuffer& owned(BufferSlot slot);

  Device& device_;
  PhotonSettings settings_;
  double scene_area_ = 0;
  uint32_t batch_size_ = 0;
  uint32_t batch_count_ = 0;
  uint32_t slots_per_photon_ = 0;
  uint32_t last_hit_count_ = 0;
  std::vector<uint32_t> per_light_;
  bool map_intact_ = false;
  LaunchParams map_params_{};  // the map's fields (hit bounds and count, T) of the last batch
  PhotonStats map_stats_;      // what the run that built the map reported

  std::vector<DeviceBuffer> buffers_;
  SortBuffers sort_;
  DeviceBuffer stats_;
};

}  // namespace pm

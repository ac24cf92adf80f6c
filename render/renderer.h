// Frame orchestration: owns the device-side copy of one scene and runs the stages of a frame
// (S5 camera, S7 film; photon stages join here) through the backend-neutral Device interface.
// The scene BVH is built and uploaded once per Renderer, i.e. once per sequence.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "render/device.h"
#include "render/image.h"
#include "render/photon_pass.h"
#include "render/scene.h"

namespace pm {

struct RenderSettings {
  int mirror_depth = 1;  // eye-ray perfect-mirror bounces followed
  uint32_t seed = 1;
  int width = 0;   // 0: the scene camera's resolution
  int height = 0;
  PhotonSettings photons;

  std::string describe() const;  // one line for EXR headers and logs
};

struct FrameStats {
  double render_ms = 0;       // wall time from first launch to the frame's data back on the host
  int repaired_pixels = 0;    // non-finite pixels the film stage replaced by black
  PhotonStats photons;
};

class Renderer {
 public:
  Renderer(Device& device, const Scene& scene, const RenderSettings& settings);

  FrameImage render_frame(int frame, FrameStats* stats = nullptr);

  // Benchmarks attach a timer to get per-stage device times; null (the default) records nothing.
  void set_stage_timer(StageTimer* timer) { timer_ = timer; }
  // Gather counts photons per shading point (the paper's k_PD) into FrameStats.
  void set_collect_stats(bool on) { collect_stats_ = on; }

  int width() const { return width_; }
  // A device buffer of this frame's pipeline (renderer or photon pass), for tests and tools
  // that inspect intermediate results; null when the slot is not in use.
  const DeviceBuffer* buffer(BufferSlot slot) const;
  const PhotonPass* photon_pass() const { return photon_pass_.get(); }
  int height() const { return height_; }

 private:
  void upload_scene();
  void allocate_frame_buffers();
  LaunchParams frame_params(int frame) const;

  Device& device_;
  const Scene& scene_;
  RenderSettings settings_;
  int width_ = 0;
  int height_ = 0;

  DeviceBuffer scene_nodes_, triangles_, materials_, lights_;
  DeviceBuffer shade_position_, shade_normal_, shade_outgoing_, shade_weight_;
  DeviceBuffer film_direct_, film_indirect_, film_caustic_, film_combined_;
  std::unique_ptr<PhotonPass> photon_pass_;
  StageTimer* timer_ = nullptr;
  bool collect_stats_ = false;
};

// The camera basis the kernels expect (kernels/common/types.h CameraParams).
CameraParams make_camera_params(const CameraDesc& camera, int width, int height);
// The scene's materials and lights in the device structs' layout.
std::vector<Material> to_device_materials(const Scene& scene);
// photons_per_light: each light's photon count per batch, stored in power.w (types.h); the first
// photon index of each light within a batch goes to position.w.
std::vector<PointLight> to_device_lights(const Scene& scene, const std::vector<uint32_t>& photons_per_light = {});

}  // namespace pm

// Frame orchestration: owns the device-side copy of one scene and runs the stages of a frame
// (S5 camera, photon stages S1-S4 and S6, S7 film) through the backend-neutral Device interface.
// The scene BVH is built and uploaded once per Renderer, i.e. once per sequence: use one Renderer
// for all frames of an animation. Each frame evaluates the scene's camera and light tracks;
// when the lights are those of the photon map still on the device (camera-only motion), the
// photons are reused and only the gather runs again (docs/animation.md).
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
  // Camera-only frames of a sequence reuse the photons of the first frame of their run of
  // unchanged lights (random numbers keyed by that frame, map reused when still on the device).
  // false: every frame traces photons keyed by its own frame number, like a still render of it.
  bool reuse_photons = true;

  std::string describe() const;  // one line for EXR headers and logs
};

struct FrameStats {
  double render_ms = 0;       // wall time from first launch to the frame's data back on the host
  int repaired_pixels = 0;    // non-finite pixels the film stage replaced by black
  PhotonStats photons;
  bool photons_reused = false;  // the photon map of an earlier frame was gathered again, no tracing
  int photon_frame = 0;         // the frame number that keyed this frame's photons
};

class Renderer {
 public:
  Renderer(Device& device, const Scene& scene, const RenderSettings& settings);

  // Renders the scene as it is at `frame` (its tracks evaluated at frame / frame_rate). The result
  // depends on the frame number only, never on which frames this Renderer rendered before.
  // render() then read_image().
  FrameImage render_frame(int frame, FrameStats* stats = nullptr);
  // Runs every stage of a frame on the device and waits for it; the result stays in the film
  // buffers (benchmarks stop here: no read-back).
  void render(int frame, FrameStats* stats = nullptr);
  // The film of the last render(): layers combined, direct, indirect and caustic.
  FrameImage read_image(FrameStats* stats = nullptr);
  // The frame number whose random numbers key the photons of `frame` (RenderSettings::
  // reuse_photons; 0 for the Halton sequence, which does not depend on the frame).
  int photon_frame(int frame);

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
  void bind_buffers();  // every buffer into the device's slots: Renderers may share a device
  LaunchParams frame_params(int frame, const CameraDesc& camera) const;
  void set_lights(const std::vector<LightDesc>& lights);

  Device& device_;
  const Scene& scene_;
  RenderSettings settings_;
  int width_ = 0;
  int height_ = 0;
  float ray_epsilon_ = 0;  // LaunchParams::ray_epsilon of this scene (render/scene_scale.h)

  DeviceBuffer scene_nodes_, triangles_, materials_, lights_;
  DeviceBuffer shade_position_, shade_normal_, shade_outgoing_, shade_weight_;
  DeviceBuffer film_direct_, film_indirect_, film_caustic_, film_combined_;
  std::unique_ptr<PhotonPass> photon_pass_;
  StageTimer* timer_ = nullptr;
  bool collect_stats_ = false;

  std::vector<LightDesc> device_lights_;  // the lights in lights_ (and the photon shares)
  std::vector<LightDesc> map_lights_;     // the lights the photon map on the device was traced for
  int map_photon_frame_ = -1;             // and its photon frame
  int run_frame_ = -1, run_start_ = -1;   // light_run_start of the last frame asked (memo)
  std::vector<LightDesc> run_lights_;
};

// The camera basis the kernels expect (kernels/common/types.h CameraParams).
CameraParams make_camera_params(const CameraDesc& camera, int width, int height);
// The scene's materials and lights in the device structs' layout.
std::vector<Material> to_device_materials(const Scene& scene);
// photons_per_light: each light's photon count per batch, stored in power.w (types.h); the first
// photon index of each light within a batch goes to position.w.
std::vector<PointLight> to_device_lights(const Scene& scene, const std::vector<uint32_t>& photons_per_light = {});
std::vector<PointLight> to_device_lights(const std::vector<LightDesc>& lights,
                                         const std::vector<uint32_t>& photons_per_light = {});

}  // namespace pm

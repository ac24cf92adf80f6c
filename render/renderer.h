// Frame orchestration: owns the device-side copy of one scene (buffer table, scene BVH uploaded
// once per Renderer, i.e. once per sequence) and runs a frame as the camera pass (S5), the
// passes of the chosen indirect-light method (render/indirect_method.h), and the film resolve
// (S7). It knows no method: photon mapping and the others plug in through IndirectMethod.
// Each frame evaluates the scene's camera and light tracks and tells the method what changed
// since the previous frame, so it can reuse what the change leaves valid (docs/animation.md).
#pragma once

#include <cstdint>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "render/bias_control.h"
#include "render/buffer_table.h"
#include "render/device.h"
#include "render/film_layers.h"
#include "render/image.h"
#include "render/indirect_method.h"
#include "render/scene.h"
#include "render/scene_environment.h"
#include "render/stage_timer.h"

namespace pm {

struct SceneUpload;

struct RenderSettings {
  int mirror_depth = 1;  // eye-ray perfect-mirror bounces followed
  uint32_t seed = 1;
  int width = 0;   // 0: the scene camera's resolution
  int height = 0;
  uint32_t passes = 1;  // method passes per frame (capped by the method's max_passes)
  // Camera-only frames of a sequence reuse the lighting of the first frame of their run of
  // unchanged lights (random numbers keyed by that frame; work kept when still on the device).
  // false: every frame computes its lighting keyed by its own frame number, like a still render.
  bool reuse_lighting = true;
  // Paths per control pixel of the error estimate's bias control (render/bias_control.h) by the
  // time a frame's error is estimated; 0: the estimate sees noise only.
  uint32_t control_paths = 1024;
  // Light samples of the area lights, and as many of the environment, per shading point in the
  // camera pass (direct light) and per element in radiosity's light links; unused without
  // emitting materials or an environment.
  uint32_t area_light_samples = 16;
  std::shared_ptr<const MethodSettings> method;  // null: direct light only
  // Extra layers of the image (render/film_layers.h): none by default, and then no buffers,
  // no launch and no read-back for them.
  FilmLayers layers;

  // Throws SettingError naming the first setting out of range (the method's too).
  void validate() const;
};

struct FrameStats {
  double render_ms = 0;     // wall time from first launch to the frame's data back on the host
  int repaired_pixels = 0;  // non-finite pixels the film stage replaced by black
  uint32_t passes = 0;      // method passes summed in the film
  MethodStats method;       // the method's figures about this frame
};

// The film's sums as they stand after some passes: what a checkpoint stores and what several
// devices add up. One float4 per pixel each.
struct FilmSums {
  uint32_t passes = 0;
  uint32_t odd_passes = 0;  // of passes, those with an odd pass number
  std::vector<float4> indirect, caustic, odd;
  // The error control's paths for these passes' frame, when they come with the sums (--method
  // auto's race): set_film_sums takes them over, so the frame's next estimate starts as sharp as
  // the race's last. Empty otherwise (checkpoints, other devices).
  SharedControl control;
};

class Renderer {
 public:
  // upload: the scene's host-side upload when another renderer of the same scene prepared it
  // (render/scene_upload.h); null: this renderer prepares its own. host_work: the method's host
  // work begun from the scene alone where the caller began it (--method auto, once for the
  // candidates it serves); null: the renderer begins it (MethodSettings::begin_host_work) before
  // it builds the scene's BVH and uploads the scene, which it then runs beside.
  Renderer(Device& device, const Scene& scene, const RenderSettings& settings,
           std::shared_ptr<const SceneUpload> upload = nullptr, std::shared_ptr<const HostWorkAhead> host_work = nullptr);
  // The renderer keeps a reference to its scene: a temporary one would be gone by the first frame.
  Renderer(Device& device, const Scene&& scene, const RenderSettings& settings,
           std::shared_ptr<const SceneUpload> upload = nullptr,
           std::shared_ptr<const HostWorkAhead> host_work = nullptr) = delete;
  ~Renderer();

  // Renders the scene as it is at `frame` (its tracks evaluated at frame / frame_rate): the
  // camera pass, settings.passes method passes, and (render_frame) the read-back, which
  // resolves the film. The result depends on the frame number only, never on which frames this
  // Renderer rendered before.
  FrameImage render_frame(int frame, FrameStats* stats = nullptr);
  void render(int frame, FrameStats* stats = nullptr);

  // The same frame in steps, for callers that decide the pass count as they go: begin_frame
  // (camera pass, film sums cleared), run_pass any number of times, read_image (the film
  // resolved over the passes so far) at any point between passes.
  void begin_frame(int frame);
  void run_pass();
  uint32_t passes_done() const { return passes_done_; }
  // Waits until the device has finished everything launched so far.
  void wait() { device_.synchronize(); }
  // Pass `pass` of the frame, whichever passes ran before: several renderers (devices) share one
  // frame's passes, each running its own subset; their sums add up to the frame's.
  void run_pass(uint32_t pass);

  // Expected relative error of the indirect light (indirect + caustic) of the passes so far.
  // For a method that may be biased, the relative mean absolute error at the bias control's pixels, noise
  // and bias together (render/bias_control.h: each call adds paths there, up to control_paths
  // when `final`). Otherwise, or with the control off, the noise alone: the mean absolute
  // difference between the even and the odd passes' means, scaled to the mean of all passes, over
  // the mean indirect light (docs/progressive.md; needs an even and an odd pass). Negative when
  // unknown. Waits for the device.
  // noise_scale: the noise part's factor (a device holding part of a frame's passes).
  double estimate_error(bool final = false, double noise_scale = 1.0);
  // The noise part alone (negative when unknown), and the control's last comparison.
  double estimate_noise();
  const BiasEstimate& last_bias() const { return last_bias_; }
  // The last estimate's upper end (the control's estimate plus two standard errors): a target
  // error stops a frame on this, so that a lucky low control does not stop it early.
  double last_error_upper() const { return last_error_upper_; }

  // --method auto's race (render/method_race.h): a control shared between the renderers of one
  // frame grown by `samples` paths per control pixel on this renderer's device, and this film
  // (the passes so far) at the control pixels, for compare_with_control against it: the
  // relative mean absolute error, noise and bias together, of any method, the path tracer's
  // included. Wait for the device.
  void grow_shared_control(SharedControl& shared, uint32_t samples);
  std::vector<float4> film_at_control();
  // The method's own bias measured along `samples` more control paths per control pixel, added
  // to probe (paired_bias reads it), where the method has such a measure
  // (IndirectMethod::launch_bias_probe); returns false, and adds nothing, where not.
  bool grow_bias_probe(SharedControl& probe, uint32_t samples);
  // The passes that film holds, for compare_with_control's bias_floor.
  ControlFilmPasses film_passes_at_control() const { return {passes_done_, odd_passes_}; }
  const ControlGrid& error_control_grid() const { return control_->grid(); }
  // The light bounces the control follows for this renderer's method.
  uint32_t control_bounces() const;

  // The film sums (waits for the device), and sums put back or added in: a checkpoint's resume,
  // or another device's passes. set_film_sums also sets the pass count; add_film_sums adds it.
  FilmSums film_sums();
  void set_film_sums(const FilmSums& sums);
  void add_film_sums(const FilmSums& sums);
  // The film over the passes so far, resolved (film_combine): layers combined, direct, indirect
  // and caustic, then the extra layers settings.layers asks for (their order in film_layers.cpp).
  FrameImage read_image(FrameStats* stats = nullptr);

  // Benchmarks attach a timer to get per-stage device times; null (the default) records nothing.
  void set_stage_timer(StageTimer* timer) { frame_.timer = timer; }
  // Methods count their per-stage work (e.g. photons per gather) into their stats.
  void set_collect_stats(bool on) { frame_.collect_stats = on; }

  const FilmLayers& layers() const { return settings_.layers; }
  int width() const { return width_; }
  // The mirror bounces eye rays take here: the settings', or 0 where the scene has no mirror.
  int mirror_depth() const { return mirror_depth_; }
  // Whether the film keeps a caustic sum: only a scene with mirrors makes caustics (film.h).
  bool has_caustic_film() const { return bool(buffers_[BufferSlot::film_caustic_sum]); }
  int height() const { return height_; }
  Device& device() const { return device_; }
  // Every device buffer of the pipeline, for tests and tools that inspect intermediate results.
  const BufferTable& buffers() const { return buffers_; }
  // Device bytes of the scene's textures: texels, descriptors, texture coordinates and the sRGB
  // table (0 for an untextured scene, which uploads none).
  uint64_t texture_bytes() const;
  // The method of this renderer, or null (direct light only).
  IndirectMethod* method() const { return method_.get(); }
  // The settings as resolved for this scene, one line for EXR headers and logs.
  std::string describe() const;
  // Every stage of a frame in order (camera, the method's, film), with its work per frame.
  std::vector<StageInfo> stages() const;
  // What the constructor took, step by step (BVH build, scene upload, buffers, the method), and
  // when the first frame began (its camera pass launched): the end of start-up, for reports.
  const std::vector<StartupStep>& setup_steps() const { return setup_steps_; }
  bool has_begun_a_frame() const { return rendered_before_; }
  StartupClock::time_point first_frame_begun() const { return first_frame_begun_; }

 private:
  void upload_scene(StepClock& clock, std::shared_ptr<const SceneUpload> upload);
  void set_lights(const std::vector<LightDesc>& lights);
  int light_run_start(int frame, const std::vector<LightDesc>& lights);

  Device& device_;
  const Scene& scene_;
  RenderSettings settings_;
  int width_ = 0;
  int height_ = 0;
  // The mirror bounces eye rays can take here: settings' mirror_depth, or 0 in a scene without
  // mirrors, whose shading points then take a record a pixel rather than mirror_depth + 1.
  int mirror_depth_ = 0;
  SceneMeasures measures_;
  BufferTable buffers_;
  std::unique_ptr<IndirectMethod> method_;
  std::unique_ptr<BiasControl> control_;
  BiasEstimate last_bias_;
  double last_error_upper_ = -1;
  std::chrono::steady_clock::time_point frame_begun_;  // begin_frame's call: the frame's time so far

  FrameContext frame_;            // the frame being rendered (timer and stats switch persist)
  uint32_t passes_done_ = 0;      // passes summed in the film
  uint32_t odd_passes_ = 0;       // of those, the ones with an odd pass number
  uint32_t next_pass_ = 0;        // the pass run_pass() runs
  bool rendered_before_ = false;  // a frame was begun on this renderer
  std::vector<StartupStep> setup_steps_;
  StartupClock::time_point first_frame_begun_{};
  CameraDesc last_camera_;
  std::vector<LightDesc> device_lights_;  // the lights in the lights buffer
  uint32_t emitter_count_ = 0;  // area lights: emitting triangles uploaded (render/scene_emitters.h)
  float emitter_power_ = 0;
  EnvironmentDistribution environment_;  // its type and size; texels and CDFs live on the device
  int run_frame_ = -1, run_start_ = -1;   // light_run_start of the last frame asked (memo)
};

// The camera basis the kernels expect (kernels/common/types.h CameraParams).
CameraParams make_camera_params(const CameraDesc& camera, int width, int height);
// The scene's materials and lights in the device structs' layout.
std::vector<Material> to_device_materials(const Scene& scene);
std::vector<PointLight> to_device_lights(const std::vector<LightDesc>& lights);

}  // namespace pm

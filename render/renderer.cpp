// Frame orchestration over the Device interface: scene upload once, then per frame the camera
// pass, the method's passes into the film sums, and the read-back, which resolves the film, into a
// FrameImage with its layers.
#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <sstream>

#include "kernels/common/film.h"
#include "kernels/common/pixel_order.h"
#include "render/errors.h"
#include "render/scene_bvh.h"
#include "render/scene_emitters.h"
#include "render/scene_environment.h"
#include "render/scene_frame.h"
#include "render/scene_scale.h"
#include "render/scene_textures.h"
#include "render/scene_upload.h"

namespace pm {

namespace {

Float3 sub(Float3 a, Float3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Float3 cross(Float3 a, Float3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
Float3 scaled(Float3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
Float3 normalized(Float3 a) { return scaled(a, 1.0f / std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z)); }
float4 to_float4(Float3 a) { return float4{a.x, a.y, a.z, 0.0f}; }

bool same_camera(const CameraDesc& a, const CameraDesc& b) {
  return std::memcmp(&a.position, &b.position, sizeof(Float3)) == 0 &&
         std::memcmp(&a.look_at, &b.look_at, sizeof(Float3)) == 0 && std::memcmp(&a.up, &b.up, sizeof(Float3)) == 0 &&
         a.vertical_fov_degrees == b.vertical_fov_degrees;
}

}  // namespace

void RenderSettings::validate() const {
  if (mirror_depth < 0 || mirror_depth > 16)
    throw SettingError("mirror-depth", "expected 0 to 16, got " + std::to_string(mirror_depth));
  if (width < 0 || height < 0 || width > 16384 || height > 16384)
    throw SettingError("resolution", "expected each side from 1 to 16384, got " + std::to_string(width) + "x" +
                                         std::to_string(height));
  if (passes < 1) throw SettingError("passes", "expected at least 1 pass, got 0");
  if (area_light_samples < 1 || area_light_samples > 65536)
    throw SettingError("area-light-samples", "expected 1 to 65536, got " + std::to_string(area_light_samples));
  if (method) method->validate();
}

CameraParams make_camera_params(const CameraDesc& camera, int width, int height) {
  Float3 forward = normalized(sub(camera.look_at, camera.position));
  Float3 right = normalized(cross(forward, camera.up));
  Float3 up = cross(right, forward);
  float tan_half = std::tan(camera.vertical_fov_degrees * 0.5f * float(PM_PI) / 180.0f);
  float aspect = float(width) / float(height);
  CameraParams params{};
  params.position = to_float4(camera.position);
  params.forward = to_float4(forward);
  params.right = to_float4(scaled(right, tan_half * aspect));
  params.up = to_float4(scaled(up, tan_half));
  return params;
}

std::vector<Material> to_device_materials(const Scene& scene) {
  std::vector<Material> materials;
  for (const MaterialDesc& m : scene.materials) {
    Material gpu{};
    gpu.diffuse = to_float4(m.diffuse);
    gpu.glossy = float4{m.glossy.x, m.glossy.y, m.glossy.z, m.glossy_exponent};
    gpu.mirror = to_float4(m.mirror);
    set_material_textures(m, &gpu);
    materials.push_back(gpu);
  }
  return materials;
}

std::vector<PointLight> to_device_lights(const std::vector<LightDesc>& scene_lights) {
  std::vector<PointLight> lights;
  for (const LightDesc& l : scene_lights) {
    PointLight light{to_float4(l.position), to_float4(l.power), float4{0, 0, 1, 0}};
    light.position.w = light.power.w = -1.0f;  // an isotropic point light (spot_light.h)
    if (l.type == LightType::spot) {
      light.position.w = float(std::cos(double(l.outer_cone)));
      light.power.w = float(std::cos(double(l.inner_cone)));
      light.axis = to_float4(normalized(l.direction));
    }
    lights.push_back(light);
  }
  return lights;
}

Renderer::Renderer(Device& device, const Scene& scene, const RenderSettings& settings,
                   std::shared_ptr<const SceneUpload> upload, std::shared_ptr<const HostWorkAhead> host_work)
    : device_(device), scene_(scene), settings_(settings), buffers_(device) {
  settings_.validate();
  width_ = settings.width > 0 ? settings.width : scene.camera.width;
  height_ = settings.height > 0 ? settings.height : scene.camera.height;
  mirror_depth_ = scene.has_mirrors() ? settings_.mirror_depth : 0;
  StepClock clock;
  measures_ = measure_scene(scene);
  setup_steps_.push_back({"scene measures", clock.lap_ms(), "bounds, ray epsilon"});
  // The method's host work first, on a thread of its own, so that it runs beside the BVH build.
  if (!host_work && settings_.method) host_work = settings_.method->begin_host_work(scene, measures_);
  upload_scene(clock, std::move(upload));
  BufferExtents extents;
  extents.pixels = uint64_t(width_) * uint64_t(height_);
  extents.shading_points = extents.pixels * uint64_t(mirror_depth_ + 1);
  extents.error_tiles = (extents.pixels + PM_FILM_ERROR_TILE - 1) / PM_FILM_ERROR_TILE;
  extents.layer_pixels = settings_.layers.empty() ? 0 : extents.pixels;
  // Only a mirror can send a photon to a diffuse surface by specular bounces alone: without one the
  // caustic layer is zero, and the film keeps no sum for it (kernels/common/film.h).
  extents.caustic_pixels = scene.has_mirrors() ? extents.pixels : 0;
  extents.control_pixels = control_grid(width_, height_).pixels();
  buffers_.allocate(BufferGroup::frame, extents);
  control_ = std::make_unique<BiasControl>(device_, buffers_, width_, height_);
  setup_steps_.push_back({"frame buffers", clock.lap_ms(), "film, shading points, error control"});
  if (settings_.method) {
    MethodContext context{device_,  scene_,  measures_, buffers_, width_, height_, uint32_t(extents.shading_points),
                          settings_.passes, std::move(host_work)};
    method_ = settings_.method->create(context);
    setup_steps_.push_back({"method setup", clock.lap_ms(), settings_.method->method_name()});
  }
}

// Freeing a buffer unbinds it from the device's slot table (DeviceBuffer::reset).
Renderer::~Renderer() = default;

void Renderer::upload_scene(StepClock& clock, std::shared_ptr<const SceneUpload> upload) {
  if (!upload) upload = prepare_scene_upload(scene_, clock, &setup_steps_);
  else setup_steps_.push_back({"BVH build", clock.lap_ms(), "shared with the renderers of this scene"});
  const SceneBvh& bvh = upload->bvh;
  const DeviceTextures& textures = upload->textures;
  buffers_.upload(BufferSlot::scene_nodes, bvh.nodes);
  buffers_.upload(BufferSlot::triangles, bvh.triangles);
  buffers_.upload(BufferSlot::materials, upload->materials);
  // Textures once per scene; an untextured scene leaves the three buffers unallocated (null).
  if (!textures.info.empty()) buffers_.upload(BufferSlot::texture_info, textures.info);
  if (!textures.texels.empty()) buffers_.upload(BufferSlot::texels, textures.texels);
  if (!textures.uvs.empty()) buffers_.upload(BufferSlot::triangle_uvs, textures.uvs);
  if (!textures.srgb_table.empty()) buffers_.upload(BufferSlot::texture_srgb_table, textures.srgb_table);
  // Area lights likewise: a scene without emitting materials allocates neither buffer.
  const SceneEmitters& emitters = upload->emitters;
  if (emitters.count > 0) {
    buffers_.upload(BufferSlot::emitters, emitters.records);
    buffers_.upload(BufferSlot::material_emission, emitters.material_emission);
  }
  emitter_count_ = emitters.count;
  emitter_power_ = float(emitters.power);
  // The environment map likewise, once per scene; the constant environment needs no buffer.
  if (upload->environment.type == PM_ENVIRONMENT_MAP) {
    buffers_.upload(BufferSlot::environment_texels, upload->environment.texels);
    buffers_.upload(BufferSlot::environment_cdf, upload->environment.cdf);
  }
  // On the device now; the launch parameters need the type and sizes only.
  environment_.type = upload->environment.type;
  environment_.width = upload->environment.width;
  environment_.height = upload->environment.height;
  set_lights(scene_.lights);
  setup_steps_.push_back({"scene upload", clock.lap_ms(), "BVH, triangles, materials, textures, lights, environment"});
}

uint64_t Renderer::texture_bytes() const {
  return buffers_[BufferSlot::texture_info].bytes() + buffers_[BufferSlot::texels].bytes() +
         buffers_[BufferSlot::triangle_uvs].bytes() + buffers_[BufferSlot::texture_srgb_table].bytes();
}

void Renderer::set_lights(const std::vector<LightDesc>& lights) {
  if (!device_lights_.empty() && same_lights(lights, device_lights_)) return;
  device_lights_.clear();  // unknown until the upload went through
  const std::vector<PointLight> device_lights = to_device_lights(lights);
  if (device_lights.empty()) buffers_.upload(BufferSlot::lights, std::vector<PointLight>(1, PointLight{}));
  else buffers_.upload(BufferSlot::lights, device_lights);
  device_lights_ = lights;
}

std::string Renderer::describe() const {
  std::ostringstream s;
  // The estimator's settings; the pass count is the budget's (pmrender/passes in EXR headers).
  s << width_ << "x" << height_ << " mirror_depth=" << settings_.mirror_depth << " seed=" << settings_.seed;
  if (!settings_.reuse_lighting) s << " reuse=off";
  // The environment, which the command line may change for the same scene file: part of the
  // checkpoint fingerprint, so a resumed frame is never finished under another sky.
  const EnvironmentDesc& env = scene_.environment;
  if (environment_.type == PM_ENVIRONMENT_CONSTANT)
    s << " environment=" << env.radiance.x << "," << env.radiance.y << "," << env.radiance.z;
  else if (environment_.type == PM_ENVIRONMENT_MAP)
    s << " environment=" << env.map_file << " environment_scale=" << env.scale
      << " environment_rotation=" << env.rotation_degrees;
  if (method_) s << " method=" << settings_.method->method_name() << " " << method_->describe();
  else s << " method=none";
  return s.str();
}

std::vector<StageInfo> Renderer::stages() const {
  const double pixels = double(width_) * height_;
  std::vector<StageInfo> list;
  list.push_back({"camera", pixels * double(1 + scene_.lights.size()), "rays/s",
                  "primary + one shadow ray per light per pixel (mirror rays not counted)"});
  if (method_)
    for (StageInfo& s : method_->stages(frame_)) list.push_back(std::move(s));
  return list;
}

int Renderer::light_run_start(int frame, const std::vector<LightDesc>& lights) {
  if (!scene_.animation.enabled) return frame;
  // Frames rendered in order: the previous frame's answer holds while the lights stay.
  int start;
  if (frame == run_frame_ + 1 && frame > scene_.animation.first_frame && same_lights(lights, device_lights_))
    start = run_start_;
  else
    start = pm::light_run_start(scene_, frame);
  run_frame_ = frame;
  run_start_ = start;
  return start;
}

void Renderer::begin_frame(int frame) {
  if (frame < 0) throw InputError("frame numbers start at 0, got " + std::to_string(frame));
  const CameraDesc camera = camera_at_frame(scene_, frame);
  const std::string problem = camera_problem(camera);
  if (!problem.empty()) throw InputError(scene_.source + ": camera at frame " + std::to_string(frame) + ": " + problem);
  const std::vector<LightDesc> lights = lights_at_frame(scene_, frame);

  FrameChange change;
  change.first = !rendered_before_;
  change.lights = change.first || !same_lights(lights, device_lights_);
  change.camera = change.first || !same_camera(camera, last_camera_);
  frame_.light_run_start = light_run_start(frame, lights);  // before set_lights: compares with the last frame's
  set_lights(lights);
  if (!rendered_before_) first_frame_begun_ = StartupClock::now();
  rendered_before_ = true;
  last_camera_ = camera;

  LaunchParams& p = frame_.params;
  p = LaunchParams{};
  p.camera = make_camera_params(camera, width_, height_);
  p.width = uint32_t(width_);
  p.height = uint32_t(height_);
  p.triangle_count = uint32_t(scene_.triangle_count());
  p.light_count = uint32_t(lights.size());
  p.emitter_count = emitter_count_;
  p.emitter_power = emitter_power_;
  p.area_light_samples = settings_.area_light_samples;
  set_environment_params(environment_, scene_.environment, measures_, &p);
  p.path_mis = 1u;  // paths of the error estimate's bias control; the path method sets its own
  p.ray_epsilon = measures_.ray_epsilon;
  p.mirror_depth = uint32_t(mirror_depth_);
  p.film_caustic = has_caustic_film() ? 1u : 0u;
  p.seed = settings_.seed;
  p.frame = uint32_t(frame);
  p.collect_stats = frame_.collect_stats ? 1u : 0u;
  frame_.frame = frame;
  frame_.reuse_lighting = settings_.reuse_lighting;
  frame_.lights = &device_lights_;

  buffers_.bind_all();
  {
    StageScope scope(frame_.timer, "camera");
    device_.launch(KernelId::camera_pass, pixel_work_items(p.width, p.height), p);
    // The extra layers read the shading points just recorded, before any method's pass.
    if (!settings_.layers.empty()) device_.launch(KernelId::film_layers, p.width * p.height, p);
  }
  // The camera pass has zeroed the odd-pass sum's red in the direct layer's w (film.h).
  for (BufferSlot sum : {BufferSlot::film_indirect_sum, BufferSlot::film_odd_blue, BufferSlot::film_caustic_sum})
    if (buffers_[sum]) device_.fill_zero(buffers_[sum], buffers_[sum].bytes());
  passes_done_ = 0;
  odd_passes_ = 0;
  next_pass_ = 0;
  control_->begin_frame();
  last_bias_ = BiasEstimate{};
  frame_begun_ = std::chrono::steady_clock::now();
  if (method_) method_->begin_frame(frame_, change);
}

void Renderer::run_pass() { run_pass(next_pass_); }

void Renderer::run_pass(uint32_t pass) {
  if (!method_) throw DeviceError("renderer: no indirect-light method to run a pass of");
  // Several renderers may share a device (--method auto's race, render/method_race.h): its slot
  // table then holds the buffers of whichever ran last. Binding ours again changes nothing, and
  // costs nothing, when they are bound already.
  buffers_.bind_all();
  frame_.params.pass_index = pass;
  method_->run_pass(frame_, pass);
  ++passes_done_;
  odd_passes_ += pass & 1u;
  next_pass_ = pass + 1;
}

double Renderer::estimate_error(bool final, double noise_scale) {
  buffers_.bind_all();  // as in run_pass
  double noise = estimate_noise();
  if (noise >= 0) noise *= noise_scale;
  if (method_ && method_->may_be_biased() && settings_.control_paths > 0 && passes_done_ > 0) {
    // Paths in steps as passes go (a budget asks after every pass), topped up at the end.
    // (A launch of no paths still reads the film at the control pixels again.)
    const uint64_t have = control_->paths();
    const uint64_t want = final ? std::max<uint64_t>(have, settings_.control_paths)
                                : have + std::min<uint32_t>(settings_.control_paths, kControlPathsPerStep);
    LaunchParams p = frame_.params;
    p.max_bounces = method_->light_bounces();
    p.film_passes = passes_done_;
    p.film_odd_passes = odd_passes_;  // the film's own noise told from its bias (bias_floor)
    last_bias_ = control_->add_and_compare(p, uint32_t(want - have), film_passes_at_control());
    // Where the path tracer is noisy (a small lamp in a closed box), the control's own noise
    // can dwarf the film's error: at the end of a frame the control doubles its paths, up to
    // kControlPathsGrowth times control_paths, until its noise per pixel is below the error it
    // reads there and the mean over pixels resolves that error to a quarter of itself; and
    // only while the growth takes no longer than the frame had taken (a doubling costs about
    // twice the paths already there).
    auto unresolved = [](const BiasEstimate& b) {
      const double error = b.mean_abs_error - b.mean_abs_error_stderr;
      return b.control_noise > error || b.mean_abs_error_stderr > 0.25 * error;
    };
    using Clock = std::chrono::steady_clock;
    const Clock::time_point growth_begun = Clock::now();
    const double frame_s = std::chrono::duration<double>(growth_begun - frame_begun_).count();
    double last_step_s = frame_s, growth_s = 0;
    while (final && last_bias_.known && control_->paths() < uint64_t(settings_.control_paths) * kControlPathsGrowth &&
           unresolved(last_bias_) && growth_s + (growth_s > 0 ? 2.0 * last_step_s : 0.0) <= frame_s) {
      const Clock::time_point step_begun = Clock::now();
      last_bias_ = control_->add_and_compare(p, uint32_t(control_->paths()), film_passes_at_control());
      last_step_s = std::chrono::duration<double>(Clock::now() - step_begun).count();
      growth_s = std::chrono::duration<double>(Clock::now() - growth_begun).count();
    }
  }
  // The control measures noise and bias together; without it, the even/odd noise is all we know.
  last_error_upper_ = last_bias_.known ? last_bias_.mean_abs_error_upper : noise;
  return last_bias_.known ? last_bias_.mean_abs_error : noise;
}

uint32_t Renderer::control_bounces() const { return method_ ? method_->light_bounces() : 0u; }

void Renderer::grow_shared_control(SharedControl& shared, uint32_t samples) {
  if (!control_) throw DeviceError("renderer: no error control on this renderer");
  buffers_.bind_all();  // as in run_pass
  LaunchParams p = frame_.params;
  p.max_bounces = control_bounces();
  p.film_passes = passes_done_ > 0 ? passes_done_ : 1u;
  control_->grow_shared(p, shared, samples);
  shared.bounces = p.max_bounces;
}

bool Renderer::grow_bias_probe(SharedControl& probe, uint32_t samples) {
  if (!control_ || !method_ || !method_->has_bias_probe()) return false;
  buffers_.bind_all();  // as in run_pass
  LaunchParams p = frame_.params;
  p.max_bounces = control_bounces();
  control_->grow_shared(p, probe, samples, [&](const LaunchParams& control, uint64_t work_items) {
    method_->launch_bias_probe(frame_, control, work_items);
  });
  probe.bounces = p.max_bounces;
  return true;
}

std::vector<float4> Renderer::film_at_control() {
  buffers_.bind_all();  // as in run_pass
  LaunchParams p = frame_.params;
  p.max_bounces = control_bounces();
  p.film_passes = passes_done_ > 0 ? passes_done_ : 1u;
  p.film_odd_passes = odd_passes_;  // the odd passes' mean in w: the film's own noise there
  return control_->film_at_control(p);
}

double Renderer::estimate_noise() {
  if (odd_passes_ == 0 || odd_passes_ == passes_done_) return -1.0;
  LaunchParams p = frame_.params;
  p.film_passes = passes_done_;
  p.film_odd_passes = odd_passes_;
  const uint32_t tiles = uint32_t(buffers_[BufferSlot::film_error_partials].bytes() / sizeof(float4));
  device_.launch(KernelId::film_error_tiles, tiles, p);
  std::vector<float4> partials(tiles);
  device_.download(buffers_[BufferSlot::film_error_partials], partials.data(), tiles * sizeof(float4));
  double difference = 0, level = 0;
  for (const float4& t : partials) {
    difference += t.x;
    level += t.y;
  }
  if (!(level > 0)) return -1.0;
  // Var(even mean - odd mean) = s^2 (1/n_even + 1/n_odd) and Var(mean of all) = s^2 / K, so the
  // mean of all deviates by |even - odd| / sqrt(K (1/n_even + 1/n_odd)) (2 for n_even = n_odd);
  // the mean absolute deviations scale alike for any symmetric noise.
  const double k = passes_done_, odd = odd_passes_, even = k - odd;
  return difference / std::sqrt(k * (1.0 / even + 1.0 / odd)) / level;
}

void Renderer::render(int frame, FrameStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  begin_frame(frame);
  if (method_) {
    const uint32_t cap = method_->max_passes();
    const uint32_t passes = cap > 0 && cap < settings_.passes ? cap : settings_.passes;
    for (uint32_t i = 0; i < passes; ++i) run_pass();
  }
  wait();  // the host wall time below is the frame's real time
  const auto end = std::chrono::steady_clock::now();
  if (stats) {
    stats->render_ms = std::chrono::duration<double, std::milli>(end - start).count();
    stats->passes = passes_done_;
    stats->method = method_ ? method_->stats() : MethodStats{};
  }
}

FrameImage Renderer::render_frame(int frame, FrameStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  render(frame, stats);
  FrameImage image = read_image(stats);
  if (stats) stats->render_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return image;
}

}  // namespace pm

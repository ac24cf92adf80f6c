// Frame orchestration over the Device interface: scene upload once, then per frame the camera
// pass and the film resolve, and the read-back into a FrameImage with its layers.
#include "render/renderer.h"

#include <chrono>
#include <cstring>
#include <cmath>
#include <sstream>
#include <vector>

#include "animations/scene_animation.h"
#include "render/errors.h"
#include "render/scene_bvh.h"
#include "render/scene_scale.h"

namespace pm {

namespace {

Float3 sub(Float3 a, Float3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Float3 cross(Float3 a, Float3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
Float3 scaled(Float3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
Float3 normalized(Float3 a) { return scaled(a, 1.0f / std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z)); }
float4 to_float4(Float3 a) { return float4{a.x, a.y, a.z, 0.0f}; }

template <typename T>
DeviceBuffer upload_vector(Device& device, const std::vector<T>& data, const char* what) {
  DeviceBuffer buffer = device.allocate(data.size() * sizeof(T), what);
  device.upload(buffer, data.data(), data.size() * sizeof(T));
  return buffer;
}

std::vector<float> rgb_from_float4(const std::vector<float4>& pixels) {
  std::vector<float> rgb(pixels.size() * 3);
  for (size_t i = 0; i < pixels.size(); ++i) {
    rgb[3 * i + 0] = pixels[i].x;
    rgb[3 * i + 1] = pixels[i].y;
    rgb[3 * i + 2] = pixels[i].z;
  }
  return rgb;
}

}  // namespace

std::string RenderSettings::describe() const {
  std::ostringstream s;
  s << "mirror_depth=" << mirror_depth << " seed=" << seed << " " << photons.describe();
  if (!reuse_photons) s << " photon_reuse=off";
  return s.str();
}

CameraParams make_camera_params(const CameraDesc& camera, int width, int height) {
  Float3 forward = normalized(sub(camera.look_at, camera.position));
  Float3 right = normalized(cross(forward, camera.up));
  Float3 up = cross(right, forward);
  float tan_half = std::tan(camera.vertical_fov_degrees * 0.5f * float(M_PI) / 180.0f);
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
    materials.push_back(gpu);
  }
  return materials;
}

std::vector<PointLight> to_device_lights(const Scene& scene, const std::vector<uint32_t>& photons_per_light) {
  return to_device_lights(scene.lights, photons_per_light);
}

std::vector<PointLight> to_device_lights(const std::vector<LightDesc>& scene_lights,
                                         const std::vector<uint32_t>& photons_per_light) {
  std::vector<PointLight> lights;
  uint32_t first = 0;
  for (size_t i = 0; i < scene_lights.size(); ++i) {
    PointLight light{to_float4(scene_lights[i].position), to_float4(scene_lights[i].power)};
    uint32_t count = i < photons_per_light.size() ? photons_per_light[i] : 0;
    std::memcpy(&light.position.w, &first, 4);
    std::memcpy(&light.power.w, &count, 4);
    first += count;
    lights.push_back(light);
  }
  return lights;
}

Renderer::Renderer(Device& device, const Scene& scene, const RenderSettings& settings)
    : device_(device), scene_(scene), settings_(settings) {
  width_ = settings.width > 0 ? settings.width : scene.camera.width;
  height_ = settings.height > 0 ? settings.height : scene.camera.height;
  if (settings.mirror_depth < 0 || settings.mirror_depth > 16)
    throw InputError("--mirror-depth: expected 0 to 16, got " + std::to_string(settings.mirror_depth));
  if (settings.photons.photons > 0) photon_pass_ = std::make_unique<PhotonPass>(device, scene, settings.photons);
  ray_epsilon_ = scene_ray_epsilon(scene);
  upload_scene();
  allocate_frame_buffers();
}

void Renderer::upload_scene() {
  SceneBvh bvh = build_scene_bvh(scene_);
  scene_nodes_ = upload_vector(device_, bvh.nodes, "scene BVH nodes");
  triangles_ = upload_vector(device_, bvh.triangles, "scene triangles");

  materials_ = upload_vector(device_, to_device_materials(scene_), "materials");
  lights_ = upload_vector(device_, to_device_lights(scene_, photon_pass_ ? photon_pass_->photons_per_light()
                                                                          : std::vector<uint32_t>{}),
                         "point lights");
  device_lights_ = scene_.lights;

}

void Renderer::allocate_frame_buffers() {
  const size_t pixels = size_t(width_) * size_t(height_);
  const size_t records = pixels * size_t(settings_.mirror_depth + 1);
  shade_position_ = device_.allocate(records * sizeof(float4), "shading point positions");
  shade_normal_ = device_.allocate(records * sizeof(float4), "shading point normals");
  shade_outgoing_ = device_.allocate(records * sizeof(float4), "shading point directions");
  shade_weight_ = device_.allocate(records * sizeof(float4), "shading point weights");
  film_direct_ = device_.allocate(pixels * sizeof(float4), "direct light layer");
  film_indirect_ = device_.allocate(pixels * sizeof(float4), "indirect light layer");
  film_caustic_ = device_.allocate(pixels * sizeof(float4), "caustic layer");
  film_combined_ = device_.allocate(pixels * sizeof(float4), "combined layer");
  bind_buffers();
}

void Renderer::bind_buffers() {
  device_.bind(BufferSlot::scene_nodes, scene_nodes_);
  device_.bind(BufferSlot::triangles, triangles_);
  device_.bind(BufferSlot::materials, materials_);
  device_.bind(BufferSlot::lights, lights_);
  device_.bind(BufferSlot::shade_position, shade_position_);
  device_.bind(BufferSlot::shade_normal, shade_normal_);
  device_.bind(BufferSlot::shade_outgoing, shade_outgoing_);
  device_.bind(BufferSlot::shade_weight, shade_weight_);
  device_.bind(BufferSlot::film_direct, film_direct_);
  device_.bind(BufferSlot::film_indirect, film_indirect_);
  device_.bind(BufferSlot::film_caustic, film_caustic_);
  device_.bind(BufferSlot::film_combined, film_combined_);
}

const DeviceBuffer* Renderer::buffer(BufferSlot slot) const {
  switch (slot) {
    case BufferSlot::shade_position: return &shade_position_;
    case BufferSlot::shade_normal: return &shade_normal_;
    case BufferSlot::shade_outgoing: return &shade_outgoing_;
    case BufferSlot::shade_weight: return &shade_weight_;
    case BufferSlot::film_direct: return &film_direct_;
    case BufferSlot::film_indirect: return &film_indirect_;
    case BufferSlot::film_caustic: return &film_caustic_;
    case BufferSlot::film_combined: return &film_combined_;
    default: return photon_pass_ ? photon_pass_->buffer(slot) : nullptr;
  }
}

void Renderer::set_lights(const std::vector<LightDesc>& lights) {
  if (same_lights(lights, device_lights_)) return;
  if (photon_pass_) photon_pass_->set_lights(lights);
  const std::vector<PointLight> device_lights =
      to_device_lights(lights, photon_pass_ ? photon_pass_->photons_per_light() : std::vector<uint32_t>{});
  device_lights_.clear();  // unknown until the upload went through
  device_.upload(lights_, device_lights.data(), device_lights.size() * sizeof(PointLight));
  device_lights_ = lights;
}

int Renderer::photon_frame(int frame) {
  if (settings_.photons.sequence == PM_PHOTON_SEQUENCE_HALTON) return 0;
  if (!settings_.reuse_photons || !scene_.animation.enabled) return frame;
  const std::vector<LightDesc> lights = lights_at_frame(scene_, frame);
  // Frames rendered in order: the previous frame's answer holds while the lights stay.
  int start;
  if (frame == run_frame_ + 1 && frame > scene_.animation.first_frame && same_lights(lights, run_lights_))
    start = run_start_;
  else
    start = light_run_start(scene_, frame);
  run_frame_ = frame;
  run_start_ = start;
  run_lights_ = lights;
  return start;
}

LaunchParams Renderer::frame_params(int frame, const CameraDesc& camera) const {
  LaunchParams p{};
  p.camera = make_camera_params(camera, width_, height_);
  p.width = uint32_t(width_);
  p.height = uint32_t(height_);
  p.triangle_count = uint32_t(scene_.triangle_count());
  p.light_count = uint32_t(scene_.lights.size());
  p.ray_epsilon = ray_epsilon_;
  p.mirror_depth = uint32_t(settings_.mirror_depth);
  p.seed = settings_.seed;
  p.frame = uint32_t(frame);
  p.photon_frame = uint32_t(frame);
  p.collect_stats = collect_stats_ ? 1u : 0u;
  return p;
}

FrameImage Renderer::render_frame(int frame, FrameStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  render(frame, stats);
  FrameImage image = read_image(stats);
  if (stats) stats->render_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return image;
}

void Renderer::render(int frame, FrameStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  if (frame < 0) throw InputError("frame numbers start at 0, got " + std::to_string(frame));
  const CameraDesc camera = camera_at_frame(scene_, frame);
  const std::string problem = camera_problem(camera);
  if (!problem.empty()) throw InputError(scene_.source + ": camera at frame " + std::to_string(frame) + ": " + problem);
  const std::vector<LightDesc> lights = lights_at_frame(scene_, frame);
  bind_buffers();
  set_lights(lights);
  LaunchParams params = frame_params(frame, camera);
  params.photon_frame = uint32_t(photon_frame(frame));
  const uint32_t pixels = params.width * params.height;
  PhotonStats photon_stats;
  {
    StageScope scope(timer_, Stage::camera);
    device_.launch(KernelId::camera_pass, pixels, params);
  }
  device_.fill_zero(film_indirect_, film_indirect_.bytes());
  device_.fill_zero(film_caustic_, film_caustic_.bytes());
  bool reused = false;
  if (photon_pass_) {
    reused = settings_.reuse_photons && photon_pass_->map_intact() && map_photon_frame_ == int(params.photon_frame) &&
             same_lights(lights, map_lights_);
    if (reused) {
      photon_pass_->gather_again(params, &photon_stats, timer_);
    } else {
      map_photon_frame_ = -1;
      photon_pass_->run(params, &photon_stats, timer_);
      map_photon_frame_ = int(params.photon_frame);
      map_lights_ = lights;
    }
  }

  {
    StageScope scope(timer_, Stage::film);
    device_.launch(KernelId::film_resolve, pixels, params);
  }
  device_.synchronize();  // the frame is done: host wall time below is the frame's real time
  const auto end = std::chrono::steady_clock::now();
  if (stats) {
    stats->photons = photon_stats;
    stats->render_ms = std::chrono::duration<double, std::milli>(end - start).count();
    stats->photons_reused = reused;
    stats->photon_frame = int(params.photon_frame);
  }
}

FrameImage Renderer::read_image(FrameStats* stats) {
  const size_t pixels = size_t(width_) * height_;
  std::vector<float4> combined(pixels), direct(pixels), indirect(pixels), caustic(pixels);
  device_.download(film_combined_, combined.data(), pixels * sizeof(float4));
  device_.download(film_direct_, direct.data(), pixels * sizeof(float4));
  device_.download(film_indirect_, indirect.data(), pixels * sizeof(float4));
  device_.download(film_caustic_, caustic.data(), pixels * sizeof(float4));
  int repaired = 0;
  for (const float4& px : combined) repaired += px.w != 0.0f;

  FrameImage image;
  image.width = width_;
  image.height = height_;
  image.layers.push_back(ImageLayer{"", rgb_from_float4(combined)});
  image.layers.push_back(ImageLayer{"direct", rgb_from_float4(direct)});
  image.layers.push_back(ImageLayer{"indirect", rgb_from_float4(indirect)});
  image.layers.push_back(ImageLayer{"caustic", rgb_from_float4(caustic)});
  if (stats) stats->repaired_pixels = repaired;
  return image;
}

}  // namespace pm

// The glTF 2.0 loader's entry and last steps (scene_io/gltf_loader.h has the whole loader): the
// camera (the first or the named perspective one), KHR_lights_punctual point and spot lights, their node
// animations sampled at every frame, and the Scene they make. glTF units are metres, so nothing
// is rescaled.
#include "scene_io/gltf_scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "render/scene_frame.h"
#include "scene_io/animation_json.h"
#include "scene_io/gltf_animation.h"
#include "scene_io/gltf_loader.h"
#include "scene_io/load_error.h"

namespace pm {

double candela_to_watts(double candela, double colour) { return colour * 4.0 * M_PI * candela / kLumensPerWatt; }

double roughness_to_phong_exponent(double roughness) {
  const double alpha = roughness * roughness;
  if (alpha == 0) return INFINITY;
  return std::max(0.0, 2.0 / (alpha * alpha) - 2.0);
}

namespace gltf {

namespace fs = std::filesystem;

int GltfLoader::choose_camera_node() {
  std::vector<std::string> names;
  for (int node : order_) {
    const tinygltf::Node& n = model_.nodes[size_t(node)];
    if (n.camera < 0) continue;
    const std::string where = indexed("nodes", size_t(node)) + ".camera";
    if (size_t(n.camera) >= model_.cameras.size()) fail(where, "camera index " + std::to_string(n.camera) + " out of range");
    const tinygltf::Camera& camera = model_.cameras[size_t(n.camera)];
    const std::string label = n.name.empty() ? camera.name : n.name;
    names.push_back(label.empty() ? "nodes[" + std::to_string(node) + "]" : label);
    if (!camera_name_.empty() && n.name != camera_name_ && camera.name != camera_name_) continue;
    if (camera.type != "perspective") {
      if (!camera_name_.empty())
        fail(indexed("cameras", size_t(n.camera)), "camera '" + camera_name_ + "' is " + camera.type + "; only perspective cameras are supported");
      continue;
    }
    return node;
  }
  if (!camera_name_.empty()) {
    std::string list;
    for (const std::string& name : names) list += (list.empty() ? "" : ", ") + name;
    fail(indexed("scenes", size_t(scene_index_)) + ".extras.pmrender.camera",
         "no camera node named '" + camera_name_ + "' (camera nodes: " + (list.empty() ? "none" : list) + ")");
  }
  fail("cameras", "the scene has no node with a perspective camera");
}

CameraDesc GltfLoader::camera_at(int node, double t, bool animated) const {
  const tinygltf::Camera& c = model_.cameras[size_t(model_.nodes[size_t(node)].camera)];
  const Mat4 world = world_matrix(node, t, animated);
  const Vec3d position = gltf::transform_point(world, {0, 0, 0});
  Vec3d forward = gltf::transform_direction(world, {0, 0, -1});
  const Vec3d up = gltf::transform_direction(world, {0, 1, 0});
  const double length = std::sqrt(forward[0] * forward[0] + forward[1] * forward[1] + forward[2] * forward[2]);
  CameraDesc camera;
  camera.position = Float3{float(position[0]), float(position[1]), float(position[2])};
  if (length > 0)
    for (double& v : forward) v /= length;
  camera.look_at = Float3{float(position[0] + forward[0]), float(position[1] + forward[1]), float(position[2] + forward[2])};
  camera.up = Float3{float(up[0]), float(up[1]), float(up[2])};
  camera.vertical_fov_degrees = float(c.perspective.yfov * 180.0 / M_PI);
  camera.width = width_;
  camera.height = height_;
  return camera;
}

// A spot light's axis at time t: the node's -z axis in world space.
Vec3d GltfLoader::light_direction_at(int node, double t, bool animated) const {
  return gltf::transform_direction(world_matrix(node, t, animated), {0, 0, -1});
}

void GltfLoader::read_lights(Scene& scene) {
  for (int node : order_) {
    const tinygltf::Node& n = model_.nodes[size_t(node)];
    auto ext = n.extensions.find("KHR_lights_punctual");
    if (ext == n.extensions.end()) continue;
    const std::string where = indexed("nodes", size_t(node)) + ".extensions.KHR_lights_punctual";
    if (!ext->second.Has("light") || !ext->second.Get("light").IsInt()) fail(where + ".light", "expected a light index");
    const int index = ext->second.Get("light").Get<int>();
    if (index < 0 || size_t(index) >= model_.lights.size())
      fail(where + ".light", "light index " + std::to_string(index) + " out of range (" + std::to_string(model_.lights.size()) + " lights)");
    const tinygltf::Light& l = model_.lights[size_t(index)];
    const std::string light_where = "extensions.KHR_lights_punctual.lights[" + std::to_string(index) + "]";
    if (l.type != "point" && l.type != "spot") {
      warn(light_where + quoted_name(l.name) + ": " + l.type + " lights are not supported (point and spot lights only); skipped");
      continue;
    }
    if (!(l.intensity >= 0) || !std::isfinite(l.intensity))
      fail(light_where + ".intensity", "must be a finite number >= 0 candela, got " + str(l.intensity));
    double colour[3] = {1, 1, 1};
    if (!l.color.empty()) {
      if (l.color.size() != 3) fail(light_where + ".color", "expected 3 numbers");
      for (int c = 0; c < 3; ++c) {
        colour[c] = l.color[size_t(c)];
        if (!(colour[c] >= 0 && colour[c] <= 1))
          fail(light_where + ".color[" + std::to_string(c) + "]", "must be in [0, 1], got " + str(colour[c]));
      }
    }
    if (l.range > 0) warn(light_where + quoted_name(l.name) + ": range is ignored (light falls off with the inverse square only)");
    LightDesc light;
    if (l.type == "spot") {
      const double inner = l.spot.innerConeAngle, outer = l.spot.outerConeAngle;
      if (!(outer > 0 && outer <= M_PI / 2))
        fail(light_where + ".spot.outerConeAngle", "must be in (0, pi/2] radians, got " + str(outer));
      if (!(inner >= 0 && inner < outer))
        fail(light_where + ".spot.innerConeAngle", "must be in [0, outerConeAngle = " + str(outer) + ") radians, got " + str(inner));
      const Vec3d d = light_direction_at(node, 0.0, false);
      if (!(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > 0))
        fail(indexed("nodes", size_t(node)), "the spot light's node transform has no direction (zero scale)");
      light.type = LightType::spot;
      light.direction = Float3{float(d[0]), float(d[1]), float(d[2])};
      light.inner_cone = float(inner);
      light.outer_cone = float(outer);
    }
    light.name = !l.name.empty() ? l.name : !n.name.empty() ? n.name : "light" + std::to_string(scene.lights.size());
    const Vec3d p = gltf::transform_point(world_matrix(node, 0.0, false), {0, 0, 0});
    light.position = Float3{float(p[0]), float(p[1]), float(p[2])};
    light.power = Float3{float(candela_to_watts(l.intensity, colour[0])), float(candela_to_watts(l.intensity, colour[1])),
                         float(candela_to_watts(l.intensity, colour[2]))};
    scene.lights.push_back(light);
    light_nodes_.push_back(node);
  }
  if (emissive_textures_ > 0)
    warn(first_emissive_texture_ + ": emissiveTexture is not rendered (" + std::to_string(emissive_textures_) +
         " materials have one): their emission is emissiveFactor's alone");
  if (environment_) scene.environment = *environment_;
  // Checked before anything is built or traced: a scene without light renders black.
  if (!scene.has_light())
    fail("extensions.KHR_lights_punctual", "no light: no KHR_lights_punctual point or spot light with intensity above zero and no emissive material (emissiveFactor) on any triangle");
}

// Samples the camera's and the lights' node animations at every frame of the range into linear
// keyframe tracks (exact at every frame; nothing between frames is ever rendered).
void GltfLoader::read_animation(Scene& scene) {
  bool camera_animated = node_is_animated(camera_node_);
  bool lights_animated = false;
  for (int node : light_nodes_) lights_animated |= node_is_animated(node);
  const bool animated = camera_animated || lights_animated;
  if (!animated && !has_frames_ && !has_frame_rate_) return;  // a still scene

  SceneAnimation& a = scene.animation;
  a.enabled = true;
  a.frame_rate = frame_rate_;
  if (has_frames_) {
    a.first_frame = first_frame_;
    a.last_frame = last_frame_;
  } else {
    double last_time = 0;
    for (const gltf::Sampler& s : samplers_) last_time = std::max(last_time, s.last_time());
    a.first_frame = 0;
    a.last_frame = default_last_frame(last_time, frame_rate_);
    if (a.last_frame + 1LL > kMaxSequenceFrames)
      fail("animations", "the animation lasts " + str(last_time) + " s, more than " + std::to_string(kMaxSequenceFrames) +
                             " frames at " + str(frame_rate_) + " frames per second; set extras.pmrender.frames");
  }
  auto key_time = [&](int f) { return double(f) / a.frame_rate; };  // as frame_time() computes it
  if (camera_animated) {
    CameraAnimation& c = a.camera;
    c.position.interpolation = c.look_at.interpolation = c.up.interpolation = Interpolation::linear;
    for (int f = a.first_frame; f <= a.last_frame; ++f) {
      const CameraDesc at = camera_at(camera_node_, key_time(f), true);
      c.position.keys.push_back({key_time(f), {at.position.x, at.position.y, at.position.z}});
      c.look_at.keys.push_back({key_time(f), {at.look_at.x, at.look_at.y, at.look_at.z}});
      c.up.keys.push_back({key_time(f), {at.up.x, at.up.y, at.up.z}});
    }
  }
  if (lights_animated) {
    a.lights.assign(scene.lights.size(), LightAnimation{});
    for (size_t i = 0; i < light_nodes_.size(); ++i) {
      if (!node_is_animated(light_nodes_[i])) continue;
      Vec3Track& track = a.lights[i].position;
      for (int f = a.first_frame; f <= a.last_frame; ++f) {
        const Vec3d p = gltf::transform_point(world_matrix(light_nodes_[i], key_time(f), true), {0, 0, 0});
        track.keys.push_back({key_time(f), {float(p[0]), float(p[1]), float(p[2])}});
      }
      if (scene.lights[i].type != LightType::spot) continue;
      // A spot turns with its node: its axis is a track too.
      Vec3Track& direction = a.lights[i].direction;
      for (int f = a.first_frame; f <= a.last_frame; ++f) {
        const Vec3d d = light_direction_at(light_nodes_[i], key_time(f), true);
        if (!(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > 0))
          fail(indexed("nodes", size_t(light_nodes_[i])), "the spot light has no direction at frame " + std::to_string(f) + " (zero scale)");
        direction.keys.push_back({key_time(f), {float(d[0]), float(d[1]), float(d[2])}});
      }
    }
  }
  for (long long f = a.first_frame; f <= a.last_frame; ++f) {
    const std::string problem = camera_problem(camera_at_frame(scene, int(f)));
    if (!problem.empty()) fail(indexed("nodes", size_t(camera_node_)), "camera at frame " + std::to_string(f) + ": " + problem);
  }
}

Scene GltfLoader::load() {
  parse_file();
  if (model_.scenes.empty()) fail("scenes", "the file has no scene");
  scene_index_ = model_.defaultScene >= 0 ? model_.defaultScene : 0;
  if (size_t(scene_index_) >= model_.scenes.size()) fail("scene", "scene index " + std::to_string(scene_index_) + " out of range");
  read_extras();
  build_hierarchy();
  read_animations();

  Scene scene;
  SceneTextures textures(&scene);
  textures_ = &textures;
  scene.source = path_;
  scene.name = !scene_name_.empty() ? scene_name_ : fs::path(path_).stem().string();
  read_meshes(scene);

  camera_node_ = choose_camera_node();
  const tinygltf::Camera& camera = model_.cameras[size_t(model_.nodes[size_t(camera_node_)].camera)];
  const double yfov = camera.perspective.yfov;
  if (!(yfov > 0 && yfov < M_PI))
    fail(indexed("cameras", size_t(model_.nodes[size_t(camera_node_)].camera)) + ".perspective.yfov",
         "must be in (0, pi) radians, got " + str(yfov));
  const double aspect = camera.perspective.aspectRatio;
  if (!has_resolution_) {
    height_ = int(kDefaultHeight);
    width_ = aspect > 0 ? int(std::clamp(std::round(kDefaultHeight * aspect), 1.0, double(kMaxResolution))) : int(kDefaultHeight);
  } else if (aspect > 0 && std::fabs(double(width_) / height_ / aspect - 1) > 0.01) {
    warn("camera aspectRatio " + str(aspect) + " differs from the resolution's " + str(double(width_) / height_) +
         "; the vertical field of view is kept");
  }
  scene.camera = camera_at(camera_node_, 0.0, false);
  const std::string problem = camera_problem(scene.camera);
  if (!problem.empty()) fail(indexed("nodes", size_t(camera_node_)), "camera: " + problem);

  textures_ = nullptr;
  read_lights(scene);
  read_animation(scene);
  // A still scene shows its nodes at rest; a sequence's static values are those of its first frame.
  if (scene.animation.enabled) {
    scene.camera = camera_at_frame(scene, scene.animation.first_frame);
    scene.lights = lights_at_frame(scene, scene.animation.first_frame);
  }
  return scene;
}

}  // namespace gltf

Scene load_gltf_scene(const std::string& path, SceneLoadReport* report, const EnvironmentDesc* environment) {
  SceneLoadReport local_report;
  SceneLoadReport* r = report ? report : &local_report;
  *r = SceneLoadReport{};
  return gltf::GltfLoader(path, r, environment).load();
}

}  // namespace pm

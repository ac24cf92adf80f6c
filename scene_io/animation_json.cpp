// Owns reading the "animation" object of a JSON scene: tracks (interpolation + keys of time and
// value), the frame rate and range, the camera's and the named lights' tracks.
#include "scene_io/animation_json.h"

#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <sstream>

#include "render/scene_frame.h"
#include "scene_io/lights_camera_json.h"
#include "scene_io/load_error.h"

namespace pm {
namespace {

const long long kMaxFrameNumber = 999999999;  // what --frames can name (9 digits)

std::string seconds(double t) {
  std::ostringstream s;
  s << t;
  return s.str();
}

// {"interpolation": "linear"|"smooth"|"step", "keys": [{"time": t, "value": v}, ...]}; read_value
// turns one key's "value" field into the track's value type.
template <int N>
Track<N> read_track(const JsonField& field, const std::function<std::array<float, N>(const JsonField&)>& read_value,
                    double* last_key_time) {
  field.expect_object_with_keys({"interpolation", "keys"});
  Track<N> track;
  if (field.has("interpolation")) {
    const JsonField interpolation = field.member("interpolation");
    const std::string name = interpolation.non_empty_string();
    if (!parse_interpolation(name, &track.interpolation))
      interpolation.fail("expected \"linear\", \"smooth\" or \"step\", got \"" + name + "\"");
  }
  const JsonField keys = field.member("keys");
  const size_t count = keys.expect_array();
  if (count == 0) keys.fail("a track needs at least one key");
  for (size_t i = 0; i < count; ++i) {
    const JsonField key = keys.element(i);
    key.expect_object_with_keys({"time", "value"});
    const JsonField time = key.member("time");
    typename Track<N>::Key k;
    k.time = time.finite_number();
    if (i > 0 && !(k.time > track.keys.back().time))
      time.fail("must be after the previous key's time " + seconds(track.keys.back().time) + " s, got " +
                describe_json_value(time.value()));
    k.value = read_value(key.member("value"));
    track.keys.push_back(k);
  }
  *last_key_time = std::max(*last_key_time, track.keys.back().time);
  return track;
}

std::array<float, 3> as_array(const Float3& v) { return {v.x, v.y, v.z}; }

// A key's position in metres, bounded as the scene's static positions are (lights_camera_json.h).
std::array<float, 3> read_position(const JsonField& value, double meters_per_unit) {
  return as_array(read_position_in_metres(value, meters_per_unit));
}

std::array<float, 3> read_direction(const JsonField& value) {
  const Float3 v = value.float3();
  if (!(v.x != 0 || v.y != 0 || v.z != 0)) value.fail("must not be the zero vector");
  return as_array(v);
}

std::array<float, 1> read_fov(const JsonField& value) {
  const double degrees = value.finite_number();
  if (!(degrees > 0 && degrees < 180)) value.fail("must be in (0, 180) degrees, got " + describe_json_value(value.value()));
  return {static_cast<float>(degrees)};
}

std::array<float, 3> read_power(const JsonField& value) {
  const Float3 power = value.float3();
  const float p[3] = {power.x, power.y, power.z};
  for (size_t c = 0; c < 3; ++c) {
    if (p[c] < 0) value.element(c).fail("must be >= 0 W, got " + describe_json_value(value.element(c).value()));
  }
  return as_array(power);
}

void read_camera_tracks(const JsonField& field, double meters_per_unit, CameraAnimation* camera, double* last_time) {
  field.expect_object_with_keys({"position", "look_at", "up", "vertical_fov"});
  auto position = [&](const JsonField& v) { return read_position(v, meters_per_unit); };
  if (field.has("position")) camera->position = read_track<3>(field.member("position"), position, last_time);
  if (field.has("look_at")) camera->look_at = read_track<3>(field.member("look_at"), position, last_time);
  if (field.has("up")) camera->up = read_track<3>(field.member("up"), read_direction, last_time);
  if (field.has("vertical_fov")) camera->vertical_fov = read_track<1>(field.member("vertical_fov"), read_fov, last_time);
}

void read_light_tracks(const JsonField& field, double meters_per_unit, Scene* scene, double* last_time) {
  if (!field.value().is_object()) field.fail("expected an object (light name -> tracks), got " + describe_json_value(field.value()));
  std::multimap<std::string, size_t> by_name;
  for (size_t i = 0; i < scene->lights.size(); ++i) by_name.emplace(scene->lights[i].name, i);
  scene->animation.lights.assign(scene->lights.size(), LightAnimation{});
  auto position = [&](const JsonField& v) { return read_position(v, meters_per_unit); };
  for (const auto& item : field.value().items()) {
    const JsonField light(field.file(), item.value(), field.path() + "." + item.key());
    const size_t matches = by_name.count(item.key());
    if (matches == 0) {
      std::string names;
      for (const LightDesc& l : scene->lights) names += (names.empty() ? "" : ", ") + l.name;
      light.fail("no light of that name (lights: " + names + ")");
    }
    if (matches > 1) light.fail(std::to_string(matches) + " lights have this name; animated lights need unique names");
    LightAnimation& a = scene->animation.lights[by_name.find(item.key())->second];
    light.expect_object_with_keys({"position", "power", "direction"});
    if (light.has("position")) a.position = read_track<3>(light.member("position"), position, last_time);
    if (light.has("power")) a.power = read_track<3>(light.member("power"), read_power, last_time);
    if (light.has("direction")) {
      const JsonField direction = light.member("direction");
      if (scene->lights[by_name.find(item.key())->second].type != LightType::spot)
        direction.fail("only a spot light has a direction");
      a.direction = read_track<3>(direction, read_direction, last_time);
    }
  }
}

}  // namespace

int default_last_frame(double last_key_time, double frame_rate) {
  if (!(last_key_time > 0)) return 0;
  const double frames = std::ceil(last_key_time * frame_rate - 1e-9);
  return frames > double(kMaxFrameNumber) ? int(kMaxFrameNumber) : int(frames);
}

void check_animated_camera(const Scene& scene, const JsonField& where) {
  for (long long f = scene.animation.first_frame; f <= scene.animation.last_frame; ++f) {
    const std::string problem = camera_problem(camera_at_frame(scene, int(f)));
    if (!problem.empty())
      where.fail("at frame " + std::to_string(f) + " (t = " + seconds(frame_time(scene, int(f))) + " s): " + problem);
  }
}

void read_animation_json(const JsonField& field, double meters_per_unit, Scene* scene) {
  field.expect_object_with_keys({"frame_rate", "frames", "camera", "lights"});
  SceneAnimation& animation = scene->animation;
  animation = SceneAnimation{};
  animation.enabled = true;
  if (field.has("frame_rate")) {
    const JsonField rate = field.member("frame_rate");
    animation.frame_rate = rate.finite_number();
    if (!(animation.frame_rate > 0 && animation.frame_rate <= 1e6))
      rate.fail("must be in (0, 1e6] frames per second, got " + describe_json_value(rate.value()));
  }
  double last_time = -std::numeric_limits<double>::infinity();
  if (field.has("camera")) read_camera_tracks(field.member("camera"), meters_per_unit, &animation.camera, &last_time);
  if (field.has("lights")) read_light_tracks(field.member("lights"), meters_per_unit, scene, &last_time);

  if (field.has("frames")) {
    const JsonField frames = field.member("frames");
    frames.expect_array(2);
    animation.first_frame = int(frames.element(0).integer_in(0, kMaxFrameNumber));
    animation.last_frame = int(frames.element(1).integer_in(0, kMaxFrameNumber));
    if (animation.last_frame < animation.first_frame)
      frames.element(1).fail("the last frame is before the first (" + std::to_string(animation.first_frame) + ")");
  } else {
    animation.first_frame = 0;
    animation.last_frame = default_last_frame(last_time, animation.frame_rate);
  }
  if (static_cast<long long>(animation.last_frame) - animation.first_frame + 1 > kMaxSequenceFrames)
    field.fail("the sequence has " + std::to_string(static_cast<long long>(animation.last_frame) - animation.first_frame + 1) +
               " frames, more than the " + std::to_string(kMaxSequenceFrames) + " allowed");
  check_animated_camera(*scene, field.has("camera") ? field.member("camera") : field);
}

}  // namespace pm

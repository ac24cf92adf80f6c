// Animated scenes: the "animation" object of JSON scene files (frame rate, range, camera and light
// tracks, unit conversion, every error naming the field), evaluation at frames, the light runs
// that photon reuse relies on, and the flicker measure.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "scene_io/frame_spec.h"
#include "render/image_metrics.h"
#include "render/scene_frame.h"
#include "render/errors.h"
#include "scene_io/scene_file.h"
#include "support/test_folder.h"

namespace pm {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json animated_scene() {
  return json::parse(R"({
    "format": "pmrender-scene", "version": 1, "meters_per_unit": 0.5,
    "meshes": [ { "file": "tri.obj" } ],
    "lights": [ { "name": "key", "position": [0, 4, 0], "power": [1, 1, 1] },
                { "name": "fill", "position": [2, 4, 0], "power": [0.5, 0.5, 0.5] } ],
    "camera": { "position": [0, 0, -10], "look_at": [0, 0, 0], "resolution": [64, 48] },
    "animation": {
      "frame_rate": 10,
      "camera": {
        "position": { "interpolation": "smooth", "keys": [
          { "time": 0, "value": [0, 0, -10] }, { "time": 1, "value": [4, 0, -10] }, { "time": 2, "value": [4, 2, -8] } ] },
        "vertical_fov": { "keys": [ { "time": 0, "value": 40 }, { "time": 2, "value": 60 } ] }
      },
      "lights": {
        "key": { "position": { "keys": [ { "time": 0, "value": [0, 4, 0] }, { "time": 0.5, "value": [2, 4, 0] } ] },
                 "power": { "interpolation": "step", "keys": [ { "time": 0, "value": [1, 1, 1] },
                                                               { "time": 1.5, "value": [2, 0, 1] } ] } }
      }
    }
  })");
}

class AnimationJson : public test::FolderTest {
 protected:
  AnimationJson() : FolderTest("pm_animation_json_") {}
  void SetUp() override {
    FolderTest::SetUp();
    write("tri.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
  }

  Scene load(const json& scene) {
    std::ofstream(dir_ / "scene.json") << scene.dump(2);
    return load_scene_file((dir_ / "scene.json").string());
  }
  // The one-line InputError of loading `scene`, which must name the file and contain `expected`.
  void expect_error(const json& scene, const std::string& expected) {
    try {
      load(scene);
      ADD_FAILURE() << "loaded; expected an error containing: " << expected;
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind((dir_ / "scene.json").string() + ": ", 0), 0u) << message;
      EXPECT_NE(message.find(expected), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }
};

TEST_F(AnimationJson, ReadsTracksInMetresAndSeconds) {
  const Scene scene = load(animated_scene());
  const SceneAnimation& a = scene.animation;
  ASSERT_TRUE(a.enabled);
  EXPECT_EQ(a.frame_rate, 10.0);
  EXPECT_EQ(a.first_frame, 0);
  EXPECT_EQ(a.last_frame, 20);  // the last key is at 2 s
  ASSERT_EQ(a.camera.position.keys.size(), 3u);
  EXPECT_EQ(a.camera.position.interpolation, Interpolation::smooth);
  EXPECT_EQ(a.camera.position.keys[2].value, (std::array<float, 3>{2.0f, 1.0f, -4.0f}));  // x 0.5 m per unit
  EXPECT_TRUE(a.camera.look_at.empty());
  EXPECT_EQ(a.camera.vertical_fov.keys[1].value[0], 60.0f);  // degrees are not scaled
  ASSERT_EQ(a.lights.size(), 2u);
  EXPECT_EQ(a.lights[0].position.keys[1].value, (std::array<float, 3>{1.0f, 2.0f, 0.0f}));
  EXPECT_EQ(a.lights[0].power.keys[1].value, (std::array<float, 3>{2.0f, 0.0f, 1.0f}));  // watts are not scaled
  EXPECT_TRUE(a.lights[1].empty());
}

TEST_F(AnimationJson, FramesShowTheTracksAtFrameOverFrameRate) {
  const Scene scene = load(animated_scene());
  EXPECT_DOUBLE_EQ(frame_time(scene, 15), 1.5);
  const CameraDesc c10 = camera_at_frame(scene, 10);  // t = 1 s: the middle key
  EXPECT_EQ(c10.position.x, 2.0f);
  EXPECT_EQ(c10.position.z, -5.0f);
  EXPECT_EQ(c10.look_at.z, 0.0f);             // no look_at track: the static camera's
  EXPECT_FLOAT_EQ(c10.vertical_fov_degrees, 50.0f);
  EXPECT_EQ(c10.width, 64);

  const std::vector<LightDesc> l2 = lights_at_frame(scene, 2);  // t = 0.2 s: 40 % along the key's path
  EXPECT_FLOAT_EQ(l2[0].position.x, 0.4f);
  EXPECT_EQ(l2[1].position.x, 1.0f);  // the fill light does not move
  EXPECT_EQ(lights_at_frame(scene, 14)[0].power.x, 1.0f);  // step: the old power until 1.5 s
  EXPECT_EQ(lights_at_frame(scene, 15)[0].power.x, 2.0f);
  EXPECT_EQ(lights_at_frame(scene, 500)[0].power.y, 0.0f);  // held after the last key
}

TEST_F(AnimationJson, ExplicitFramesAndDefaults) {
  json scene = animated_scene();
  scene["animation"]["frames"] = {5, 12};
  const Scene explicit_range = load(scene);
  EXPECT_EQ(explicit_range.animation.first_frame, 5);
  EXPECT_EQ(explicit_range.animation.last_frame, 12);

  scene = animated_scene();
  scene["animation"] = json::object();  // a sequence of one frame: no tracks, 24 fps
  const Scene empty = load(scene);
  EXPECT_TRUE(empty.animation.enabled);
  EXPECT_EQ(empty.animation.frame_rate, 24.0);
  EXPECT_EQ(empty.animation.last_frame, 0);
  scene["animation"]["frames"] = {0, 9};  // a static sequence of ten frames
  EXPECT_EQ(load(scene).animation.last_frame, 9);

  json still = animated_scene();
  still.erase("animation");
  EXPECT_FALSE(load(still).animation.enabled);
}

TEST_F(AnimationJson, LightRunsStartWhereTheLightsLastChanged) {
  const Scene scene = load(animated_scene());
  // The key light moves until 0.5 s (frame 5), then holds until its power steps at 1.5 s (15).
  EXPECT_EQ(light_run_start(scene, 0), 0);
  EXPECT_EQ(light_run_start(scene, 3), 3);
  EXPECT_EQ(light_run_start(scene, 5), 5);
  EXPECT_EQ(light_run_start(scene, 6), 5);
  EXPECT_EQ(light_run_start(scene, 14), 5);
  EXPECT_EQ(light_run_start(scene, 15), 15);
  EXPECT_EQ(light_run_start(scene, 20), 15);
  EXPECT_EQ(light_run_start(scene, 40), 15);  // beyond the range the lights hold

  json static_lights = animated_scene();
  static_lights["animation"].erase("lights");
  EXPECT_EQ(light_run_start(load(static_lights), 13), 0);
  static_lights["animation"]["frames"] = {4, 20};
  EXPECT_EQ(light_run_start(load(static_lights), 13), 4);
  EXPECT_EQ(light_run_start(load(static_lights), 2), 2);  // before the sequence: its own

  json still = animated_scene();
  still.erase("animation");
  EXPECT_EQ(light_run_start(load(still), 7), 7);  // a still scene: every frame its own photons
}

TEST_F(AnimationJson, SameLightsComparesPositionsAndPowersBitwise) {
  const Scene scene = load(animated_scene());
  std::vector<LightDesc> a = lights_at_frame(scene, 7), b = lights_at_frame(scene, 8);
  EXPECT_TRUE(same_lights(a, b));
  b[1].power.z = std::nextafter(b[1].power.z, 1.0f);
  EXPECT_FALSE(same_lights(a, b));
  b = a;
  b[0].name = "renamed";
  EXPECT_TRUE(same_lights(a, b));
  b.pop_back();
  EXPECT_FALSE(same_lights(a, b));
}

TEST_F(AnimationJson, ErrorsNameTheField) {
  json s = animated_scene();
  s["animation"]["fps"] = 24;
  expect_error(s, "animation.fps: unknown key");
  s = animated_scene();
  s["animation"]["frame_rate"] = 0;
  expect_error(s, "animation.frame_rate: must be in (0, 1e6] frames per second, got 0");
  s = animated_scene();
  s["animation"]["frames"] = {5, 2};
  expect_error(s, "animation.frames[1]: the last frame is before the first (5)");
  s = animated_scene();
  s["animation"]["frames"] = {-1, 2};
  expect_error(s, "animation.frames[0]: expected an integer");
  s = animated_scene();
  s["animation"]["frames"] = {0, 2000000};
  expect_error(s, "animation: the sequence has 2000001 frames");
  s = animated_scene();
  s["animation"]["camera"]["position"]["interpolation"] = "cubic";
  expect_error(s, "animation.camera.position.interpolation: expected \"linear\", \"smooth\" or \"step\", got \"cubic\"");
  s = animated_scene();
  s["animation"]["camera"]["position"]["keys"][2]["time"] = 1;
  expect_error(s, "animation.camera.position.keys[2].time: must be after the previous key's time 1 s");
  s = animated_scene();
  s["animation"]["camera"]["position"]["keys"] = json::array();
  expect_error(s, "animation.camera.position.keys: a track needs at least one key");
  s = animated_scene();
  s["animation"]["camera"]["position"]["keys"][0].erase("value");
  expect_error(s, "animation.camera.position.keys[0].value: missing required key");
  s = animated_scene();
  s["animation"]["camera"]["vertical_fov"]["keys"][1]["value"] = 180;
  expect_error(s, "animation.camera.vertical_fov.keys[1].value: must be in (0, 180) degrees");
  s = animated_scene();
  s["animation"]["camera"]["up"] = {{"keys", {{{"time", 0}, {"value", {0, 0, 0}}}}}};
  expect_error(s, "animation.camera.up.keys[0].value: must not be the zero vector");
  s = animated_scene();
  s["animation"]["camera"]["roll"] = json::object();
  expect_error(s, "animation.camera.roll: unknown key");
  s = animated_scene();
  s["animation"]["lights"]["key"]["power"]["keys"][0]["value"][1] = -1;
  expect_error(s, "animation.lights.key.power.keys[0].value[1]: must be >= 0 W");
  s = animated_scene();
  s["animation"]["lights"]["lamp"] = json::object();
  expect_error(s, "animation.lights.lamp: no light of that name (lights: key, fill)");
  s = animated_scene();
  s["lights"][1]["name"] = "key";
  expect_error(s, "animation.lights.key: 2 lights have this name");
  s = animated_scene();
  s["animation"]["camera"]["position"]["keys"][0]["value"][0] = nullptr;
  expect_error(s, "animation.camera.position.keys[0].value[0]: expected a finite number, got null");
  // A key's position is bounded as a static one is (1e15 m, meters_per_unit 0.5 here): a light
  // key at 4e15 units, 2e15 m, is refused where it was once read as long as it stayed finite.
  s = animated_scene();
  s["animation"]["lights"]["key"]["position"]["keys"][1]["value"][2] = 4e15;
  expect_error(s, "animation.lights.key.position.keys[1].value: a position is 1.99");
  expect_error(s, "e+15 m from the origin once converted to metres; at most 1e15 m renders");
  s = animated_scene();
  s["lights"][0]["position"][2] = 4e15;
  expect_error(s, "lights[0].position: a position is 1.99");
}

TEST_F(AnimationJson, TheCameraIsCheckedAtEveryFrame) {
  json s = animated_scene();
  // The camera passes through its look_at point (0, 0, 0) at t = 0.5 s: frame 5.
  s["animation"]["camera"]["position"] = {
      {"keys", {{{"time", 0}, {"value", {0, 0, -10}}}, {{"time", 1}, {"value", {0, 0, 10}}}}}};
  expect_error(s, "animation.camera: at frame 5 (t = 0.5 s): look_at equals position");
  s["animation"]["frames"] = {6, 10};  // frames that avoid it are fine
  EXPECT_NO_THROW(load(s));
}

TEST(SequenceFlicker, RelativeMeanAbsoluteFrameDifference) {
  const std::vector<float> a(12, 1.0f), b(12, 3.0f);
  EXPECT_EQ(sequence_flicker({a}).mean, 0.0);
  EXPECT_EQ(sequence_flicker({a, a, a}).max, 0.0);
  const FlickerStats ab = sequence_flicker({a, b});
  EXPECT_DOUBLE_EQ(ab.mean, 1.0);  // |3 - 1| over the mean level 2
  const FlickerStats aba = sequence_flicker({a, a, b});
  EXPECT_DOUBLE_EQ(aba.mean, 0.5);
  EXPECT_DOUBLE_EQ(aba.max, 1.0);
}

TEST(FrameSpecLimits, AtMostAMillionFrames) {
  EXPECT_EQ(parse_frame_spec("0-999999", 0, 999999999).size(), 1000000u);
  EXPECT_EQ(parse_frame_spec("0-999999999:1000", 0, 999999999).size(), 1000000u);
  try {
    parse_frame_spec("5,0-999999999", 0, 999999999);
    ADD_FAILURE() << "a billion frames accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'0-999999999': selects more than 1000000 frames"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace pm

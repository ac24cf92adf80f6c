// Tests that bad JSON scene files fail with a one-line pm::InputError naming the file and the
// field path or line: syntax, types, non-finite numbers, unknown and missing keys, format and
// version, camera/light/material range checks, empty scenes and unresolvable names.
// OBJ/MTL content errors: scene_obj_errors_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "render/errors.h"
#include "scene_io/scene_file.h"
#include "support/scene_load_error.h"

namespace pm {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A valid scene; each test breaks one thing.
json valid_scene() {
  return json::parse(R"({
    "format": "pmrender-scene", "version": 1,
    "meshes": [ { "file": "tri.obj" } ],
    "materials": { "white": { "diffuse": [0.7, 0.7, 0.7] } },
    "lights": [ { "name": "key", "position": [0, 2, 0], "power": [1, 1, 1] } ],
    "camera": { "position": [0, 0, -5], "look_at": [0, 0, 0], "up": [0, 1, 0],
                "vertical_fov": 40, "resolution": [64, 64] }
  })");
}

class SceneJsonErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) / (std::string("pm_scene_json_errors_") + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
  }

  static std::string error_of(const std::string& path) { return test::scene_load_error(path); }
  std::string error_of_text(const std::string& text) { return error_of(write("scene.json", text)); }
  std::string error_of_scene(const json& scene) { return error_of_text(scene.dump(2)); }

  // The message starts with the file path, contains `expected`, and is one line.
  void expect_message(const std::string& message, const std::string& file, const std::string& expected) {
    EXPECT_EQ(message.rfind((dir_ / file).string() + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(expected), std::string::npos)
        << "message: " << message << "\nexpected part: " << expected;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  void expect_scene_message(const std::string& message, const std::string& expected) {
    expect_message(message, "scene.json", "scene.json: " + expected);
  }

  fs::path dir_;
};

TEST_F(SceneJsonErrors, ValidBaseSceneLoads) {
  // Guards the other tests: each must fail because of what it changes, not the base.
  EXPECT_NO_THROW(load_scene_file(write("scene.json", valid_scene().dump(2))));
}

// A device or pipe would be read without end: refused up front, naming the file or the field.
TEST_F(SceneJsonErrors, DeviceFilesAreRefusedNotRead) {
  EXPECT_NE(error_of("/dev/zero").find("/dev/zero: not a regular file"), std::string::npos);
  std::string scene = write("dev.json", R"({"format": "pmrender-scene", "version": 1,
    "meshes": [{"file": "/dev/zero"}], "lights": [{"position": [0, 2, 0], "power": [1, 1, 1]}],
    "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0]}})");
  EXPECT_NE(error_of(scene).find("meshes[0].file: '/dev/zero' is not a regular file"), std::string::npos);
}

TEST_F(SceneJsonErrors, MissingFileNamesIt) {
  expect_message(error_of((dir_ / "nope.json").string()), "nope.json", "nope.json: cannot open");
}

TEST_F(SceneJsonErrors, SyntaxErrorGivesTheLine) {
  const std::string text =
      "{\n"
      "  \"format\": \"pmrender-scene\",\n"
      "  \"version\": 1,\n"
      "  \"meshes\": [ { \"file\": \"tri.obj\" } ]\n"
      "  \"camera\": {}\n"  // line 5: missing comma before this key
      "}\n";
  expect_scene_message(error_of_text(text), "line 5: JSON parse error: ");
}

TEST_F(SceneJsonErrors, SyntaxErrorInsideAStringGivesItsLine) {
  // A raw line break inside a string is not JSON; the error is on the string's line (3).
  expect_scene_message(error_of_text("{\n  \"format\": \"pmrender-scene\",\n  \"name\": \"a\nb\"\n}\n"),
                       "line 3: JSON parse error: ");
}

TEST_F(SceneJsonErrors, DeepNestingIsRefusedWithItsLine) {
  // 101 levels, the last on line 3; strings holding brackets do not count.
  std::string text = "{\"name\": \"[[[[{{{{\",\n\"x\":\n" + std::string(100, '[') + std::string(100, ']') + "}";
  expect_scene_message(error_of_text(text), "line 3: JSON nested deeper than 100 levels");
  // 100 levels pass the check (and fail later for what they are).
  text = "{\"x\": " + std::string(99, '[') + std::string(99, ']') + "}";
  EXPECT_EQ(error_of_text(text).find("nested deeper"), std::string::npos);
}

TEST_F(SceneJsonErrors, MillionLevelsAreRefusedQuickly) {
  // Building the field paths of 200,000 levels took all memory; the check is one linear scan.
  const auto start = std::chrono::steady_clock::now();
  expect_scene_message(error_of_text(std::string(1000000, '[')), "line 1: JSON nested deeper than 100 levels");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

TEST_F(SceneJsonErrors, NullWhereANumberIsExpected) {
  json scene = valid_scene();
  scene["camera"]["position"][1] = nullptr;
  expect_scene_message(error_of_scene(scene), "camera.position[1]: expected a finite number, got null");
}

TEST_F(SceneJsonErrors, NumberBeyondDoubleRangeGivesLineAndField) {
  std::string text = valid_scene().dump(2);
  // dump(2) puts camera.position's elements on their own lines; make the middle one 1e999.
  const size_t camera = text.find("\"camera\"");
  const size_t position = text.find("\"position\"", camera);
  const size_t second = text.find("0,", text.find("0,", position) + 2);
  text.replace(second, 1, "1e999");
  const size_t line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(second), '\n');
  expect_scene_message(error_of_text(text), "line " + std::to_string(line) +
                                                ": camera.position[1]: expected a finite number, got 1e999");
}

TEST_F(SceneJsonErrors, WrongTypeIsNamed) {
  json scene = valid_scene();
  scene["camera"]["vertical_fov"] = "wide";
  expect_scene_message(error_of_scene(scene), "camera.vertical_fov: expected a finite number, got a string");
  scene = valid_scene();
  scene["lights"][0]["position"] = {1, 2};
  expect_scene_message(error_of_scene(scene), "lights[0].position: expected an array of 3 elements, got 2");
  scene = valid_scene();
  scene["meshes"] = json::object();
  expect_scene_message(error_of_scene(scene), "meshes: expected an array, got an object");
}

TEST_F(SceneJsonErrors, TopLevelMustBeAnObject) {
  expect_message(error_of_text("[1, 2]"), "scene.json",
                 "scene.json: expected a JSON object at the top level");
}

TEST_F(SceneJsonErrors, UnknownKeyListsTheKnownOnes) {
  json scene = valid_scene();
  scene["lights"][0]["colour"] = {1, 1, 1};
  expect_scene_message(error_of_scene(scene),
                       "lights[0].colour: unknown key (expected one of: name, type, position, power, direction, inner_cone_angle, outer_cone_angle)");
}

TEST_F(SceneJsonErrors, UnknownKeysAreErrorsEverywhere) {
  json scene = valid_scene();
  scene["background"] = "black";
  expect_scene_message(error_of_scene(scene), "background: unknown key (expected one of: format, version,");
  scene = valid_scene();
  scene["materials"]["white"]["specular"] = {0, 0, 0};
  expect_scene_message(error_of_scene(scene), "materials.white.specular: unknown key");
  scene = valid_scene();
  scene["meshes"][0]["scale"] = 2;
  expect_scene_message(error_of_scene(scene), "meshes[0].scale: unknown key");
  scene = valid_scene();
  scene["camera"]["fov"] = 40;
  expect_scene_message(error_of_scene(scene), "camera.fov: unknown key");
}

TEST_F(SceneJsonErrors, AnimationKeyIsCheckedLikeTheRest) {
  json scene = valid_scene();
  scene["animation"] = {{"speed", 2}};  // "animation" is optional in version 1 (animation_json.h)
  expect_scene_message(error_of_scene(scene), "animation.speed: unknown key");
}

TEST_F(SceneJsonErrors, DuplicateKeyIsRejected) {
  std::string text = valid_scene().dump();
  text.insert(text.find("\"look_at\""), "\"look_at\": [1, 1, 1], ");
  expect_scene_message(error_of_text(text), "camera.look_at: duplicate key");
}

TEST_F(SceneJsonErrors, MissingRequiredKeys) {
  for (const char* key : {"format", "version", "meshes", "camera"}) {
    SCOPED_TRACE(key);
    json scene = valid_scene();
    scene.erase(key);
    expect_scene_message(error_of_scene(scene), std::string(key) + ": missing required key");
  }
  json scene = valid_scene();
  scene["camera"].erase("look_at");
  expect_scene_message(error_of_scene(scene), "camera.look_at: missing required key");
  scene = valid_scene();
  scene["lights"][0].erase("power");
  expect_scene_message(error_of_scene(scene), "lights[0].power: missing required key");
  scene = valid_scene();
  scene["meshes"][0].erase("file");
  expect_scene_message(error_of_scene(scene), "meshes[0].file: missing required key");
}

TEST_F(SceneJsonErrors, WrongFormatString) {
  json scene = valid_scene();
  scene["format"] = "mitsuba";
  expect_scene_message(error_of_scene(scene), "format: expected \"pmrender-scene\", got \"mitsuba\"");
}

TEST_F(SceneJsonErrors, UnsupportedVersion) {
  json scene = valid_scene();
  scene["version"] = 2;
  scene["animation"] = json::object();  // version is checked first: no "unknown key" noise
  expect_scene_message(error_of_scene(scene), "version: unsupported version 2 (this build reads version 1)");
  scene["version"] = 1.5;
  expect_scene_message(error_of_scene(scene), "version: expected an integer");
}

TEST_F(SceneJsonErrors, MissingMeshFile) {
  json scene = valid_scene();
  scene["meshes"][0]["file"] = "missing.obj";
  expect_scene_message(error_of_scene(scene), "meshes[0].file: cannot open 'missing.obj'");
}

TEST_F(SceneJsonErrors, MeshFileThatIsADirectory) {
  fs::create_directories(dir_ / "folder.obj");
  json scene = valid_scene();
  scene["meshes"][0]["file"] = "folder.obj";
  expect_scene_message(error_of_scene(scene), "meshes[0].file: cannot open 'folder.obj' (it is a directory)");
}

TEST_F(SceneJsonErrors, UnknownOverrideMaterial) {
  json scene = valid_scene();
  scene["meshes"][0]["material"] = "black";
  expect_scene_message(error_of_scene(scene), "meshes[0].material: unknown material 'black'");
}

TEST_F(SceneJsonErrors, NegativeLightPower) {
  json scene = valid_scene();
  scene["lights"][0]["power"] = {1, -0.5, 1};
  expect_scene_message(error_of_scene(scene), "lights[0].power[1]: must be >= 0 W, got -0.5");
}

const char* const kNoLight =
    "lights: no light: no light with power above zero under lights and no emitting material (materials' emission, "
    "MTL Ke) on any triangle";

TEST_F(SceneJsonErrors, AtLeastOneLightIsRequired) {
  json scene = valid_scene();
  scene["lights"] = json::array();
  expect_scene_message(error_of_scene(scene), kNoLight);
  scene.erase("lights");
  expect_scene_message(error_of_scene(scene), kNoLight);
  // An emitting material the triangles do not use is no light either.
  scene["materials"]["glow"] = {{"emission", {1, 1, 1}}};
  expect_scene_message(error_of_scene(scene), kNoLight);
}

TEST_F(SceneJsonErrors, AllLightsDark) {
  json scene = valid_scene();
  scene["lights"][0]["power"] = {0, 0, 0};
  expect_scene_message(error_of_scene(scene), kNoLight);
}

TEST_F(SceneJsonErrors, SpotLightFields) {
  json scene = valid_scene();
  scene["lights"][0]["direction"] = {0, -1, 0};
  expect_scene_message(error_of_scene(scene), "lights[0].direction: only a spot light has this key (\"type\": \"spot\")");
  scene["lights"][0]["type"] = "cone";
  expect_scene_message(error_of_scene(scene), "lights[0].type: expected \"point\" or \"spot\", got 'cone'");
  scene["lights"][0]["type"] = "spot";
  scene["lights"][0]["direction"] = {0, 0, 0};
  expect_scene_message(error_of_scene(scene), "lights[0].direction: must not be zero");
  scene["lights"][0].erase("direction");
  expect_scene_message(error_of_scene(scene), "lights[0].direction: missing required key");
  scene["lights"][0]["direction"] = {0, -1, 0};
  scene["lights"][0]["outer_cone_angle"] = 91;
  expect_scene_message(error_of_scene(scene), "lights[0].outer_cone_angle: must be in [0, 90] degrees, got 91");
  scene["lights"][0]["outer_cone_angle"] = 30;
  scene["lights"][0]["inner_cone_angle"] = -1;
  expect_scene_message(error_of_scene(scene), "lights[0].inner_cone_angle: must be in [0, 90] degrees, got -1");
  scene["lights"][0]["inner_cone_angle"] = 30;
  expect_scene_message(error_of_scene(scene), "lights[0].inner_cone_angle: the inner cone angle must be below the outer one");
}

TEST_F(SceneJsonErrors, EmissionMustBeNonNegative) {
  json scene = valid_scene();
  scene["materials"]["white"]["emission"] = {1, -0.5, 1};
  expect_scene_message(error_of_scene(scene), "materials.white.emission[1]: must be >= 0 W sr^-1 m^-2, got -0.5");
  scene["materials"]["white"]["emission"] = {1, 1};
  EXPECT_NE(error_of_scene(scene).find("materials.white.emission"), std::string::npos);
}

TEST_F(SceneJsonErrors, ResolutionMustBePositiveIntegersUpTo16384) {
  const json bad[] = {json{0, 64}, json{64, -1}, json{64.5, 64}, json{16385, 64}, json{"64", 64}};
  for (const json& resolution : bad) {
    SCOPED_TRACE(resolution.dump());
    json scene = valid_scene();
    scene["camera"]["resolution"] = resolution;
    const std::string message = error_of_scene(scene);
    expect_scene_message(message, "camera.resolution[");
    EXPECT_NE(message.find("expected an integer in [1, 16384]"), std::string::npos) << message;
  }
  json scene = valid_scene();
  scene["camera"]["resolution"] = {64, 64, 1};
  expect_scene_message(error_of_scene(scene), "camera.resolution: expected an array of 2 elements, got 3");
}

TEST_F(SceneJsonErrors, FieldOfViewMustBeInsideZeroTo180) {
  for (double fov : {0.0, -10.0, 180.0, 200.0}) {
    SCOPED_TRACE(fov);
    json scene = valid_scene();
    scene["camera"]["vertical_fov"] = fov;
    expect_scene_message(error_of_scene(scene), "camera.vertical_fov: must be in (0, 180) degrees");
  }
}

TEST_F(SceneJsonErrors, LookAtEqualToPosition) {
  json scene = valid_scene();
  scene["camera"]["look_at"] = scene["camera"]["position"];
  expect_scene_message(error_of_scene(scene), "camera.look_at: equals camera.position");
}

TEST_F(SceneJsonErrors, UpParallelToViewDirection) {
  json scene = valid_scene();
  scene["camera"]["up"] = {0, 0, -3};  // view direction is +z
  expect_scene_message(error_of_scene(scene), "camera.up: is parallel to the view direction");
  scene["camera"]["up"] = {0, 0, 0};
  expect_scene_message(error_of_scene(scene), "camera.up: must not be the zero vector");
  scene["camera"].erase("up");
  scene["camera"]["look_at"] = {0, 5, -5};  // straight up from the position, default up +y
  expect_scene_message(error_of_scene(scene), "camera: the default up [0, 1, 0] is parallel");
}

TEST_F(SceneJsonErrors, MetersPerUnitMustBeFinitePositive) {
  json scene = valid_scene();
  scene["meters_per_unit"] = 0;
  expect_scene_message(error_of_scene(scene), "meters_per_unit: must be > 0, got 0");
  scene["meters_per_unit"] = -0.001;
  expect_scene_message(error_of_scene(scene), "meters_per_unit: must be > 0");
  scene["meters_per_unit"] = nullptr;
  expect_scene_message(error_of_scene(scene), "meters_per_unit: expected a finite number, got null");
}

TEST_F(SceneJsonErrors, EmptySceneHasNoTriangles) {
  json scene = valid_scene();
  scene["meshes"] = json::array();
  expect_scene_message(error_of_scene(scene), "meshes: the scene has no triangles");
}

TEST_F(SceneJsonErrors, MeshOfOnlyDegenerateTrianglesLeavesAnEmptyScene) {
  write("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n");
  json scene = valid_scene();
  scene["meshes"][0]["file"] = "flat.obj";
  expect_scene_message(error_of_scene(scene), "meshes: the scene has no triangles (1 meshes, 2 degenerate");
}

TEST_F(SceneJsonErrors, JsonMaterialReflectingMoreThanItReceives) {
  json scene = valid_scene();
  scene["materials"]["hot"] = {
      {"diffuse", {0.5, 0.5, 0.5}}, {"glossy", {0.3, 0.3, 0.3}}, {"mirror", {0.1, 0.3, 0.1}}};
  expect_scene_message(error_of_scene(scene), "materials.hot: diffuse + glossy + mirror = 1.1");
  EXPECT_NE(error_of_scene(scene).find("green channel"), std::string::npos);
}

TEST_F(SceneJsonErrors, JsonMaterialSummingToExactlyOneIsAccepted) {
  // As floats 0.6 + 0.4 is slightly above 1; the check must not reject it.
  json scene = valid_scene();
  scene["materials"]["white"] = {
      {"diffuse", {0.6, 0.7, 0.1}}, {"glossy", {0.4, 0.3, 0.2}}, {"mirror", {0, 0, 0.7}}};
  EXPECT_NO_THROW(load_scene_file(write("scene.json", scene.dump())));
}

TEST_F(SceneJsonErrors, JsonMaterialValuesOutOfRange) {
  json scene = valid_scene();
  scene["materials"]["white"]["diffuse"] = {0.5, 1.5, 0.5};
  expect_scene_message(error_of_scene(scene), "materials.white.diffuse[1]: must be in [0, 1], got 1.5");
  scene = valid_scene();
  scene["materials"]["white"]["exponent"] = -1;
  expect_scene_message(error_of_scene(scene), "materials.white.exponent: must be in [0, 1e6], got -1");
  scene = valid_scene();
  scene["materials"]["white"] = {0.7, 0.7, 0.7};
  expect_scene_message(error_of_scene(scene), "materials.white: expected an object, got an array");
}

TEST_F(SceneJsonErrors, UsemtlNameFoundNowhere) {
  write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl nope\nf 1 2 3\n");
  expect_message(
      error_of_scene(valid_scene()), "tri.obj",
      "tri.obj: line 4: usemtl 'nope': no such material in the scene's materials or the OBJ's MTL files");
}

}  // namespace
}  // namespace pm

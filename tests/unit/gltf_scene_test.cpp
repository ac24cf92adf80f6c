// glTF 2.0 scenes (scene_io/gltf_scene.h): the hand-written twin of a JSON scene loads into the
// same pm::Scene, and small glTF files written by the test cover index types, primitive modes,
// node transforms, the material mapping, cameras, KHR_lights_punctual lights, node animations
// (STEP, LINEAR, CUBICSPLINE, rotations, hierarchies), .glb containers and errors.
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "render/scene_frame.h"
#include "render/errors.h"
#include "scene_io/gltf_scene.h"
#include "scene_io/scene_file.h"
#include "support/paths.h"

namespace pm {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string base64(const std::string& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const uint32_t v = uint32_t(uint8_t(bytes[i])) << 16 | uint32_t(uint8_t(bytes[i + 1])) << 8 | uint8_t(bytes[i + 2]);
    for (int k = 3; k >= 0; --k) out += table[(v >> (6 * k)) & 63];
  }
  if (i + 1 == bytes.size()) {
    const uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
    out += std::string{table[v >> 18], table[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == bytes.size()) {
    const uint32_t v = uint32_t(uint8_t(bytes[i])) << 16 | uint32_t(uint8_t(bytes[i + 1])) << 8;
    out += std::string{table[v >> 18], table[(v >> 12) & 63], table[(v >> 6) & 63], '='};
  }
  return out;
}

// Builds a glTF document: each accessor gets its own bufferView in one buffer.
class GltfBuilder {
 public:
  GltfBuilder() {
    doc_ = {{"asset", {{"version", "2.0"}}},
            {"scene", 0},
            {"scenes", {{{"nodes", json::array()}}}},
            {"nodes", json::array()},
            {"meshes", json::array()},
            {"accessors", json::array()},
            {"bufferViews", json::array()}};
  }
  json& doc() { return doc_; }

  template <typename T>
  int accessor(const std::vector<T>& data, int component_type, const std::string& type, bool normalized = false) {
    while (bytes_.size() % 4) bytes_ += '\0';
    const size_t offset = bytes_.size();
    bytes_.append(reinterpret_cast<const char*>(data.data()), data.size() * sizeof(T));
    const int per_element = type == "SCALAR" ? 1 : type == "VEC3" ? 3 : 4;
    doc_["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", data.size() * sizeof(T)}});
    json a = {{"bufferView", doc_["bufferViews"].size() - 1},
              {"componentType", component_type},
              {"count", data.size() / size_t(per_element)},
              {"type", type}};
    if (normalized) a["normalized"] = true;
    doc_["accessors"].push_back(a);
    return int(doc_["accessors"].size()) - 1;
  }
  int floats(const std::vector<float>& v, const std::string& type) { return accessor(v, 5126, type); }

  int node(json node, bool root = true) {
    doc_["nodes"].push_back(node);
    const int index = int(doc_["nodes"].size()) - 1;
    if (root) doc_["scenes"][0]["nodes"].push_back(index);
    return index;
  }
  int mesh(json primitives) {
    doc_["meshes"].push_back({{"primitives", primitives}});
    return int(doc_["meshes"].size()) - 1;
  }
  // A camera node looking down -z from `position`, and one point light.
  void add_camera_and_light(std::vector<double> position = {0, 0, 5}) {
    doc_["cameras"].push_back({{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"aspectRatio", 1.5}, {"znear", 0.01}}}});
    node({{"name", "cam"}, {"camera", int(doc_["cameras"].size()) - 1}, {"translation", position}});
    add_light({{"type", "point"}, {"intensity", 10.0}}, {0, 3, 0});
  }
  int add_light(json light, std::vector<double> position) {
    doc_["extensionsUsed"] = {"KHR_lights_punctual"};
    doc_["extensions"]["KHR_lights_punctual"]["lights"].push_back(light);
    const int index = int(doc_["extensions"]["KHR_lights_punctual"]["lights"].size()) - 1;
    return node({{"translation", position}, {"extensions", {{"KHR_lights_punctual", {{"light", index}}}}}});
  }
  // One triangle in the xy plane.
  int triangle_mesh(json extra = json::object()) {
    json primitive = {{"attributes", {{"POSITION", floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3")}}}};
    primitive.update(extra);
    return mesh(json::array({primitive}));  // {primitive} alone is a copy, not an array, for clang
  }
  void animate(int node, const std::string& path, const std::vector<float>& times, const std::vector<float>& values,
               const std::string& interpolation = "LINEAR") {
    const std::string type = path == "rotation" ? "VEC4" : "VEC3";
    if (doc_["animations"].is_null()) doc_["animations"] = {{{"samplers", json::array()}, {"channels", json::array()}}};
    json& animation = doc_["animations"][0];
    animation["samplers"].push_back({{"input", floats(times, "SCALAR")},
                                     {"output", floats(values, type)},
                                     {"interpolation", interpolation}});
    animation["channels"].push_back(
        {{"sampler", animation["samplers"].size() - 1}, {"target", {{"node", node}, {"path", path}}}});
  }

  // The document with the given buffers instead of the embedded one (bytes() is its content).
  std::string gltf_text_with_buffer(const json& buffer) {
    json doc = doc_;
    doc["buffers"] = json::array({buffer});
    return doc.dump(1);
  }
  const std::string& bytes() const { return bytes_; }

  std::string gltf_text() {
    json doc = doc_;
    doc["buffers"] = {{{"byteLength", bytes_.size()}, {"uri", "data:application/octet-stream;base64," + base64(bytes_)}}};
    return doc.dump(1);
  }
  // The binary container: 12-byte header, a JSON chunk and a BIN chunk, each 4-byte aligned.
  std::string glb() {
    json doc = doc_;
    std::string bin = bytes_;
    while (bin.size() % 4) bin += '\0';
    doc["buffers"] = {{{"byteLength", bytes_.size()}}};
    std::string text = doc.dump();
    while (text.size() % 4) text += ' ';
    std::string out;
    auto u32 = [&out](uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
    u32(0x46546C67u);  // "glTF"
    u32(2);
    u32(uint32_t(12 + 8 + text.size() + 8 + bin.size()));
    u32(uint32_t(text.size()));
    u32(0x4E4F534Au);  // "JSON"
    out += text;
    u32(uint32_t(bin.size()));
    u32(0x004E4942u);  // "BIN"
    out += bin;
    return out;
  }

 private:
  json doc_;
  std::string bytes_;
};

class Gltf : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) /
           (std::string("pm_gltf_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& content) {
    std::ofstream(dir_ / name, std::ios::binary) << content;
    return (dir_ / name).string();
  }
  Scene load(GltfBuilder& b, SceneLoadReport* report = nullptr) {
    return load_scene_file(write("scene.gltf", b.gltf_text()), report);
  }
  void expect_error(GltfBuilder& b, const std::string& expected) {
    const std::string path = write("scene.gltf", b.gltf_text());
    try {
      load_scene_file(path);
      ADD_FAILURE() << "loaded; expected an error containing: " << expected;
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
      EXPECT_NE(message.find(expected), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }
  static bool has_warning(const SceneLoadReport& report, const std::string& part) {
    for (const std::string& w : report.warnings)
      if (w.find(part) != std::string::npos) return true;
    return false;
  }

  fs::path dir_;
};

bool same(const Float3& a, const Float3& b) { return std::memcmp(&a, &b, sizeof(Float3)) == 0; }

TEST_F(Gltf, TwinFileGivesTheSameSceneAsItsJsonTwin) {
  const std::string data = test::test_data_dir() + "/animation/";
  SceneLoadReport report;
  const Scene g = load_scene_file(data + "twin.gltf", &report);
  const Scene j = load_scene_file(data + "twin.json");
  EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
  EXPECT_EQ(g.name, "twin");
  ASSERT_EQ(g.triangle_count(), 20u);
  ASSERT_EQ(g.triangle_count(), j.triangle_count());
  for (size_t t = 0; t < g.triangle_count(); ++t) {
    for (int c = 0; c < 3; ++c)
      EXPECT_TRUE(same(g.positions[g.indices[3 * t + c]], j.positions[j.indices[3 * t + c]])) << "triangle " << t;
    EXPECT_EQ(g.triangle_material[t], j.triangle_material[t]);
  }
  ASSERT_EQ(g.materials.size(), j.materials.size());
  for (size_t m = 0; m < g.materials.size(); ++m) {
    SCOPED_TRACE(g.materials[m].name);
    EXPECT_EQ(g.materials[m].name, j.materials[m].name);
    EXPECT_TRUE(same(g.materials[m].diffuse, j.materials[m].diffuse));
    EXPECT_TRUE(same(g.materials[m].glossy, j.materials[m].glossy));
    EXPECT_TRUE(same(g.materials[m].mirror, j.materials[m].mirror));
    EXPECT_EQ(g.materials[m].glossy_exponent, j.materials[m].glossy_exponent);
  }
  ASSERT_TRUE(g.animation.enabled);
  EXPECT_EQ(g.animation.frame_rate, j.animation.frame_rate);
  EXPECT_EQ(g.animation.first_frame, j.animation.first_frame);
  EXPECT_EQ(g.animation.last_frame, 24);
  EXPECT_EQ(j.animation.last_frame, 24);
  for (int f = 0; f <= 24; ++f) {
    SCOPED_TRACE("frame " + std::to_string(f));
    const CameraDesc cg = camera_at_frame(g, f), cj = camera_at_frame(j, f);
    EXPECT_TRUE(same(cg.position, cj.position));
    EXPECT_TRUE(same(cg.look_at, cj.look_at));
    EXPECT_TRUE(same(cg.up, cj.up));
    EXPECT_EQ(cg.vertical_fov_degrees, cj.vertical_fov_degrees);
    EXPECT_EQ(cg.width, cj.width);
    EXPECT_EQ(cg.height, cj.height);
    EXPECT_TRUE(same_lights(lights_at_frame(g, f), lights_at_frame(j, f)));
  }
  EXPECT_EQ(lights_at_frame(g, 12)[0].position.x, 1.0f);
  EXPECT_EQ(camera_at_frame(g, 12).position.y, 1.125f);  // rig (0, 1, 0) plus the node's 0.125
}

TEST_F(Gltf, IndexTypesStripsFansAndNodeTransforms) {
  GltfBuilder b;
  const std::vector<float> square = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const int pos = b.floats(square, "VEC3");
  json primitives = json::array();
  primitives.push_back({{"attributes", {{"POSITION", pos}}}, {"indices", b.accessor(std::vector<uint8_t>{0, 1, 2, 0, 2, 3}, 5121, "SCALAR")}});
  primitives.push_back({{"attributes", {{"POSITION", pos}}}, {"indices", b.accessor(std::vector<uint16_t>{0, 1, 2}, 5123, "SCALAR")}});
  primitives.push_back({{"attributes", {{"POSITION", pos}}}, {"indices", b.accessor(std::vector<uint32_t>{0, 2, 3}, 5125, "SCALAR")}});
  primitives.push_back({{"attributes", {{"POSITION", pos}}}, {"mode", 5}, {"indices", b.accessor(std::vector<uint16_t>{0, 1, 3, 2}, 5123, "SCALAR")}});
  primitives.push_back({{"attributes", {{"POSITION", pos}}}, {"mode", 6}});  // fan 0 1 2 3: two triangles
  primitives.push_back({{"attributes", {{"POSITION", pos}}}, {"mode", 1}});  // lines: skipped with a warning
  const int mesh = b.mesh(primitives);
  const double h = std::sqrt(0.5);
  // A parent that moves by +10 x, a child turned 90 degrees about +z and scaled by 2.
  const int child = b.node({{"mesh", mesh}, {"rotation", {0, 0, h, h}}, {"scale", {2, 2, 2}}}, false);
  b.node({{"translation", {10, 0, 0}}, {"children", {child}}});
  b.node({{"mesh", mesh}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -3, 1}}});
  b.add_camera_and_light();
  SceneLoadReport report;
  const Scene scene = load(b, &report);
  EXPECT_EQ(scene.triangle_count(), 2u * (2 + 1 + 1 + 2 + 2));
  EXPECT_TRUE(has_warning(report, "points and lines are not rendered"));
  // The parented instance: local (1, 0, 0) -> scaled (2, 0, 0) -> turned (0, 2, 0) -> moved (10, 2, 0).
  const Float3 p = scene.positions[1];
  EXPECT_NEAR(p.x, 10.0f, 1e-6);
  EXPECT_NEAR(p.y, 2.0f, 1e-6);
  EXPECT_EQ(scene.positions[5 * 4 + 1].z, -3.0f);  // the matrix node's instance, second vertex
  // Strip: (0 1 3), then (3 1 2) with the winding kept.
  const size_t strip = 2 + 1 + 1;
  EXPECT_EQ(scene.indices[3 * strip + 0] % 4, 0u);
  EXPECT_EQ(scene.indices[3 * strip + 2] % 4, 3u);
  EXPECT_EQ(scene.indices[3 * strip + 3] % 4, 3u);
  EXPECT_EQ(scene.indices[3 * strip + 4] % 4, 1u);
  EXPECT_EQ(scene.indices[3 * strip + 5] % 4, 2u);
}

TEST_F(Gltf, MetallicRoughnessMapsOntoModifiedPhong) {
  EXPECT_NEAR(roughness_to_phong_exponent(0.5), 30.0, 1e-12);
  EXPECT_EQ(roughness_to_phong_exponent(1.0), 0.0);
  EXPECT_TRUE(std::isinf(roughness_to_phong_exponent(0.0)));
  GltfBuilder b;
  b.doc()["materials"] = {
      {{"name", "paint"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.4, 0.3, 1}}, {"metallicFactor", 0.0}}}},
      {{"name", "chrome"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.9, 0.9, 0.9, 1}}, {"roughnessFactor", 0.05}}}},
      {{"name", "brushed"},
       {"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.6, 0.4, 1}}, {"metallicFactor", 0.25}, {"roughnessFactor", 0.5}}}},
      {{"name", "textured"},
       {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.0}}},
       {"emissiveFactor", {1, 1, 1}}}};
  b.doc()["textures"] = {{{"source", 0}}};
  b.doc()["images"] = {{{"uri", "missing.png"}}};
  for (int m = 0; m < 4; ++m) b.node({{"mesh", b.triangle_mesh({{"material", m}})}});
  b.node({{"mesh", b.triangle_mesh()}});  // no material
  b.add_camera_and_light();
  SceneLoadReport report;
  const Scene scene = load(b, &report);
  ASSERT_EQ(scene.materials.size(), 5u);
  const MaterialDesc& paint = scene.materials[0];
  EXPECT_EQ(paint.diffuse.x, 0.5f);
  EXPECT_EQ(paint.glossy.x, 0.0f);
  EXPECT_EQ(paint.mirror.x, 0.0f);
  const MaterialDesc& chrome = scene.materials[1];  // metallic defaults to 1; smooth: a mirror
  EXPECT_EQ(chrome.diffuse.x, 0.0f);
  EXPECT_EQ(chrome.mirror.y, 0.9f);
  EXPECT_EQ(chrome.glossy.y, 0.0f);
  const MaterialDesc& brushed = scene.materials[2];
  EXPECT_FLOAT_EQ(brushed.diffuse.x, 0.6f);
  EXPECT_FLOAT_EQ(brushed.glossy.x, 0.2f);
  EXPECT_FLOAT_EQ(brushed.glossy.z, 0.1f);
  EXPECT_FLOAT_EQ(brushed.glossy_exponent, 30.0f);
  EXPECT_EQ(scene.materials[3].diffuse.x, 1.0f);  // baseColorFactor defaults to white
  EXPECT_TRUE(has_warning(report, "materials[3] ('textured'): ignored: baseColorTexture, emissiveFactor"));
  EXPECT_EQ(scene.materials[4].name, "default");
  EXPECT_EQ(scene.materials[4].diffuse.x, 0.8f);
}

TEST_F(Gltf, CamerasLightsAndTheirConversions) {
  EXPECT_NEAR(candela_to_watts(683.0 / (4 * M_PI), 1.0), 1.0, 1e-12);
  GltfBuilder b;
  b.node({{"mesh", b.triangle_mesh()}});
  const double h = std::sqrt(0.5);
  b.doc()["cameras"] = {{{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 10}}}},
                        {{"type", "perspective"}, {"name", "wide"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.01}}}},
                        {{"type", "perspective"}, {"perspective", {{"yfov", M_PI / 4}, {"aspectRatio", 4.0 / 3.0}, {"znear", 0.01}}}}};
  b.node({{"camera", 0}});
  // Turned 90 degrees about +y: it looks down -x.
  b.node({{"name", "side"}, {"camera", 2}, {"translation", {1, 2, 3}}, {"rotation", {0, h, 0, h}}});
  b.node({{"name", "front"}, {"camera", 1}, {"translation", {0, 0, 4}}});
  b.add_light({{"type", "point"}, {"intensity", 683.0 / (4 * M_PI)}, {"color", {1.0, 0.5, 0.0}}, {"name", "bulb"}}, {0, 3, 0});
  b.add_light({{"type", "spot"}, {"intensity", 5.0}, {"spot", json::object()}}, {0, 3, 0});
  b.add_light({{"type", "directional"}, {"intensity", 5.0}}, {0, 3, 0});
  SceneLoadReport report;
  Scene scene = load(b, &report);
  // The first perspective camera in the node order; the orthographic one is passed over.
  EXPECT_NEAR(scene.camera.position.x, 1.0f, 1e-6);
  EXPECT_NEAR(scene.camera.look_at.x - scene.camera.position.x, -1.0f, 1e-6);
  EXPECT_NEAR(scene.camera.look_at.z - scene.camera.position.z, 0.0f, 1e-6);
  EXPECT_NEAR(scene.camera.up.y, 1.0f, 1e-6);
  EXPECT_NEAR(scene.camera.vertical_fov_degrees, 45.0f, 1e-5);
  EXPECT_EQ(scene.camera.height, 512);
  EXPECT_EQ(scene.camera.width, 683);  // 512 * 4/3 rounded
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].name, "bulb");
  EXPECT_NEAR(scene.lights[0].power.x, 1.0f, 1e-6);
  EXPECT_NEAR(scene.lights[0].power.y, 0.5f, 1e-6);
  EXPECT_EQ(scene.lights[0].power.z, 0.0f);
  EXPECT_EQ(scene.lights[0].position.y, 3.0f);
  EXPECT_TRUE(has_warning(report, "spot lights are not supported"));
  EXPECT_TRUE(has_warning(report, "directional lights are not supported"));
  EXPECT_FALSE(scene.animation.enabled);

  // The camera the scene's extras name, and the resolution they set.
  b.doc()["scenes"][0]["extras"] = {{"pmrender", {{"camera", "wide"}, {"resolution", {64, 32}}}}};
  scene = load(b);
  EXPECT_EQ(scene.camera.position.z, 4.0f);
  EXPECT_NEAR(scene.camera.vertical_fov_degrees, 57.29578f, 1e-4);
  EXPECT_EQ(scene.camera.width, 64);
  EXPECT_EQ(scene.camera.height, 32);
  b.doc()["scenes"][0]["extras"] = {{"pmrender", {{"camera", "nobody"}}}};
  expect_error(b, "scenes[0].extras.pmrender.camera: no camera node named 'nobody' (camera nodes: nodes[1], side, front)");
  b.doc()["scenes"][0]["extras"] = {{"pmrender", {{"fps", 30}}}};
  expect_error(b, "scenes[0].extras.pmrender.fps: unknown key");
}

TEST_F(Gltf, NodeAnimationsBecomeTracksSampledAtEveryFrame) {
  GltfBuilder b;
  b.node({{"mesh", b.triangle_mesh()}});
  b.doc()["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.01}}}}};
  const int camera = b.node({{"camera", 0}, {"translation", {0, 0, 5}}});
  const int rig = b.node({{"translation", {0, 0, 0}}, {"children", json::array()}});
  b.doc()["extensionsUsed"] = {"KHR_lights_punctual"};
  b.doc()["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}, {"intensity", 1.0}}};
  b.doc()["nodes"].push_back({{"translation", {1, 0, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  b.doc()["nodes"][size_t(rig)]["children"].push_back(b.doc()["nodes"].size() - 1);
  const double s = std::sqrt(0.5);
  // The camera turns 90 degrees about +y over 1 s (slerp); it steps up by 1 at 0.5 s.
  b.animate(camera, "rotation", {0, 1}, {0, 0, 0, 1, 0, float(s), 0, float(s)});
  b.animate(camera, "translation", {0, 0.5f}, {0, 0, 5, 0, 1, 5}, "STEP");
  // The light's parent turns 180 degrees about +y over 2 s: the light circles the origin.
  b.animate(rig, "rotation", {0, 2}, {0, 0, 0, 1, 0, 1, 0, 0});
  b.doc()["scenes"][0]["extras"] = {{"pmrender", {{"frame_rate", 4}}}};
  Scene scene = load(b);
  ASSERT_TRUE(scene.animation.enabled);
  EXPECT_EQ(scene.animation.last_frame, 8);  // 2 s at 4 frames per second
  const CameraDesc c2 = camera_at_frame(scene, 2);  // 0.5 s: 45 degrees, stepped up
  EXPECT_EQ(c2.position.y, 1.0f);
  EXPECT_EQ(camera_at_frame(scene, 1).position.y, 0.0f);
  EXPECT_NEAR(c2.look_at.x - c2.position.x, -std::sqrt(0.5f), 1e-6);
  EXPECT_NEAR(c2.look_at.z - c2.position.z, -std::sqrt(0.5f), 1e-6);
  const CameraDesc c8 = camera_at_frame(scene, 8);
  EXPECT_NEAR(c8.look_at.x - c8.position.x, -1.0f, 1e-6);
  EXPECT_NEAR(lights_at_frame(scene, 4)[0].position.z, -1.0f, 1e-6);  // 90 degrees: (1,0,0) -> (0,0,-1)
  EXPECT_NEAR(lights_at_frame(scene, 8)[0].position.x, -1.0f, 1e-6);
  EXPECT_EQ(scene.lights[0].position.x, 1.0f);  // the static light is the first frame's

  b.doc()["scenes"][0]["extras"] = {{"pmrender", {{"frame_rate", 4}, {"frames", {2, 3}}}}};
  scene = load(b);
  EXPECT_EQ(scene.animation.first_frame, 2);
  EXPECT_EQ(scene.animation.last_frame, 3);
  EXPECT_EQ(scene.camera.position.y, 1.0f);  // frame 2's camera
}

TEST_F(Gltf, CubicSplineAnimationsAndAnimatedMeshes) {
  GltfBuilder b;
  const int mesh_node = b.node({{"mesh", b.triangle_mesh()}});
  b.add_camera_and_light();
  // Camera x: 0 -> 4 over 2 s, out-tangent 1 at the start, in-tangent 3 at the end.
  b.animate(1, "translation", {0, 2}, {0, 0, 0, 0, 0, 5, 1, 0, 0, 3, 0, 0, 4, 0, 5, 0, 0, 0}, "CUBICSPLINE");
  b.animate(mesh_node, "translation", {0, 1}, {0, 0, 0, 0, 0, 1});
  b.doc()["scenes"][0]["extras"] = {{"pmrender", {{"frame_rate", 2}}}};
  SceneLoadReport report;
  const Scene scene = load(b, &report);
  EXPECT_NEAR(camera_at_frame(scene, 2).position.x, 1.5f, 1e-6);  // as GltfAnimation.CubicSplineUsesTheTangents
  EXPECT_TRUE(has_warning(report, "meshes do not move"));
  EXPECT_EQ(scene.positions[0].z, 0.0f);  // the mesh stays at rest
}

TEST_F(Gltf, BinaryGlbLoadsLikeTheTextForm) {
  GltfBuilder b;
  b.node({{"mesh", b.triangle_mesh()}});
  b.add_camera_and_light({0, 1, 6});
  const Scene text = load(b);
  const Scene binary = load_scene_file(write("scene.GLB", b.glb()));
  ASSERT_EQ(binary.triangle_count(), 1u);
  EXPECT_TRUE(same(binary.positions[1], text.positions[1]));
  EXPECT_EQ(binary.camera.position.z, 6.0f);
  EXPECT_EQ(binary.name, "scene");
}

TEST_F(Gltf, ErrorsNameTheFileAndThePlace) {
  {
    const std::string missing = (dir_ / "missing.gltf").string();
    try {
      load_scene_file(missing);
      ADD_FAILURE() << "loaded a missing file";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(missing + ": cannot open (No such file"), std::string::npos) << e.what();
    }
    try {
      load_scene_file(write("broken.gltf", "{ \"asset\": "));
      ADD_FAILURE() << "loaded broken JSON";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("broken.gltf: glTF: "), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  }
  {
    GltfBuilder b;
    b.node({{"mesh", b.triangle_mesh({{"indices", b.accessor(std::vector<uint16_t>{0, 1, 7}, 5123, "SCALAR")}})}});
    b.add_camera_and_light();
    expect_error(b, "meshes[0].primitives[0].indices: index 7 at position 2 out of range (3 vertices)");
  }
  {
    GltfBuilder b;
    b.node({{"mesh", b.triangle_mesh({{"attributes", {{"POSITION", 42}}}})}});
    b.add_camera_and_light();
    expect_error(b, "meshes[0].primitives[0].attributes.POSITION: accessor 42 out of range");
  }
  {
    GltfBuilder b;
    b.node({{"mesh", b.triangle_mesh({{"indices", b.accessor(std::vector<int16_t>{0, 1, 2}, 5122, "SCALAR")}})}});
    b.add_camera_and_light();
    expect_error(b, "indices must be UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
  }
  {
    GltfBuilder b;
    b.node({{"mesh", b.triangle_mesh()}});
    expect_error(b, "cameras: the scene has no node with a perspective camera");
  }
  {
    GltfBuilder b;
    b.node({{"mesh", b.triangle_mesh()}});
    b.add_camera_and_light();
    b.doc()["extensions"]["KHR_lights_punctual"]["lights"][0]["type"] = "spot";
    b.doc()["extensions"]["KHR_lights_punctual"]["lights"][0]["spot"] = json::object();
    expect_error(b, "extensions.KHR_lights_punctual: at least one point light is required");
  }
  {
    GltfBuilder b;
    b.node({{"mesh", b.triangle_mesh()}});
    b.add_camera_and_light();
    b.animate(1, "translation", {0, 1, 1}, {0, 0, 5, 0, 0, 6, 0, 0, 7});
    expect_error(b, "animations[0].samplers[0].input: key times must increase");
  }
  {
    GltfBuilder b;
    b.node({{"mesh", b.triangle_mesh()}});
    b.add_camera_and_light();
    b.doc()["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {1.5, 0, 0, 1}}}}}};
    b.doc()["meshes"][0]["primitives"][0]["material"] = 0;
    expect_error(b, "materials[0].pbrMetallicRoughness.baseColorFactor[0]: must be in [0, 1], got 1.5");
  }
  {
    GltfBuilder b;
    b.node({{"mesh", b.triangle_mesh()}});
    b.add_camera_and_light();
    b.doc()["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    b.doc()["extensionsUsed"].push_back("KHR_draco_mesh_compression");
    expect_error(b, "extensionsRequired: extension 'KHR_draco_mesh_compression' is required by the file but not supported");
  }
}

// Buffers follow the OBJ loader's file rules: regular files only, relative to the glTF's folder
// unless absolute, and short messages naming the field.
class GltfBuffers : public Gltf {
 protected:
  GltfBuffers() {
    b_.node({{"mesh", b_.triangle_mesh()}});
    b_.add_camera_and_light();
  }
  // The message of loading the scene with this buffer; "" (and a failure) when it loads.
  std::string error_with(const json& buffer) {
    try {
      load_scene_file(write("scene.gltf", b_.gltf_text_with_buffer(buffer)));
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      EXPECT_LT(std::string(e.what()).size(), 400u) << e.what();
      return e.what();
    }
    ADD_FAILURE() << "loaded " << buffer.dump().substr(0, 200);
    return "";
  }
  json external(const std::string& uri, size_t length) { return {{"byteLength", length}, {"uri", uri}}; }
  GltfBuilder b_;
};

TEST_F(GltfBuffers, AnExternalBufferLoadsRelativeOrAbsolute) {
  write("mesh data.bin", b_.bytes());
  EXPECT_EQ(load_scene_file(write("scene.gltf", b_.gltf_text_with_buffer(external("mesh%20data.bin", b_.bytes().size()))))
                .triangle_count(), 1u);
  const std::string absolute = (dir_ / "mesh data.bin").string();
  EXPECT_EQ(load_scene_file(write("scene.gltf", b_.gltf_text_with_buffer(external(absolute, b_.bytes().size()))))
                .triangle_count(), 1u);
}

TEST_F(GltfBuffers, AFifoIsRefusedWithoutBlocking) {
  ASSERT_EQ(::mkfifo((dir_ / "pipe.bin").c_str(), 0644), 0);
  const std::string scene = write("scene.gltf", b_.gltf_text_with_buffer(external("pipe.bin", 12)));
  // In a child with an alarm: reading the FIFO used to block forever.
  EXPECT_EXIT(
      {
        ::alarm(20);
        try {
          load_scene_file(scene);
        } catch (const InputError& e) {
          std::exit(std::string(e.what()).find(": buffers[0].uri: 'pipe.bin' is not a regular file") != std::string::npos
                        ? 0 : 3);
        }
        std::exit(4);
      },
      ::testing::ExitedWithCode(0), "");
}

TEST_F(GltfBuffers, AFolderIsRefused) {
  EXPECT_NE(error_with(external(".", 12)).find("buffers[0].uri: '.' is a folder, not a regular file"), std::string::npos);
}

TEST_F(GltfBuffers, AWrongByteLengthOfADataUriIsOneShortLine) {
  // 6 MB of base64 claimed to be 12 bytes: the message used to echo the whole URI.
  const std::string big(4500000, 'x');
  const std::string message =
      error_with({{"byteLength", 12}, {"uri", "data:application/octet-stream;base64," + base64(big)}});
  EXPECT_NE(message.find("buffers[0].byteLength: 12, but its data URI holds 4500000 bytes"), std::string::npos) << message;
  EXPECT_NE(error_with({{"byteLength", 12}, {"uri", "data:application/octet-stream;base64,@@@@"}})
                .find("buffers[0].uri: the data URI is not valid base64"), std::string::npos);
}

TEST_F(GltfBuffers, AFileOfTheWrongSizeIsNamedNotCalledMissing) {
  const std::string message = error_with(external("/etc/passwd", 12));
  EXPECT_NE(message.find("buffers[0].byteLength: 12, but '/etc/passwd' has "), std::string::npos) << message;
  EXPECT_EQ(message.find("not found"), std::string::npos) << message;
}

TEST_F(GltfBuffers, AMissingFileSaysWhereItWasLookedFor) {
  const std::string message = error_with(external("nope.bin", 12));
  EXPECT_NE(message.find("buffers[0].uri: 'nope.bin' not found (looked for '" + (dir_ / "nope.bin").string() + "')"),
            std::string::npos) << message;
}

TEST_F(GltfBuffers, ADeeplyNestedDocumentIsRefused) {
  std::string text = b_.gltf_text();
  text.insert(text.size() - 1, ", \"extras\": " + std::string(200, '[') + std::string(200, ']'));
  try {
    load_scene_file(write("deep.gltf", text));
    ADD_FAILURE() << "loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("JSON nested deeper than 100 levels"), std::string::npos) << e.what();
  }
}

TEST_F(GltfBuffers, AnImageThatIsAFifoDoesNotBlock) {
  ASSERT_EQ(::mkfifo((dir_ / "tex.png").c_str(), 0644), 0);
  b_.doc()["images"] = {{{"uri", "tex.png"}}};
  const std::string scene = write("scene.gltf", b_.gltf_text());
  EXPECT_EXIT(
      {
        ::alarm(20);
        SceneLoadReport report;
        std::exit(load_scene_file(scene, &report).triangle_count() == 1 ? 0 : 3);
      },
      ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace pm

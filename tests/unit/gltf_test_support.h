// Test support for the glTF loader's tests (gltf_scene_test.cpp, gltf_buffers_test.cpp): a builder
// of small glTF documents (each accessor its own bufferView in one base64 buffer) and a fixture
// that writes them to a per-test folder, loads them and checks one-line error messages.
#pragma once

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
#include "support/test_folder.h"

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
    const int per_element = type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : 4;
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

class Gltf : public test::FolderTest {
 protected:
  Gltf() : FolderTest("pm_gltf_") {}
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
};

}  // namespace
}  // namespace pm

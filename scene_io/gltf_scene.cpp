// Owns the glTF 2.0 loader: tinygltf parses the file (Debian's libtinygltf, image decoding
// disabled: textures are ignored), this file validates what pmrender uses and converts it into
// pm::Scene. glTF units are metres, so nothing is rescaled.
#include "scene_io/gltf_scene.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "render/scene_frame.h"
#include "scene_io/animation_json.h"
#include "scene_io/gltf_animation.h"
#include "scene_io/gltf_files.h"
#include "scene_io/json_reader.h"
#include "scene_io/load_error.h"
#include "scene_io/obj_mesh.h"

namespace pm {

double candela_to_watts(double candela, double colour) { return colour * 4.0 * M_PI * candela / 683.0; }

double roughness_to_phong_exponent(double roughness) {
  const double alpha = roughness * roughness;
  if (alpha == 0) return INFINITY;
  return std::max(0.0, 2.0 / (alpha * alpha) - 2.0);
}

namespace {

namespace fs = std::filesystem;
using gltf::Mat4;
using gltf::Vec3d;

const int kMaxResolution = 16384;
const double kDefaultHeight = 512;

std::string str(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string indexed(const std::string& array, size_t i) { return array + "[" + std::to_string(i) + "]"; }

std::string quoted_name(const std::string& name) { return name.empty() ? "" : " ('" + name + "')"; }

// tinygltf decodes images unless told otherwise; pmrender has no textures, so it takes none.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

class GltfLoader {
 public:
  GltfLoader(std::string path, SceneLoadReport* report) : path_(std::move(path)), report_(report) {}

  Scene load();

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw_input_error(where.empty() ? path_ : path_ + ": " + where, what);
  }
  void warn(const std::string& text) { report_->warnings.push_back(single_line(path_ + ": " + text)); }

  void parse_file();
  void read_extras();
  void build_hierarchy();
  void read_animations();
  Mat4 local_matrix(int node, double t, bool animated) const;
  Mat4 world_matrix(int node, double t, bool animated) const;
  bool node_is_animated(int node) const;  // the node or an ancestor has a TRS channel

  std::vector<double> read_accessor(int index, const std::string& where, std::vector<int> types, bool normalized_ints,
                                    size_t* count, int* components) const;
  std::vector<uint32_t> read_indices(int index, const std::string& where) const;

  void read_meshes(Scene& scene);
  void append_primitive(const tinygltf::Primitive& primitive, const std::string& where, const Mat4& world,
                        Scene& scene, std::map<int, uint32_t>& material_index);
  MaterialDesc convert_material(int index);
  int choose_camera_node();
  CameraDesc camera_at(int node, double t, bool animated) const;
  void read_lights(Scene& scene);
  void read_animation(Scene& scene);

  std::string path_;
  SceneLoadReport* report_;
  tinygltf::Model model_;
  int scene_index_ = 0;
  std::vector<int> parent_;
  std::vector<int> order_;  // nodes of the scene, depth first
  std::vector<std::array<const gltf::Sampler*, 3>> channels_;  // per node: translation, rotation, scale
  std::vector<gltf::Sampler> samplers_;
  std::vector<std::string> sampler_where_;

  // extras.pmrender of the chosen scene
  nlohmann::json extras_document_;
  bool has_frame_rate_ = false, has_frames_ = false, has_resolution_ = false;
  double frame_rate_ = kGltfDefaultFrameRate;
  int first_frame_ = 0, last_frame_ = 0;
  int width_ = 0, height_ = 0;
  std::string camera_name_, scene_name_;

  int camera_node_ = -1;
  std::vector<int> light_nodes_;
};

void GltfLoader::parse_file() {
  check_gltf_files(path_);  // the file, its nesting and its buffers, before tinygltf reads them

  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks(regular_file_callbacks(&path_));
  loader.SetImageLoader(&skip_image, nullptr);
  loader.SetStoreOriginalJSONForExtrasAndExtensions(true);
  std::string err, warn;
  std::string ext = fs::path(path_).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const bool ok = ext == ".glb" ? loader.LoadBinaryFromFile(&model_, &err, &warn, path_)
                                : loader.LoadASCIIFromFile(&model_, &err, &warn, path_);
  if (!ok) fail("", "glTF: " + (err.empty() ? std::string("cannot be read") : short_tinygltf_message(err)));
  std::istringstream lines(warn);
  for (std::string line; std::getline(lines, line);)
    if (!short_tinygltf_message(line).empty()) this->warn("glTF: " + short_tinygltf_message(line));
  for (const std::string& required : model_.extensionsRequired) {
    if (required != "KHR_lights_punctual" && required != "KHR_materials_emissive_strength")
      fail("extensionsRequired", "extension '" + required + "' is required by the file but not supported");
  }
}

void GltfLoader::read_extras() {
  const tinygltf::Scene& scene = model_.scenes[size_t(scene_index_)];
  if (scene.extras_json_string.empty()) return;
  try {
    extras_document_ = nlohmann::json::parse(scene.extras_json_string);
  } catch (const std::exception& e) {
    fail(indexed("scenes", size_t(scene_index_)) + ".extras", std::string("not valid JSON: ") + e.what());
  }
  const JsonField extras(path_, extras_document_, indexed("scenes", size_t(scene_index_)) + ".extras");
  if (!extras.has("pmrender")) return;
  const JsonField field = extras.member("pmrender");
  field.expect_object_with_keys({"name", "frame_rate", "frames", "resolution", "camera"});
  if (field.has("name")) scene_name_ = field.member("name").non_empty_string();
  if (field.has("frame_rate")) {
    const JsonField rate = field.member("frame_rate");
    frame_rate_ = rate.finite_number();
    if (!(frame_rate_ > 0 && frame_rate_ <= 1e6))
      rate.fail("must be in (0, 1e6] frames per second, got " + describe_json_value(rate.value()));
    has_frame_rate_ = true;
  }
  if (field.has("frames")) {
    const JsonField frames = field.member("frames");
    frames.expect_array(2);
    first_frame_ = int(frames.element(0).integer_in(0, 999999999));
    last_frame_ = int(frames.element(1).integer_in(0, 999999999));
    if (last_frame_ < first_frame_)
      frames.element(1).fail("the last frame is before the first (" + std::to_string(first_frame_) + ")");
    if (static_cast<long long>(last_frame_) - first_frame_ + 1 > kMaxSequenceFrames)
      frames.fail("more than " + std::to_string(kMaxSequenceFrames) + " frames");
    has_frames_ = true;
  }
  if (field.has("resolution")) {
    const JsonField resolution = field.member("resolution");
    resolution.expect_array(2);
    width_ = int(resolution.element(0).integer_in(1, kMaxResolution));
    height_ = int(resolution.element(1).integer_in(1, kMaxResolution));
    has_resolution_ = true;
  }
  if (field.has("camera")) camera_name_ = field.member("camera").non_empty_string();
}

void GltfLoader::build_hierarchy() {
  parent_.assign(model_.nodes.size(), -1);
  std::vector<char> seen(model_.nodes.size(), 0);
  std::function<void(int, int, const std::string&)> visit = [&](int node, int parent, const std::string& where) {
    if (node < 0 || size_t(node) >= model_.nodes.size())
      fail(where, "node index " + std::to_string(node) + " out of range (" + std::to_string(model_.nodes.size()) +
                      " nodes)");
    if (seen[size_t(node)]) fail(where, "node " + std::to_string(node) + " appears twice in the scene (a cycle or a shared child)");
    seen[size_t(node)] = 1;
    parent_[size_t(node)] = parent;
    order_.push_back(node);
    const tinygltf::Node& n = model_.nodes[size_t(node)];
    if (!n.matrix.empty() && n.matrix.size() != 16) fail(indexed("nodes", size_t(node)) + ".matrix", "expected 16 numbers");
    for (size_t c = 0; c < n.children.size(); ++c)
      visit(n.children[c], node, indexed(indexed("nodes", size_t(node)) + ".children", c));
  };
  const tinygltf::Scene& scene = model_.scenes[size_t(scene_index_)];
  for (size_t i = 0; i < scene.nodes.size(); ++i)
    visit(scene.nodes[i], -1, indexed(indexed("scenes", size_t(scene_index_)) + ".nodes", i));
}

std::vector<double> GltfLoader::read_accessor(int index, const std::string& where, std::vector<int> types,
                                              bool normalized_ints, size_t* count, int* components) const {
  if (index < 0 || size_t(index) >= model_.accessors.size())
    fail(where, "accessor " + std::to_string(index) + " out of range (" + std::to_string(model_.accessors.size()) +
                    " accessors)");
  const tinygltf::Accessor& a = model_.accessors[size_t(index)];
  const std::string at = where + " (accessors[" + std::to_string(index) + "])";
  if (std::find(types.begin(), types.end(), a.type) == types.end()) fail(at, "unexpected element type");
  if (a.sparse.isSparse) fail(at, "sparse accessors are not supported");
  if (a.bufferView < 0 || size_t(a.bufferView) >= model_.bufferViews.size()) fail(at, "no valid bufferView");
  const bool is_float = a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
  const bool is_normalized_int =
      normalized_ints && a.normalized &&
      (a.componentType == TINYGLTF_COMPONENT_TYPE_BYTE || a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
       a.componentType == TINYGLTF_COMPONENT_TYPE_SHORT || a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  if (!is_float && !is_normalized_int)
    fail(at, normalized_ints ? "components must be FLOAT or normalized integers" : "components must be FLOAT");
  const tinygltf::BufferView& view = model_.bufferViews[size_t(a.bufferView)];
  if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size()) fail(at, "bufferView has no valid buffer");
  const std::vector<unsigned char>& data = model_.buffers[size_t(view.buffer)].data;
  const int n = tinygltf::GetNumComponentsInType(uint32_t(a.type));
  const int size = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
  const int stride = a.ByteStride(view);
  if (n <= 0 || size <= 0 || stride <= 0) fail(at, "invalid byteStride or component type");
  if (a.count > 0 && (a.byteOffset + (a.count - 1) * size_t(stride) + size_t(n * size) > view.byteLength ||
                      view.byteOffset + view.byteLength > data.size()))
    fail(at, "reads past the end of its bufferView or buffer");
  std::vector<double> out(a.count * size_t(n));
  for (size_t e = 0; e < a.count; ++e) {
    const unsigned char* p = data.data() + view.byteOffset + a.byteOffset + e * size_t(stride);
    for (int c = 0; c < n; ++c) {
      const unsigned char* q = p + c * size;
      double v = 0;
      switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, q, 4); v = f; break; }
        case TINYGLTF_COMPONENT_TYPE_BYTE: { int8_t i; std::memcpy(&i, q, 1); v = std::max(i / 127.0, -1.0); break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: { uint8_t i; std::memcpy(&i, q, 1); v = i / 255.0; break; }
        case TINYGLTF_COMPONENT_TYPE_SHORT: { int16_t i; std::memcpy(&i, q, 2); v = std::max(i / 32767.0, -1.0); break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t i; std::memcpy(&i, q, 2); v = i / 65535.0; break; }
      }
      if (!std::isfinite(v)) fail(at, "element " + std::to_string(e) + " is not finite");
      out[e * size_t(n) + size_t(c)] = v;
    }
  }
  *count = a.count;
  *components = n;
  return out;
}

std::vector<uint32_t> GltfLoader::read_indices(int index, const std::string& where) const {
  if (index < 0 || size_t(index) >= model_.accessors.size())
    fail(where, "accessor " + std::to_string(index) + " out of range");
  const tinygltf::Accessor& a = model_.accessors[size_t(index)];
  const std::string at = where + " (accessors[" + std::to_string(index) + "])";
  if (a.type != TINYGLTF_TYPE_SCALAR) fail(at, "indices must be SCALAR");
  if (a.sparse.isSparse) fail(at, "sparse accessors are not supported");
  if (a.bufferView < 0 || size_t(a.bufferView) >= model_.bufferViews.size()) fail(at, "no valid bufferView");
  const int size = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
  if (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    fail(at, "indices must be UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
  const tinygltf::BufferView& view = model_.bufferViews[size_t(a.bufferView)];
  if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size()) fail(at, "bufferView has no valid buffer");
  const std::vector<unsigned char>& data = model_.buffers[size_t(view.buffer)].data;
  const int stride = a.ByteStride(view);
  if (stride <= 0) fail(at, "invalid byteStride");
  if (a.count > 0 && (a.byteOffset + (a.count - 1) * size_t(stride) + size_t(size) > view.byteLength ||
                      view.byteOffset + view.byteLength > data.size()))
    fail(at, "reads past the end of its bufferView or buffer");
  std::vector<uint32_t> out(a.count);
  for (size_t e = 0; e < a.count; ++e) {
    const unsigned char* p = data.data() + view.byteOffset + a.byteOffset + e * size_t(stride);
    if (size == 1) out[e] = p[0];
    else if (size == 2) { uint16_t v; std::memcpy(&v, p, 2); out[e] = v; }
    else { uint32_t v; std::memcpy(&v, p, 4); out[e] = v; }
  }
  return out;
}

void GltfLoader::read_animations() {
  channels_.assign(model_.nodes.size(), {nullptr, nullptr, nullptr});
  size_t total = 0;
  for (const tinygltf::Animation& animation : model_.animations) total += animation.samplers.size();
  samplers_.reserve(total);  // channels_ points into it
  for (size_t a = 0; a < model_.animations.size(); ++a) {
    const tinygltf::Animation& animation = model_.animations[a];
    const std::string at = indexed("animations", a);
    const size_t first_sampler = samplers_.size();
    for (size_t s = 0; s < animation.samplers.size(); ++s) {
      const tinygltf::AnimationSampler& in = animation.samplers[s];
      const std::string where = indexed(at + ".samplers", s);
      gltf::Sampler sampler;
      if (in.interpolation == "LINEAR") sampler.interpolation = gltf::SamplerInterpolation::linear;
      else if (in.interpolation == "STEP") sampler.interpolation = gltf::SamplerInterpolation::step;
      else if (in.interpolation == "CUBICSPLINE") sampler.interpolation = gltf::SamplerInterpolation::cubic_spline;
      else fail(where + ".interpolation", "expected LINEAR, STEP or CUBICSPLINE, got '" + in.interpolation + "'");
      size_t count = 0;
      int components = 0;
      sampler.times = read_accessor(in.input, where + ".input", {TINYGLTF_TYPE_SCALAR}, false, &count, &components);
      if (count == 0) fail(where + ".input", "no key times");
      for (size_t k = 1; k < count; ++k)
        if (!(sampler.times[k] > sampler.times[k - 1]))
          fail(where + ".input", "key times must increase (key " + std::to_string(k) + ": " + str(sampler.times[k]) +
                                     " after " + str(sampler.times[k - 1]) + ")");
      size_t out_count = 0;
      sampler.values = read_accessor(in.output, where + ".output", {TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4, TINYGLTF_TYPE_SCALAR},
                                     true, &out_count, &sampler.components);
      const size_t expected = sampler.interpolation == gltf::SamplerInterpolation::cubic_spline ? 3 * count : count;
      if (out_count != expected && sampler.components != 1)
        fail(where + ".output", std::to_string(out_count) + " elements for " + std::to_string(count) + " key times (expected " +
                                    std::to_string(expected) + ")");
      samplers_.push_back(std::move(sampler));
      sampler_where_.push_back(where);
    }
    for (size_t c = 0; c < animation.channels.size(); ++c) {
      const tinygltf::AnimationChannel& channel = animation.channels[c];
      const std::string where = indexed(at + ".channels", c);
      if (channel.sampler < 0 || size_t(channel.sampler) >= animation.samplers.size())
        fail(where + ".sampler", "sampler index " + std::to_string(channel.sampler) + " out of range");
      const gltf::Sampler* sampler = &samplers_[first_sampler + size_t(channel.sampler)];
      if (channel.target_node < 0 || size_t(channel.target_node) >= model_.nodes.size()) {
        warn(where + ": no target node; ignored");
        continue;
      }
      int slot;
      int components;
      if (channel.target_path == "translation") slot = 0, components = 3;
      else if (channel.target_path == "rotation") slot = 1, components = 4;
      else if (channel.target_path == "scale") slot = 2, components = 3;
      else {
        warn(where + ": '" + channel.target_path + "' animation is not supported; ignored");
        continue;
      }
      if (sampler->components != components)
        fail(where, channel.target_path + " needs " + std::to_string(components) + "-component output, sampler has " +
                        std::to_string(sampler->components));
      auto& target = channels_[size_t(channel.target_node)][size_t(slot)];
      if (target) {
        warn(where + ": node " + std::to_string(channel.target_node) + " " + channel.target_path +
             " is animated by an earlier channel; ignored");
        continue;
      }
      target = sampler;
    }
  }
}

Mat4 GltfLoader::local_matrix(int node, double t, bool animated) const {
  const tinygltf::Node& n = model_.nodes[size_t(node)];
  if (n.matrix.size() == 16) {
    Mat4 m;
    for (int i = 0; i < 16; ++i) m.m[size_t(i)] = n.matrix[size_t(i)];
    return m;
  }
  Vec3d translation{0, 0, 0}, scale{1, 1, 1};
  gltf::Quat rotation{0, 0, 0, 1};
  if (n.translation.size() == 3) translation = {n.translation[0], n.translation[1], n.translation[2]};
  if (n.rotation.size() == 4) rotation = {n.rotation[0], n.rotation[1], n.rotation[2], n.rotation[3]};
  if (n.scale.size() == 3) scale = {n.scale[0], n.scale[1], n.scale[2]};
  if (animated) {
    const auto& ch = channels_[size_t(node)];
    if (ch[0]) { auto v = ch[0]->evaluate(t); translation = {v[0], v[1], v[2]}; }
    if (ch[1]) { auto v = ch[1]->evaluate(t); rotation = {v[0], v[1], v[2], v[3]}; }
    if (ch[2]) { auto v = ch[2]->evaluate(t); scale = {v[0], v[1], v[2]}; }
  }
  return gltf::mat4_from_trs(translation, rotation, scale);
}

Mat4 GltfLoader::world_matrix(int node, double t, bool animated) const {
  Mat4 m = local_matrix(node, t, animated);
  for (int p = parent_[size_t(node)]; p >= 0; p = parent_[size_t(p)]) m = local_matrix(p, t, animated) * m;
  return m;
}

bool GltfLoader::node_is_animated(int node) const {
  for (int n = node; n >= 0; n = parent_[size_t(n)]) {
    const auto& ch = channels_[size_t(n)];
    if (ch[0] || ch[1] || ch[2]) return true;
  }
  return false;
}

MaterialDesc GltfLoader::convert_material(int index) {
  const tinygltf::Material& m = model_.materials[size_t(index)];
  const std::string where = indexed("materials", size_t(index));
  const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
  MaterialDesc desc;
  desc.name = m.name.empty() ? "material" + std::to_string(index) : m.name;
  if (pbr.baseColorFactor.size() != 4) fail(where + ".pbrMetallicRoughness.baseColorFactor", "expected 4 numbers");
  double base[3];
  for (int c = 0; c < 3; ++c) {
    base[c] = pbr.baseColorFactor[size_t(c)];
    if (!(base[c] >= 0 && base[c] <= 1))
      fail(where + ".pbrMetallicRoughness.baseColorFactor[" + std::to_string(c) + "]", "must be in [0, 1], got " + str(base[c]));
  }
  const double metallic = pbr.metallicFactor, roughness = pbr.roughnessFactor;
  if (!(metallic >= 0 && metallic <= 1))
    fail(where + ".pbrMetallicRoughness.metallicFactor", "must be in [0, 1], got " + str(metallic));
  if (!(roughness >= 0 && roughness <= 1))
    fail(where + ".pbrMetallicRoughness.roughnessFactor", "must be in [0, 1], got " + str(roughness));
  const Float3 diffuse{float(base[0] * (1 - metallic)), float(base[1] * (1 - metallic)), float(base[2] * (1 - metallic))};
  const Float3 specular{float(base[0] * metallic), float(base[1] * metallic), float(base[2] * metallic)};
  desc.diffuse = diffuse;
  desc.glossy = Float3{0, 0, 0};
  desc.mirror = Float3{0, 0, 0};
  desc.glossy_exponent = 1.0f;
  if (metallic > 0) {
    const double exponent = roughness_to_phong_exponent(roughness);
    if (exponent >= kGltfMirrorExponent) {
      desc.mirror = specular;
    } else {
      desc.glossy = specular;
      desc.glossy_exponent = float(exponent);
    }
  }
  std::vector<std::string> ignored;
  if (pbr.baseColorTexture.index >= 0) ignored.push_back("baseColorTexture");
  if (pbr.metallicRoughnessTexture.index >= 0) ignored.push_back("metallicRoughnessTexture");
  if (m.normalTexture.index >= 0) ignored.push_back("normalTexture");
  if (m.occlusionTexture.index >= 0) ignored.push_back("occlusionTexture");
  if (m.emissiveTexture.index >= 0) ignored.push_back("emissiveTexture");
  if (m.emissiveFactor.size() == 3 && (m.emissiveFactor[0] > 0 || m.emissiveFactor[1] > 0 || m.emissiveFactor[2] > 0))
    ignored.push_back("emissiveFactor (emissive surfaces do not become lights)");
  if (m.alphaMode != "OPAQUE") ignored.push_back("alphaMode " + m.alphaMode);
  for (const auto& extension : m.extensions) ignored.push_back(extension.first);
  if (!ignored.empty()) {
    std::string list;
    for (const std::string& item : ignored) list += (list.empty() ? "" : ", ") + item;
    warn(where + quoted_name(m.name) + ": ignored: " + list);
  }
  return desc;
}

void GltfLoader::append_primitive(const tinygltf::Primitive& primitive, const std::string& where, const Mat4& world,
                                  Scene& scene, std::map<int, uint32_t>& material_index) {
  const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    warn(where + ": points and lines are not rendered; skipped");
    return;
  }
  auto position_it = primitive.attributes.find("POSITION");
  if (position_it == primitive.attributes.end()) fail(where + ".attributes", "no POSITION attribute");
  size_t vertex_count = 0;
  int components = 0;
  const std::vector<double> local =
      read_accessor(position_it->second, where + ".attributes.POSITION", {TINYGLTF_TYPE_VEC3}, false, &vertex_count, &components);
  if (!primitive.targets.empty()) warn(where + ": morph targets are ignored (base shape used)");

  std::vector<uint32_t> corners;
  if (primitive.indices >= 0) {
    corners = read_indices(primitive.indices, where + ".indices");
    for (size_t i = 0; i < corners.size(); ++i)
      if (corners[i] >= vertex_count)
        fail(where + ".indices", "index " + std::to_string(corners[i]) + " at position " + std::to_string(i) +
                                     " out of range (" + std::to_string(vertex_count) + " vertices)");
  } else {
    corners.resize(vertex_count);
    for (size_t i = 0; i < vertex_count; ++i) corners[i] = uint32_t(i);
  }
  std::vector<uint32_t> triangles;
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    if (corners.size() % 3 != 0) fail(where, std::to_string(corners.size()) + " corners are not a multiple of 3 (TRIANGLES)");
    triangles = corners;
  } else {
    for (size_t i = 2; i < corners.size(); ++i) {
      if (mode == TINYGLTF_MODE_TRIANGLE_FAN) triangles.insert(triangles.end(), {corners[0], corners[i - 1], corners[i]});
      else if (i % 2 == 0) triangles.insert(triangles.end(), {corners[i - 2], corners[i - 1], corners[i]});
      else triangles.insert(triangles.end(), {corners[i - 1], corners[i - 2], corners[i]});
    }
  }

  uint32_t material;
  const int m = primitive.material;
  auto it = material_index.find(m);
  if (it != material_index.end()) {
    material = it->second;
  } else {
    if (m >= 0 && size_t(m) >= model_.materials.size())
      fail(where + ".material", "material index " + std::to_string(m) + " out of range");
    MaterialDesc desc;  // no material: pmrender's grey default (glTF's default is a white metal)
    desc.name = "default";
    if (m >= 0) desc = convert_material(m);
    material = uint32_t(scene.materials.size());
    scene.materials.push_back(desc);
    material_index[m] = material;
  }

  const size_t base = scene.positions.size();
  if (base + vertex_count > UINT32_MAX) fail(where, "too many vertices in the scene for 32-bit indices");
  for (size_t v = 0; v < vertex_count; ++v) {
    const Vec3d p = gltf::transform_point(world, {local[3 * v], local[3 * v + 1], local[3 * v + 2]});
    const Float3 f{float(p[0]), float(p[1]), float(p[2])};
    if (!std::isfinite(f.x) || !std::isfinite(f.y) || !std::isfinite(f.z))
      fail(where + ".attributes.POSITION", "vertex " + std::to_string(v) + " is beyond float range after its node transform");
    scene.positions.push_back(f);
  }
  size_t dropped = 0;
  for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const uint32_t a = uint32_t(base + triangles[t]), b = uint32_t(base + triangles[t + 1]), c = uint32_t(base + triangles[t + 2]);
    if (is_degenerate_triangle(scene.positions[a], scene.positions[b], scene.positions[c])) {
      ++dropped;
      continue;
    }
    scene.indices.insert(scene.indices.end(), {a, b, c});
    scene.triangle_material.push_back(material);
  }
  if (dropped > 0) {
    report_->degenerate_triangles_dropped += dropped;
    warn(where + ": " + std::to_string(dropped) + " degenerate triangles dropped");
  }
}

void GltfLoader::read_meshes(Scene& scene) {
  std::map<int, uint32_t> material_index;
  bool warned_animation = false;
  for (int node : order_) {
    const tinygltf::Node& n = model_.nodes[size_t(node)];
    if (n.mesh < 0) continue;
    const std::string where = indexed("nodes", size_t(node));
    if (size_t(n.mesh) >= model_.meshes.size()) fail(where + ".mesh", "mesh index " + std::to_string(n.mesh) + " out of range");
    if (n.skin >= 0) warn(where + quoted_name(n.name) + ": skinning is ignored (the mesh is used as stored)");
    if (node_is_animated(node) && !warned_animation) {
      warn(where + quoted_name(n.name) + ": meshes do not move (geometry is static for a sequence); the rest pose is used");
      warned_animation = true;
    }
    const Mat4 world = world_matrix(node, 0.0, false);
    const tinygltf::Mesh& mesh = model_.meshes[size_t(n.mesh)];
    for (size_t p = 0; p < mesh.primitives.size(); ++p)
      append_primitive(mesh.primitives[p], indexed(indexed("meshes", size_t(n.mesh)) + ".primitives", p), world, scene,
                       material_index);
  }
  if (scene.triangle_count() == 0)
    fail("meshes", "the scene has no triangles (" + std::to_string(report_->degenerate_triangles_dropped) +
                       " degenerate triangles dropped)");
}

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

void GltfLoader::read_lights(Scene& scene) {
  double total = 0;
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
    if (l.type != "point") {
      warn(light_where + quoted_name(l.name) + ": " + l.type + " lights are not supported (isotropic point lights only); skipped");
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
    light.name = !l.name.empty() ? l.name : !n.name.empty() ? n.name : "light" + std::to_string(scene.lights.size());
    const Vec3d p = gltf::transform_point(world_matrix(node, 0.0, false), {0, 0, 0});
    light.position = Float3{float(p[0]), float(p[1]), float(p[2])};
    light.power = Float3{float(candela_to_watts(l.intensity, colour[0])), float(candela_to_watts(l.intensity, colour[1])),
                         float(candela_to_watts(l.intensity, colour[2]))};
    total += double(light.power.x) + light.power.y + light.power.z;
    scene.lights.push_back(light);
    light_nodes_.push_back(node);
  }
  if (scene.lights.empty()) fail("extensions.KHR_lights_punctual", "at least one point light is required");
  if (total == 0) fail("extensions.KHR_lights_punctual", "every light has zero intensity");
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

  read_lights(scene);
  read_animation(scene);
  // A still scene shows its nodes at rest; a sequence's static values are those of its first frame.
  if (scene.animation.enabled) {
    scene.camera = camera_at_frame(scene, scene.animation.first_frame);
    scene.lights = lights_at_frame(scene, scene.animation.first_frame);
  }
  return scene;
}

}  // namespace

Scene load_gltf_scene(const std::string& path, SceneLoadReport* report) {
  SceneLoadReport local_report;
  SceneLoadReport* r = report ? report : &local_report;
  *r = SceneLoadReport{};
  return GltfLoader(path, r).load();
}

}  // namespace pm

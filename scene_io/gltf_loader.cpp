// The glTF loader's first steps (scene_io/gltf_loader.h): tinygltf parses the file (images kept
// encoded: gltf_textures.cpp decodes the used ones), then extras.pmrender, the node hierarchy of the
// chosen scene, typed accessor reads with every index and range checked, and the animation
// channels with the node transforms they drive.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include "render/scene_frame.h"
#include "scene_io/animation_json.h"
#include "scene_io/gltf_animation.h"
#include "scene_io/gltf_files.h"
#include "scene_io/gltf_loader.h"
#include "scene_io/json_reader.h"
#include "scene_io/load_error.h"
#include "scene_io/obj_mesh.h"

namespace pm::gltf {

namespace fs = std::filesystem;

std::string str(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

namespace {

// tinygltf would decode every image with its own limits; pmrender keeps a URI image's encoded
// bytes (file or data URI) and decodes those its materials use (gltf_textures.cpp), with its own
// limits and messages. A bufferView image is read from its buffer there, bounds checked first.
bool keep_encoded_image(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  if (image->bufferView < 0 && bytes && size > 0) image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

}  // namespace

void GltfLoader::parse_file() {
  check_gltf_files(path_);  // the file, its nesting and its buffers, before tinygltf reads them

  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks(regular_file_callbacks(&path_));
  loader.SetImageLoader(&keep_encoded_image, nullptr);
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

}  // namespace pm::gltf

// Internal to scene_io: the glTF 2.0 loader's state and steps, shared by the four files that
// implement them: gltf_loader.cpp (the file, extras.pmrender, the node hierarchy, accessors and
// animation channels), gltf_geometry.cpp (materials and mesh primitives), gltf_textures.cpp
// (base-colour textures, images, alpha masks, texture coordinates) and gltf_scene.cpp (the
// camera, the lights, their animation and the Scene). The public entry is gltf_scene.h.
#pragma once

#include <tiny_gltf.h>

#include <array>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "render/scene.h"
#include "scene_io/gltf_animation.h"
#include "scene_io/gltf_scene.h"
#include "scene_io/load_error.h"
#include "scene_io/scene_file.h"
#include "scene_io/texture_files.h"

namespace pm {
namespace gltf {

constexpr int kMaxResolution = 16384;
constexpr double kDefaultHeight = 512;

// Pieces of the one-line messages: a number as written, "array[i]", " ('name')".
std::string str(double v);
inline std::string indexed(const std::string& array, size_t i) { return array + "[" + std::to_string(i) + "]"; }
inline std::string quoted_name(const std::string& name) { return name.empty() ? "" : " ('" + name + "')"; }

class GltfLoader {
 public:
  GltfLoader(std::string path, SceneLoadReport* report, const EnvironmentDesc* environment = nullptr)
      : path_(std::move(path)), report_(report), environment_(environment) {}

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
  Float3 read_emission(int index);
  // Textures: the material's base-colour texture and alpha mask (into desc; features left out
  // into ignored), the scene image of a glTF image, the scene texture of a textureInfo (-1 when
  // it has no image pmrender can read), a primitive's texture coordinates.
  void add_material_textures(int index, MaterialDesc* desc, std::vector<std::string>* ignored);
  uint32_t decoded_image(int index, const std::string& where);
  int texture_of(const tinygltf::TextureInfo& info, const std::string& where);
  std::vector<Float2> read_texcoords(const tinygltf::Primitive& primitive, int set, const std::string& where,
                                     size_t vertex_count, int material) const;
  int choose_camera_node();
  CameraDesc camera_at(int node, double t, bool animated) const;
  void read_lights(Scene& scene);
  Vec3d light_direction_at(int node, double t, bool animated) const;
  void read_animation(Scene& scene);

  std::string path_;
  SceneLoadReport* report_;
  const EnvironmentDesc* environment_;  // the command line's --environment, or null
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
  int emissive_textures_ = 0;           // materials with an emissiveTexture (not read)
  std::string first_emissive_texture_;  // the first of them, for the one warning

  SceneTextures* textures_ = nullptr;   // the scene's, while load() runs
  std::map<int, uint32_t> image_index_;  // glTF image -> Scene::images entry
  std::map<int, int> material_texcoord_;  // glTF material -> its TEXCOORD set, -1: untextured
};

}  // namespace gltf
}  // namespace pm

// The glTF loader's geometry (scene_io/gltf_loader.h): metallic-roughness materials mapped onto
// modified Phong (docs/scene-format.md, "glTF scenes"), and the triangle primitives of every mesh
// node, transformed to world space, appended to the Scene with their materials and, where the
// material is textured, their texture coordinates.
#include <algorithm>
#include <cmath>
#include <cstring>
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
#include "scene_io/obj_text_check.h"

namespace pm::gltf {

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
  add_material_textures(index, &desc, &ignored);
  if (pbr.metallicRoughnessTexture.index >= 0) ignored.push_back("metallicRoughnessTexture");
  if (m.normalTexture.index >= 0) ignored.push_back("normalTexture");
  if (m.occlusionTexture.index >= 0) ignored.push_back("occlusionTexture");
  desc.emission = read_emission(index);
  for (const auto& extension : m.extensions)
    if (extension.first != "KHR_materials_emissive_strength") ignored.push_back(extension.first);
  if (!ignored.empty()) {
    std::string list;
    for (const std::string& item : ignored) list += (list.empty() ? "" : ", ") + item;
    warn(where + quoted_name(m.name) + ": ignored: " + list);
  }
  return desc;
}

// Emitted radiance: emissiveFactor times KHR_materials_emissive_strength's emissiveStrength is
// a luminance in cd/m^2 (nits), turned into W sr^-1 m^-2 per channel at 683 lm/W as the
// lights' candela are (docs/scene-format.md). emissiveTexture is not read (one warning per scene).
Float3 GltfLoader::read_emission(int index) {
  const tinygltf::Material& m = model_.materials[size_t(index)];
  const std::string where = indexed("materials", size_t(index));
  if (m.emissiveTexture.index >= 0) {
    ++emissive_textures_;
    if (first_emissive_texture_.empty()) first_emissive_texture_ = where + quoted_name(m.name);
  }
  if (m.emissiveFactor.empty()) return Float3{0, 0, 0};
  if (m.emissiveFactor.size() != 3) fail(where + ".emissiveFactor", "expected 3 numbers");
  double strength = 1;
  auto ext = m.extensions.find("KHR_materials_emissive_strength");
  if (ext != m.extensions.end() && ext->second.Has("emissiveStrength")) {
    const tinygltf::Value& value = ext->second.Get("emissiveStrength");
    strength = value.IsNumber() ? value.GetNumberAsDouble() : NAN;
    if (!(strength >= 0) || !std::isfinite(strength))
      fail(where + ".extensions.KHR_materials_emissive_strength.emissiveStrength",
           "must be a finite number >= 0, got " + (value.IsNumber() ? str(strength) : std::string("a non-number")));
  }
  double radiance[3];
  for (int c = 0; c < 3; ++c) {
    const double factor = m.emissiveFactor[size_t(c)];
    if (!(factor >= 0 && factor <= 1))
      fail(where + ".emissiveFactor[" + std::to_string(c) + "]", "must be in [0, 1], got " + str(factor));
    radiance[c] = factor * strength / kLumensPerWatt;
    if (!(radiance[c] <= 3.0e38)) fail(where + ".extensions.KHR_materials_emissive_strength.emissiveStrength", "beyond float range");
  }
  return Float3{float(radiance[0]), float(radiance[1]), float(radiance[2])};
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

  // A textured material's primitive brings the texture coordinates its texture reads.
  std::vector<Float2> uvs;
  auto texcoord_set = material_texcoord_.find(m);
  if (texcoord_set != material_texcoord_.end() && texcoord_set->second >= 0)
    uvs = read_texcoords(primitive, texcoord_set->second, where, vertex_count, m);

  const size_t base = scene.positions.size();
  if (base + vertex_count > UINT32_MAX) fail(where, "too many vertices in the scene for 32-bit indices");
  for (size_t v = 0; v < vertex_count; ++v) {
    const Vec3d p = gltf::transform_point(world, {local[3 * v], local[3 * v + 1], local[3 * v + 2]});
    // The bound of OBJ vertices and JSON scenes' positions (obj_text_check.h): beyond it
    // single-precision ray-triangle products overflow and surfaces vanish.
    for (double c : p)
      if (!(std::fabs(c) <= kMaxObjCoordinate))
        fail(where + ".attributes.POSITION", "vertex " + std::to_string(v) + " is " + describe_json_value(c) +
                                                 " m from the origin after its node transform; at most 1e15 m renders");
    scene.positions.push_back(Float3{float(p[0]), float(p[1]), float(p[2])});
  }
  // A node transform of negative determinant turns glTF's counter-clockwise front faces
  // clockwise: swapping two corners keeps the geometric normal on the front (the side emitters
  // emit from).
  const std::array<double, 16>& w = world.m;
  const double determinant = w[0] * (w[5] * w[10] - w[9] * w[6]) - w[4] * (w[1] * w[10] - w[9] * w[2]) +
                             w[8] * (w[1] * w[6] - w[5] * w[2]);
  if (determinant < 0)
    for (size_t t = 0; t + 2 < triangles.size(); t += 3) std::swap(triangles[t + 1], triangles[t + 2]);
  size_t dropped = 0;
  for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const uint32_t a = uint32_t(base + triangles[t]), b = uint32_t(base + triangles[t + 1]), c = uint32_t(base + triangles[t + 2]);
    if (is_degenerate_triangle(scene.positions[a], scene.positions[b], scene.positions[c])) {
      ++dropped;
      continue;
    }
    if (!uvs.empty()) {
      scene.triangle_uvs.resize(3 * scene.triangle_count());  // earlier untextured triangles: (0, 0)
      for (size_t k = 0; k < 3; ++k) scene.triangle_uvs.push_back(uvs[triangles[t + k]]);
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
    // Each node with a mesh is one object of the object_id layer (a mesh instanced twice: two).
    scene.triangle_object.resize(scene.triangle_material.size(), uint32_t(scene.object_names.size()));
    scene.object_names.push_back(n.name.empty() ? where : n.name);
  }
  if (scene.triangle_count() == 0)
    fail("meshes", "the scene has no triangles (" + std::to_string(report_->degenerate_triangles_dropped) +
                       " degenerate triangles dropped)");
}

}  // namespace pm::gltf

// Owns loading a pmrender JSON scene (format version 1, docs/scene-format.md) into pm::Scene:
// the top-level keys, JSON materials, meshes (through obj_mesh) with their vertices in metres, and
// the usemtl name -> material resolution (JSON materials first, then MTL); the lights and camera go
// through lights_camera_json, the environment through environment_json and the optional
// "animation" object through animation_json. Files ending in .gltf or .glb go to
// the glTF loader (gltf_scene.h) instead.
#include "scene_io/scene_file.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "scene_io/animation_json.h"
#include "scene_io/environment_json.h"
#include "scene_io/gltf_scene.h"
#include "scene_io/json_reader.h"
#include "scene_io/lights_camera_json.h"
#include "scene_io/load_error.h"
#include "scene_io/obj_mesh.h"
#include "scene_io/texture_files.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

const char kFormatName[] = "pmrender-scene";
const char* const kChannelNames[3] = {"red", "green", "blue"};
// Values are stored as floats, so 0.6 + 0.4 sums to 1.00000003; that must still count as 1.
constexpr double kReflectanceSumTolerance = 1e-6;

float component(const Float3& v, int i) { return i == 0 ? v.x : (i == 1 ? v.y : v.z); }

// --- materials -------------------------------------------------------------------------------

Float3 read_reflectance(const JsonField& field) {
  const Float3 value = field.float3();
  for (size_t i = 0; i < 3; ++i) {
    const float v = component(value, static_cast<int>(i));
    if (v < 0 || v > 1)
      field.element(i).fail("must be in [0, 1], got " + describe_json_value(field.element(i).value()));
  }
  return value;
}

MaterialDesc read_json_material(const JsonField& field, const std::string& name) {
  field.expect_object_with_keys({"diffuse", "glossy", "exponent", "mirror", "emission"});
  MaterialDesc desc;  // defaults: diffuse 0.8 grey, no glossy or mirror, exponent 1
  desc.name = name;
  if (field.has("diffuse")) desc.diffuse = read_reflectance(field.member("diffuse"));
  if (field.has("glossy")) desc.glossy = read_reflectance(field.member("glossy"));
  if (field.has("mirror")) desc.mirror = read_reflectance(field.member("mirror"));
  if (field.has("emission")) {
    // Radiance of a Lambertian emitter (an area light), W sr^-1 m^-2 per channel.
    const JsonField emission = field.member("emission");
    desc.emission = emission.float3();
    for (size_t i = 0; i < 3; ++i)
      if (!(component(desc.emission, static_cast<int>(i)) >= 0))
        emission.element(i).fail("must be >= 0 W sr^-1 m^-2, got " + describe_json_value(emission.element(i).value()));
  }
  if (field.has("exponent")) {
    const JsonField exponent = field.member("exponent");
    const double value = exponent.finite_number();
    if (value < 0 || value > 1e6)
      exponent.fail("must be in [0, 1e6], got " + describe_json_value(exponent.value()));
    desc.glossy_exponent = static_cast<float>(value);
  }
  // Hand-written materials that reflect more than they receive are mistakes; say so instead of
  // quietly rescaling (MTL files, written by exporters, are rescaled instead: mtl_material.h).
  for (int c = 0; c < 3; ++c) {
    const double sum =
        double(component(desc.diffuse, c)) + component(desc.glossy, c) + component(desc.mirror, c);
    if (sum > 1.0 + kReflectanceSumTolerance) {
      std::ostringstream text;
      text << "diffuse + glossy + mirror = " << sum << " exceeds 1 in the " << kChannelNames[c] << " channel";
      field.fail(text.str());
    }
  }
  return desc;
}

std::map<std::string, MaterialDesc> read_json_materials(const JsonField& root) {
  std::map<std::string, MaterialDesc> materials;
  if (!root.has("materials")) return materials;
  const JsonField field = root.member("materials");
  if (!field.value().is_object()) field.fail("expected an object, got " + describe_json_value(field.value()));
  for (const auto& item : field.value().items()) {
    if (item.key().empty()) field.fail("material names must not be empty");
    materials[item.key()] = read_json_material(
        JsonField(field.file(), item.value(), field.path() + "." + item.key()), item.key());
  }
  return materials;
}

// Builds Scene.materials in first-use order. Keys say where a material came from, so an MTL
// material and a JSON material of the same name, or two MTL files' "wall", stay distinct.
class MaterialTable {
 public:
  explicit MaterialTable(std::vector<MaterialDesc>* materials) : materials_(materials) {}

  uint32_t index_of(const std::string& key, const std::function<MaterialDesc()>& make) {
    auto it = index_by_key_.find(key);
    if (it != index_by_key_.end()) return it->second;
    const uint32_t index = static_cast<uint32_t>(materials_->size());
    materials_->push_back(make());
    index_by_key_[key] = index;
    return index;
  }

 private:
  std::vector<MaterialDesc>* materials_;
  std::map<std::string, uint32_t> index_by_key_;
};

// --- meshes ----------------------------------------------------------------------------------

struct LoadContext {
  fs::path json_dir;
  double meters_per_unit = 1.0;
  std::map<std::string, MaterialDesc> json_materials;
  SceneLoadReport* report;
  SceneTextures* textures = nullptr;
  // MTL statements the used materials have but pmrender does not render: per MTL file, per
  // statement, the materials (one warning each, at the end).
  std::map<std::string, std::map<std::string, std::vector<std::string>>> mtl_ignored;
};

void warn_ignored_mtl_statements(const LoadContext& ctx) {
  for (const auto& file : ctx.mtl_ignored) {
    for (const auto& statement : file.second) {
      const std::vector<std::string>& names = statement.second;
      ctx.report->warnings.push_back(single_line(
          file.first + ": " + statement.first + " is not rendered; ignored in " + std::to_string(names.size()) +
          (names.size() == 1 ? " material ('" : " materials (first '") + names.front() + "')"));
    }
  }
}

std::string check_mesh_file(const JsonField& file_field, const LoadContext& ctx) {
  const std::string name = file_field.non_empty_string();
  const fs::path path = fs::path(name).is_absolute() ? fs::path(name) : ctx.json_dir / name;
  std::error_code ec;
  if (fs::is_directory(path, ec)) file_field.fail("cannot open '" + name + "' (it is a directory)");
  // Devices and pipes (/dev/zero, a FIFO) would be read without end.
  if (fs::exists(path, ec) && !fs::is_regular_file(path, ec)) file_field.fail("'" + name + "' is not a regular file");
  std::ifstream probe(path);
  if (!probe) file_field.fail("cannot open '" + name + "' (" + std::strerror(errno) + ")");
  return path.string();
}

// Where one usemtl name of a mesh points: a JSON material (by name) or an MTL material.
struct UsemtlTarget {
  const MaterialDesc* json = nullptr;
  const MtlMaterial* mtl = nullptr;
};

UsemtlTarget resolve_usemtl(const ObjMesh& mesh, const ObjUsemtl& usemtl, const std::string& obj_path,
                            const LoadContext& ctx) {
  UsemtlTarget target;
  auto json_it = ctx.json_materials.find(usemtl.name);
  if (json_it != ctx.json_materials.end()) {
    target.json = &json_it->second;
    return target;
  }
  auto mtl_it = mesh.mtl_materials.find(usemtl.name);
  if (mtl_it != mesh.mtl_materials.end()) {
    target.mtl = &mtl_it->second;
    return target;
  }
  throw_input_error(
      file_line(obj_path, usemtl.first_line),
      "usemtl '" + usemtl.name + "': no such material in the scene's materials or the OBJ's MTL files");
}

void append_mesh(const JsonField& field, LoadContext& ctx, MaterialTable& table, Scene& scene) {
  field.expect_object_with_keys({"file", "material"});
  const std::string obj_path = check_mesh_file(field.member("file"), ctx);

  // "material" replaces every face's material, so the OBJ's own (and its MTL files) are unused.
  std::string override_name;
  if (field.has("material")) {
    const JsonField material = field.member("material");
    override_name = material.non_empty_string();
    if (!ctx.json_materials.count(override_name)) {
      material.fail("unknown material '" + override_name + "' (not defined under materials)");
    }
  }

  const ObjMesh mesh = load_obj_mesh(obj_path, override_name.empty());

  std::vector<UsemtlTarget> targets;
  if (override_name.empty()) {
    for (const ObjUsemtl& usemtl : mesh.usemtl_names)
      targets.push_back(resolve_usemtl(mesh, usemtl, obj_path, ctx));
  }

  // Materials enter the table on first use, so unused ones do not reach the renderer.
  std::vector<int64_t> slot_material(mesh.usemtl_names.size() + 1, -1);  // slot 0: no usemtl
  auto material_for = [&](int32_t usemtl) -> uint32_t {
    int64_t& cached = slot_material[static_cast<size_t>(usemtl + 1)];
    if (cached >= 0) return static_cast<uint32_t>(cached);
    if (!override_name.empty()) {
      cached = table.index_of("json:" + override_name, [&] { return ctx.json_materials.at(override_name); });
    } else if (usemtl < 0) {
      // Faces without usemtl take "default": a JSON material of that name, else built-in grey.
      auto json_default = ctx.json_materials.find("default");
      if (json_default != ctx.json_materials.end()) {
        cached = table.index_of("json:default", [&] { return json_default->second; });
      } else {
        cached = table.index_of("builtin:default", [] {
          MaterialDesc grey;
          grey.name = "default";
          return grey;
        });
      }
    } else if (const MaterialDesc* json = targets[static_cast<size_t>(usemtl)].json) {
      cached = table.index_of("json:" + json->name, [&] { return *json; });
    } else {
      const MtlMaterial* mtl = targets[static_cast<size_t>(usemtl)].mtl;
      cached = table.index_of("mtl:" + mtl->mtl_file + ":" + mtl->name, [&] {
        for (const std::string& statement : mtl->ignored) ctx.mtl_ignored[mtl->mtl_file][statement].push_back(mtl->name);
        return material_from_mtl(*mtl, &ctx.report->warnings, ctx.textures);
      });
    }
    return static_cast<uint32_t>(cached);
  };

  const size_t base = scene.positions.size();
  if (base + mesh.positions.size() > UINT32_MAX)
    field.fail("too many vertices in the scene for 32-bit indices");
  const JsonField file_field = field.member("file");
  for (const Float3& p : mesh.positions)
    scene.positions.push_back(position_in_metres(p, ctx.meters_per_unit, file_field));
  // Texture coordinates line up with the triangles: earlier meshes' come first.
  scene.triangle_uvs.resize(3 * scene.triangle_count());
  scene.triangle_uvs.insert(scene.triangle_uvs.end(), mesh.triangle_uvs.begin(), mesh.triangle_uvs.end());
  for (uint32_t index : mesh.indices) scene.indices.push_back(static_cast<uint32_t>(base + index));
  for (int32_t usemtl : mesh.triangle_usemtl) scene.triangle_material.push_back(material_for(usemtl));
  // Each meshes[] entry is one object of the object_id layer, named by its OBJ file.
  scene.triangle_object.resize(scene.triangle_material.size(), uint32_t(scene.object_names.size()));
  scene.object_names.push_back(std::filesystem::path(obj_path).filename().string());

  ctx.report->warnings.insert(ctx.report->warnings.end(), mesh.warnings.begin(), mesh.warnings.end());
  if (mesh.degenerate_triangles_dropped > 0) {
    ctx.report->degenerate_triangles_dropped += mesh.degenerate_triangles_dropped;
    ctx.report->warnings.push_back(single_line(obj_path + ": " +
                                               std::to_string(mesh.degenerate_triangles_dropped) +
                                               " degenerate triangles dropped"));
  }
}

bool has_extension(const std::string& path, const std::string& extension) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == extension;
}

}  // namespace

Scene load_scene_file(const std::string& path, SceneLoadReport* report, const EnvironmentDesc* environment) {
  if (has_extension(path, ".gltf") || has_extension(path, ".glb")) return load_gltf_scene(path, report, environment);
  SceneLoadReport local_report;
  LoadContext ctx;
  ctx.json_dir = fs::path(path).parent_path();
  ctx.report = report ? report : &local_report;
  *ctx.report = SceneLoadReport{};  // the report describes this load only

  const nlohmann::json document = parse_json_file_strict(path);
  const JsonField root(path, document, "");
  if (!document.is_object())
    root.fail("expected a JSON object at the top level, got " + describe_json_value(document));

  // Identify the format before anything else, so a newer file gets "unsupported version" rather
  // than complaints about keys this build does not know.
  const JsonField format = root.member("format");
  if (format.non_empty_string() != kFormatName) {
    format.fail(std::string("expected \"") + kFormatName + "\", got \"" + format.value().get<std::string>() +
                "\"");
  }
  const JsonField version = root.member("version");
  const long long version_number = version.integer_in(0, 1000000);
  if (version_number != kSceneFormatVersion) {
    version.fail("unsupported version " + std::to_string(version_number) + " (this build reads version " +
                 std::to_string(kSceneFormatVersion) + ")");
  }
  root.expect_object_with_keys(
      {"format", "version", "name", "meters_per_unit", "meshes", "materials", "lights", "environment", "camera",
       "animation"});

  Scene scene;
  SceneTextures textures(&scene);
  ctx.textures = &textures;
  scene.source = path;
  scene.name = root.has("name") ? root.member("name").non_empty_string() : fs::path(path).stem().string();
  if (root.has("meters_per_unit")) {
    const JsonField mpu = root.member("meters_per_unit");
    ctx.meters_per_unit = mpu.finite_number();
    if (!(ctx.meters_per_unit > 0)) mpu.fail("must be > 0, got " + describe_json_value(mpu.value()));
    // Nanometres to gigametres; beyond that every position rounds to 0 or overflows in floats.
    if (ctx.meters_per_unit < 1e-9 || ctx.meters_per_unit > 1e9)
      mpu.fail("must be from 1e-9 to 1e9, got " + describe_json_value(mpu.value()));
  }
  ctx.json_materials = read_json_materials(root);

  const JsonField meshes = root.member("meshes");
  const size_t mesh_count = meshes.expect_array();
  MaterialTable table(&scene.materials);
  for (size_t i = 0; i < mesh_count; ++i) append_mesh(meshes.element(i), ctx, table, scene);
  warn_ignored_mtl_statements(ctx);
  if (!scene.has_textures()) scene.triangle_uvs = {};  // nothing samples them
  if (scene.triangle_count() == 0) {
    meshes.fail("the scene has no triangles (" + std::to_string(mesh_count) + " meshes, " +
                std::to_string(ctx.report->degenerate_triangles_dropped) + " degenerate triangles dropped)");
  }

  scene.lights = read_lights(root, ctx.meters_per_unit);
  if (root.has("environment")) scene.environment = read_environment_json(root.member("environment"), ctx.json_dir);
  if (environment) scene.environment = *environment;
  // Nothing to render without light: say so now, before anything is built or traced.
  if (!scene.has_light()) {
    throw_input_error(root.file() + ": lights",
                      "no light: no light with power above zero under lights and no emitting material "
                      "(materials' emission, MTL Ke) on any triangle, and no environment with radiance above zero");
  }
  scene.camera = read_camera(root, ctx.meters_per_unit);
  if (root.has("animation")) read_animation_json(root.member("animation"), ctx.meters_per_unit, &scene);
  return scene;
}

}  // namespace pm

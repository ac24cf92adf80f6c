// Owns loading a pmrender JSON scene (format version 1, docs/scene-format.md) into pm::Scene:
// the top-level keys, JSON materials, meshes (through obj_mesh), lights, the environment
// (through environment_json), camera, unit conversion
// to metres and the usemtl name -> material resolution (JSON materials first, then MTL); the
// optional "animation" object goes through animation_json. Files ending in .gltf or .glb go to
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
#include "scene_io/load_error.h"
#include "scene_io/obj_mesh.h"
#include "scene_io/texture_files.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

const char kFormatName[] = "pmrender-scene";
const int kMaxResolution = 16384;
const char* const kChannelNames[3] = {"red", "green", "blue"};
// Values are stored as floats, so 0.6 + 0.4 sums to 1.00000003; that must still count as 1.
constexpr double kReflectanceSumTolerance = 1e-6;

float component(const Float3& v, int i) { return i == 0 ? v.x : (i == 1 ? v.y : v.z); }

// Converts a position from scene units to metres; fails on the field beyond what single-precision
// geometry can render (the same bound as OBJ vertex coordinates, now in metres).
Float3 to_metres(const Float3& units, double meters_per_unit, const JsonField& field) {
  const double m[3] = {units.x * meters_per_unit, units.y * meters_per_unit, units.z * meters_per_unit};
  for (double v : m) {
    if (!(std::fabs(v) <= kMaxObjCoordinate))
      field.fail("a position is " + describe_json_value(v) + " m from the origin once converted to metres; at most 1e15 m renders");
  }
  return Float3{static_cast<float>(m[0]), static_cast<float>(m[1]), static_cast<float>(m[2])};
}

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
    scene.positions.push_back(to_metres(p, ctx.meters_per_unit, file_field));
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

// --- lights and camera -----------------------------------------------------------------------

float length(const Float3& v) { return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }

// A spot light's cone angle in degrees, as radians: in [0, 90] degrees.
float read_cone_angle(const JsonField& field) {
  const double degrees = field.finite_number();
  if (!(degrees >= 0 && degrees <= 90)) field.fail("must be in [0, 90] degrees, got " + describe_json_value(field.value()));
  return static_cast<float>(degrees * M_PI / 180.0);
}

LightDesc read_light(const JsonField& field, size_t index, double meters_per_unit) {
  field.expect_object_with_keys({"name", "type", "position", "power", "direction", "inner_cone_angle", "outer_cone_angle"});
  LightDesc light;
  light.name = field.has("name") ? field.member("name").non_empty_string() : "light" + std::to_string(index);
  if (field.has("type")) {
    const JsonField type = field.member("type");
    const std::string name = type.non_empty_string();
    if (name == "spot") light.type = LightType::spot;
    else if (name != "point") type.fail("expected \"point\" or \"spot\", got '" + name + "'");
  }
  const JsonField position = field.member("position");
  light.position = to_metres(position.float3(), meters_per_unit, position);
  const JsonField power = field.member("power");
  light.power = power.float3();
  for (size_t c = 0; c < 3; ++c)
    if (component(light.power, static_cast<int>(c)) < 0)
      power.element(c).fail("must be >= 0 W, got " + describe_json_value(power.element(c).value()));
  if (light.type != LightType::spot) {
    for (const char* key : {"direction", "inner_cone_angle", "outer_cone_angle"})
      if (field.has(key)) field.member(key).fail("only a spot light has this key (\"type\": \"spot\")");
    return light;
  }
  const JsonField direction = field.member("direction");
  light.direction = direction.float3();
  if (!(length(light.direction) > 0)) direction.fail("must not be zero");
  light.outer_cone = field.has("outer_cone_angle") ? read_cone_angle(field.member("outer_cone_angle")) : float(M_PI / 4);
  light.inner_cone = field.has("inner_cone_angle") ? read_cone_angle(field.member("inner_cone_angle")) : 0.0f;
  if (!(light.inner_cone < light.outer_cone)) {
    const JsonField where = field.has("inner_cone_angle") ? field.member("inner_cone_angle") : field.member("outer_cone_angle");
    where.fail("the inner cone angle must be below the outer one (" + std::to_string(light.inner_cone * 180.0 / M_PI) +
               " >= " + std::to_string(light.outer_cone * 180.0 / M_PI) + " degrees)");
  }
  return light;
}

// Lights are optional: a scene may be lit by emitting materials alone; load_scene_file checks
// that some light, of either kind, is there.
std::vector<LightDesc> read_lights(const JsonField& root, double meters_per_unit) {
  std::vector<LightDesc> result;
  if (!root.has("lights")) return result;
  const JsonField lights = root.member("lights");
  const size_t count = lights.expect_array();
  for (size_t i = 0; i < count; ++i) result.push_back(read_light(lights.element(i), i, meters_per_unit));
  return result;
}


CameraDesc read_camera(const JsonField& root, double meters_per_unit) {
  const JsonField field = root.member("camera");
  field.expect_object_with_keys({"position", "look_at", "up", "vertical_fov", "resolution"});
  CameraDesc camera;  // defaults: up +y, 45 degrees, 512 x 512
  const JsonField position = field.member("position");
  camera.position = to_metres(position.float3(), meters_per_unit, position);
  const JsonField look_at = field.member("look_at");
  camera.look_at = to_metres(look_at.float3(), meters_per_unit, look_at);
  const Float3 view{camera.look_at.x - camera.position.x, camera.look_at.y - camera.position.y,
                    camera.look_at.z - camera.position.z};
  const float view_length = length(view);
  if (!(view_length > 0)) look_at.fail("equals camera.position (no view direction)");

  // up is a direction, so it is not scaled. It must leave a "right" axis: |view x up| is
  // |sin| of their angle times both lengths, and near zero means (anti)parallel.
  const bool up_given = field.has("up");
  if (up_given) camera.up = field.member("up").float3();
  const float up_length = length(camera.up);
  const Float3 cross{view.y * camera.up.z - view.z * camera.up.y, view.z * camera.up.x - view.x * camera.up.z,
                     view.x * camera.up.y - view.y * camera.up.x};
  if (up_given && !(up_length > 0)) field.member("up").fail("must not be the zero vector");
  if (!(length(cross) > 1e-6f * view_length * up_length)) {
    if (up_given) field.member("up").fail("is parallel to the view direction (look_at - position)");
    field.fail("the default up [0, 1, 0] is parallel to the view direction; set camera.up");
  }

  if (field.has("vertical_fov")) {
    const JsonField fov = field.member("vertical_fov");
    const double degrees = fov.finite_number();
    if (!(degrees > 0 && degrees < 180))
      fov.fail("must be in (0, 180) degrees, got " + describe_json_value(fov.value()));
    camera.vertical_fov_degrees = static_cast<float>(degrees);
  }
  if (field.has("resolution")) {
    const JsonField resolution = field.member("resolution");
    resolution.expect_array(2);
    camera.width = static_cast<int>(resolution.element(0).integer_in(1, kMaxResolution));
    camera.height = static_cast<int>(resolution.element(1).integer_in(1, kMaxResolution));
  }
  return camera;
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

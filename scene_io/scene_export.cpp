// Writing a Scene as JSON + per-material OBJ files (scene_export.h).
#include "scene_io/scene_export.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <vector>

#include "render/atomic_file.h"
#include "render/scene_frame.h"

namespace pm {

namespace {

using Json = nlohmann::ordered_json;

// Nine significant digits: a float survives the round trip through text exactly.
std::string number(float v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.9g", double(v));
  return text;
}

Json vec(Float3 v) { return Json::array({Json::parse(number(v.x)), Json::parse(number(v.y)), Json::parse(number(v.z))}); }

// The OBJ of one material's triangles: only the vertices they use, renumbered from 1.
std::string material_obj(const Scene& scene, uint32_t material) {
  std::vector<int64_t> renumbered(scene.positions.size(), -1);
  std::ostringstream vertices, faces;
  int64_t next = 1;
  for (size_t t = 0; t < scene.triangle_count(); ++t) {
    if (scene.triangle_material[t] != material) continue;
    faces << "f";
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = scene.indices[3 * t + c];
      if (renumbered[v] < 0) {
        renumbered[v] = next++;
        const Float3& p = scene.positions[v];
        vertices << "v " << number(p.x) << " " << number(p.y) << " " << number(p.z) << "\n";
      }
      faces << " " << renumbered[v];
    }
    faces << "\n";
  }
  return "# " + scene.materials[material].name + ", metres (pmrender export-scene)\n" + vertices.str() + faces.str();
}

}  // namespace

void export_scene(const Scene& scene, int frame, const std::string& json_path) {
  namespace fs = std::filesystem;
  const fs::path json(json_path);
  const std::string stem = json.stem().string();
  std::vector<bool> used(scene.materials.size(), false);
  for (uint32_t m : scene.triangle_material) used[m] = true;

  Json meshes = Json::array(), materials = Json::object();
  std::set<std::string> names;
  for (uint32_t m = 0; m < scene.materials.size(); ++m) {
    if (!used[m]) continue;
    const MaterialDesc& desc = scene.materials[m];
    std::string name = desc.name.empty() ? "material" : desc.name;
    for (int k = 2; names.count(name); ++k) name = desc.name + "-" + std::to_string(k);
    names.insert(name);
    const std::string file = stem + "." + std::to_string(m) + ".obj";
    write_file_atomically((json.parent_path() / file).string(), material_obj(scene, m));
    meshes.push_back({{"file", file}, {"material", name}});
    materials[name] = {{"diffuse", vec(desc.diffuse)},
                       {"glossy", vec(desc.glossy)},
                       {"exponent", Json::parse(number(desc.glossy_exponent))},
                       {"mirror", vec(desc.mirror)}};
    if (desc.emits()) materials[name]["emission"] = vec(desc.emission);
  }
  Json lights = Json::array();
  for (const LightDesc& l : lights_at_frame(scene, frame)) {
    Json light = {{"name", l.name.empty() ? "light" + std::to_string(lights.size()) : l.name},
                  {"position", vec(l.position)},
                  {"power", vec(l.power)}};
    if (l.type == LightType::spot) {
      light["type"] = "spot";
      light["direction"] = vec(l.direction);
      light["inner_cone_angle"] = Json::parse(number(float(l.inner_cone * 180.0 / M_PI)));
      light["outer_cone_angle"] = Json::parse(number(float(l.outer_cone * 180.0 / M_PI)));
    }
    lights.push_back(light);
  }
  const CameraDesc camera = camera_at_frame(scene, frame);
  Json j;
  j["format"] = "pmrender-scene";
  j["version"] = 1;
  j["name"] = scene.name;
  j["meshes"] = meshes;
  j["materials"] = materials;
  j["lights"] = lights;
  // The environment as the scene file said it: a map by its resolved (absolute) path, so the
  // exported scene finds it from any folder.
  const EnvironmentDesc& env = scene.environment;
  if (env.type == EnvironmentType::constant) {
    j["environment"] = {{"radiance", vec(env.radiance)}};
  } else if (env.type == EnvironmentType::map) {
    j["environment"] = {{"map", std::filesystem::absolute(env.map_file).string()},
                        {"scale", Json::parse(number(env.scale))},
                        {"rotation_deg", Json::parse(number(env.rotation_degrees))}};
  }
  j["camera"] = {{"position", vec(camera.position)},
                 {"look_at", vec(camera.look_at)},
                 {"up", vec(camera.up)},
                 {"vertical_fov", Json::parse(number(camera.vertical_fov_degrees))},
                 {"resolution", {camera.width, camera.height}}};
  write_file_atomically(json_path, j.dump(2) + "\n");
}

}  // namespace pm

// libFuzzer target for the scene parser: load_scene_file on a JSON scene, an OBJ mesh and an MTL
// file written to a private temporary folder. Input layout: JSON, then optionally a NUL byte and
// the OBJ text ("mesh.obj"), then optionally a NUL byte and the MTL text ("mesh.mtl").
// The contract checked: every problem is a pm::InputError (anything else escapes and crashes
// the fuzzer), and a scene that loads is consistent (indices, materials, finite values).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "render/errors.h"
#include "scene_io/scene_file.h"

namespace {

// A private folder for this process's input files, removed at exit.
char g_folder[4096];

std::string folder() {
  if (!g_folder[0]) {
    const std::string pattern = (std::filesystem::temp_directory_path() / "pm_fuzz_scene_XXXXXX").string();
    if (pattern.size() >= sizeof(g_folder)) std::abort();
    pattern.copy(g_folder, pattern.size());
    if (!mkdtemp(g_folder)) std::abort();
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(g_folder, ec);
    });
  }
  return g_folder;
}

void write(const std::string& name, const uint8_t* data, size_t size) {
  std::ofstream out(folder() + "/" + name, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
}

void require(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "scene fuzzer: loaded scene violates: %s\n", what);
    __builtin_trap();
  }
}

bool finite(const pm::Float3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void check(const pm::Scene& s) {
  require(s.triangle_count() > 0, "at least one triangle");
  require(s.indices.size() % 3 == 0, "three indices per triangle");
  require(s.triangle_material.size() == s.triangle_count(), "one material per triangle");
  for (uint32_t i : s.indices) require(i < s.positions.size(), "indices in range");
  for (uint32_t m : s.triangle_material) require(m < s.materials.size(), "material indices in range");
  for (const pm::Float3& p : s.positions) require(finite(p), "finite positions");
  for (const pm::MaterialDesc& m : s.materials) {
    const float sum[3] = {m.diffuse.x + m.glossy.x + m.mirror.x, m.diffuse.y + m.glossy.y + m.mirror.y,
                          m.diffuse.z + m.glossy.z + m.mirror.z};
    for (float v : sum) require(v >= 0 && v <= 1.0f + 1e-5f, "reflectance sums in [0, 1]");
    require(std::isfinite(m.glossy_exponent) && m.glossy_exponent >= 0, "finite exponent");
  }
  require(!s.lights.empty(), "a light");
  for (const pm::LightDesc& l : s.lights) require(finite(l.position) && finite(l.power), "finite lights");
  require(s.camera.width >= 1 && s.camera.width <= 16384 && s.camera.height >= 1 && s.camera.height <= 16384,
          "resolution in range");
  require(s.camera.vertical_fov_degrees > 0 && s.camera.vertical_fov_degrees < 180, "field of view in range");
  require(finite(s.camera.position) && finite(s.camera.look_at) && finite(s.camera.up), "finite camera");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const uint8_t* end = data + size;
  const uint8_t* json_end = std::find(data, end, uint8_t(0));
  const uint8_t* obj = json_end == end ? end : json_end + 1;
  const uint8_t* obj_end = std::find(obj, end, uint8_t(0));
  const uint8_t* mtl = obj_end == end ? end : obj_end + 1;
  write("scene.json", data, size_t(json_end - data));
  write("mesh.obj", obj, size_t(obj_end - obj));
  write("mesh.mtl", mtl, size_t(end - mtl));
  try {
    pm::SceneLoadReport report;
    check(pm::load_scene_file(folder() + "/scene.json", &report));
  } catch (const pm::InputError&) {
  }
  return 0;
}

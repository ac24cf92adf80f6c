// What the file-based fuzz targets share: a private temporary folder for their input files, the
// crash-on-violation helper, and the consistency contract of a scene that loaded.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "render/scene.h"

namespace pm::fuzz {

// A private folder for this process's input files, removed at exit.
inline std::string folder() {
  static char path[4096];
  if (!path[0]) {
    const std::string pattern = (std::filesystem::temp_directory_path() / "pm_fuzz_XXXXXX").string();
    if (pattern.size() >= sizeof(path)) std::abort();
    pattern.copy(path, pattern.size());
    if (!mkdtemp(path)) std::abort();
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    });
  }
  return path;
}

// Writes folder()/name and returns its path.
inline std::string write(const std::string& name, const uint8_t* data, size_t size) {
  const std::string path = folder() + "/" + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path;
}

inline void require(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz target: contract violated: %s\n", what);
    __builtin_trap();
  }
}

inline bool finite(const Float3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// A scene that loaded is consistent: indices and materials in range, finite values, a light, a
// camera in range.
inline void check_scene(const Scene& s) {
  require(s.triangle_count() > 0, "at least one triangle");
  require(s.indices.size() % 3 == 0, "three indices per triangle");
  require(s.triangle_material.size() == s.triangle_count(), "one material per triangle");
  for (uint32_t i : s.indices) require(i < s.positions.size(), "indices in range");
  for (uint32_t m : s.triangle_material) require(m < s.materials.size(), "material indices in range");
  for (const Float3& p : s.positions) require(finite(p), "finite positions");
  for (const MaterialDesc& m : s.materials) {
    const float sum[3] = {m.diffuse.x + m.glossy.x + m.mirror.x, m.diffuse.y + m.glossy.y + m.mirror.y,
                          m.diffuse.z + m.glossy.z + m.mirror.z};
    for (float v : sum) require(v >= 0 && v <= 1.0f + 1e-5f, "reflectance sums in [0, 1]");
    require(std::isfinite(m.glossy_exponent) && m.glossy_exponent >= 0, "finite exponent");
  }
  for (const MaterialDesc& m : s.materials) {
    for (int t : {m.base_color_texture, m.alpha_texture}) require(t < int(s.textures.size()), "texture indices in range");
    require(m.alpha_channel >= 0 && m.alpha_channel <= 3 && std::isfinite(m.alpha_cutoff), "alpha test defined");
  }
  for (const TextureRef& t : s.textures) require(t.image < s.images.size(), "image indices in range");
  for (const TextureImage& i : s.images)
    require(i.width >= 1 && i.height >= 1 && i.rgba.size() == 4 * size_t(i.width) * size_t(i.height), "texels match sizes");
  require(s.triangle_uvs.size() <= 3 * s.triangle_count(), "at most three texture coordinates per triangle");
  for (const Float2& uv : s.triangle_uvs) require(std::isfinite(uv.u) && std::isfinite(uv.v), "finite texture coordinates");
  require(!s.lights.empty(), "a light");
  for (const LightDesc& l : s.lights) require(finite(l.position) && finite(l.power), "finite lights");
  require(s.camera.width >= 1 && s.camera.width <= 16384 && s.camera.height >= 1 && s.camera.height <= 16384,
          "resolution in range");
  require(s.camera.vertical_fov_degrees > 0 && s.camera.vertical_fov_degrees < 180, "field of view in range");
  require(finite(s.camera.position) && finite(s.camera.look_at) && finite(s.camera.up), "finite camera");
}

}  // namespace pm::fuzz

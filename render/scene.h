// The in-memory scene every loader produces and the renderer consumes: triangles in metres,
// modified-Phong materials, isotropic point lights and a pinhole camera. Format-independent:
// scene_io/ fills it from JSON+OBJ (later glTF); nothing here knows about files.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace pm {

struct Float3 {
  float x = 0, y = 0, z = 0;
};

// Modified Phong (Lafortune & Willems 1994) plus a perfect mirror; reflectances in [0,1] per
// channel with diffuse + glossy + mirror <= 1.
struct MaterialDesc {
  std::string name;
  Float3 diffuse{0.8f, 0.8f, 0.8f};
  Float3 glossy{0, 0, 0};
  float glossy_exponent = 1.0f;
  Float3 mirror{0, 0, 0};
};

// Isotropic point light. position in metres, power in watts per RGB channel.
struct LightDesc {
  std::string name;
  Float3 position;
  Float3 power;
};

// Pinhole camera. Positions in metres, vertical field of view in degrees.
struct CameraDesc {
  Float3 position{0, 0, 0};
  Float3 look_at{0, 0, 1};
  Float3 up{0, 1, 0};
  float vertical_fov_degrees = 45.0f;
  int width = 512;
  int height = 512;
};

struct Scene {
  std::string name;                       // used in default output names and EXR headers
  std::string source;                     // the file it came from, or "builtin:cornell-box"
  std::vector<Float3> positions;          // vertex positions, metres
  std::vector<uint32_t> indices;          // three vertex indices per triangle
  std::vector<uint32_t> triangle_material;  // one material index per triangle
  std::vector<MaterialDesc> materials;
  std::vector<LightDesc> lights;
  CameraDesc camera;

  size_t triangle_count() const { return indices.size() / 3; }
};

}  // namespace pm

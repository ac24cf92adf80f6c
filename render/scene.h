// The in-memory scene every loader produces and the renderer consumes: triangles in metres,
// modified-Phong materials with their textures and emission (area lights), point and spot
// lights and a pinhole camera.
// Format-independent: scene_io/ fills it from JSON+OBJ or glTF; nothing here knows about files. Cameras and lights
// may carry keyframe tracks (SceneAnimation); a scene without them is one still frame.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "animations/keyframe_track.h"

namespace pm {

struct Float3 {
  float x = 0, y = 0, z = 0;
};

// Texture coordinates, glTF's convention: (0, 0) is the top-left corner of an image, v grows
// downwards (the OBJ loader flips vt's v).
struct Float2 {
  float u = 0, v = 0;
};

// A decoded image: width x height texels, 4 bytes each (RGBA), rows top first. Colour is
// sRGB-encoded as stored in the file; alpha (255 where the file has none) is linear.
struct TextureImage {
  std::string source;  // the file (or "file.gltf: images[2]") it was decoded from, for messages
  int width = 0, height = 0;
  int file_channels = 0;  // channels the file holds (1 grey, 2 grey + alpha, 3 RGB, 4 RGBA)
  std::vector<uint8_t> rgba;
};

enum class TextureWrap : uint8_t { repeat, clamp_to_edge, mirrored_repeat };

// An image with the wrap modes it is sampled with (glTF: a texture and its sampler). Lookups are
// always bilinear (kernels/common/texture.h).
struct TextureRef {
  uint32_t image = 0;  // index into Scene::images
  TextureWrap wrap_u = TextureWrap::repeat, wrap_v = TextureWrap::repeat;
};

// Modified Phong (Lafortune & Willems 1994) plus a perfect mirror; reflectances in [0,1] per
// channel with diffuse + glossy + mirror <= 1.
struct MaterialDesc {
  std::string name;
  Float3 diffuse{0.8f, 0.8f, 0.8f};
  Float3 glossy{0, 0, 0};
  float glossy_exponent = 1.0f;
  Float3 mirror{0, 0, 0};
  // Base-colour texture (index into Scene::textures, -1: none): its linear colour multiplies
  // diffuse, and with texture_tints_specular (glTF's base colour) glossy and mirror as well.
  int base_color_texture = -1;
  bool texture_tints_specular = false;
  // Alpha mask (glTF alphaMode MASK, MTL map_d): a point is there where alpha_factor * the
  // alpha_channel (0 red .. 3 alpha) of alpha_texture (1 without one, -1) >= alpha_cutoff;
  // elsewhere every ray passes through it.
  bool alpha_mask = false;
  int alpha_texture = -1;
  int alpha_channel = 3;
  float alpha_factor = 1.0f;
  float alpha_cutoff = 0.5f;
  // Emitted radiance (W sr^-1 m^-2 per channel) of a Lambertian emitter, from each triangle's
  // front face (the side of (p1 - p0) x (p2 - p0)); zero: not a light.
  Float3 emission{0, 0, 0};
  bool emits() const { return emission.x > 0 || emission.y > 0 || emission.z > 0; }
  bool has_mirror() const { return mirror.x > 0 || mirror.y > 0 || mirror.z > 0; }
};

enum class LightType : uint8_t { point, spot };

// A point light (isotropic) or a spot light (a point light restricted to a cone about
// `direction`, with the glTF KHR_lights_punctual falloff between the inner and the outer cone
// angle; kernels/common/spot_light.h). position in metres; power in watts per RGB channel: a
// point light's radiant flux, and for a spot the flux of the point light with the same on-axis
// intensity (intensity = power / (4 pi) W/sr on the axis); the spot emits
// power * spot_emitted_fraction().
struct LightDesc {
  std::string name;
  Float3 position;
  Float3 power;
  LightType type = LightType::point;
  Float3 direction{0, 0, -1};  // spot: the axis, any length above zero
  float inner_cone = 0.0f;     // spot: radians from the axis, 0 <= inner < outer
  float outer_cone = 0.785398163f;  // spot: radians from the axis, outer <= pi / 2 (glTF's default pi / 4)
};

// The share of `power` a light emits: 1 for a point light; for a spot
// ((1 - cos inner) + (cos inner - cos outer) / 3) / 2 (spot_light.h).
double light_emitted_fraction(const LightDesc& light);

// Light arriving from infinitely far away (kernels/common/environment_light.h): none, one
// radiance from every direction, or an equirectangular (lat-long) map whose top row is the
// zenith (+y), turned about +y by rotation_degrees (kernels/common/environment_map.h has the
// parameterisation). Radiance in W sr^-1 m^-2 per channel. Static: animations do not touch it.
enum class EnvironmentType : uint8_t { none, constant, map };

struct EnvironmentDesc {
  EnvironmentType type = EnvironmentType::none;
  Float3 radiance{0, 0, 0};    // constant: the radiance from every direction
  std::string map_file;        // map: the OpenEXR file it was read from, as resolved by the loader
  int width = 0, height = 0;   // map: texels
  std::vector<float> texels;   // map: rgb radiance per texel, top row first, scale already applied
  float scale = 1.0f;          // map: the factor applied to the file's values (kept for export)
  float rotation_degrees = 0;  // map: the turn about +y
  // True when some direction sends light (radiance or a texel above zero in some channel).
  bool emits() const;
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

// Keyframe tracks of the camera; an empty track leaves that value at Scene::camera's.
// Positions in metres, up a direction, vertical_fov in degrees.
struct CameraAnimation {
  Vec3Track position, look_at, up;
  ScalarTrack vertical_fov;
  bool empty() const { return position.empty() && look_at.empty() && up.empty() && vertical_fov.empty(); }
};

// Keyframe tracks of one point or spot light; an empty track leaves that value at the
// LightDesc's. position in metres, power in watts per RGB channel (the light's colour is its RGB
// power), direction (spot lights) any non-zero vector.
struct LightAnimation {
  Vec3Track position, power, direction;
  bool empty() const { return position.empty() && power.empty() && direction.empty(); }
};

// A sequence: frame f shows the scene at time f / frame_rate seconds (render/
// scene_frame.h evaluates it). Geometry and materials never move.
struct SceneAnimation {
  // false: a still scene, the default. It renders as frame 0, any frame number shows the same
  // scene, and each frame number draws its own random numbers (as `--frame N` always did).
  // true: a sequence of frames first_frame..last_frame (the scene file asked for one).
  bool enabled = false;
  double frame_rate = 24.0;  // frames per second, > 0
  int first_frame = 0;
  int last_frame = 0;
  CameraAnimation camera;
  std::vector<LightAnimation> lights;  // empty, or one per Scene::lights entry, in that order
};

struct Scene {
  std::string name;                       // used in default output names and EXR headers
  std::string source;                     // the file it came from, or "builtin:cornell-box"
  std::vector<Float3> positions;          // vertex positions, metres
  std::vector<uint32_t> indices;          // three vertex indices per triangle
  std::vector<uint32_t> triangle_material;  // one material index per triangle
  // The object each triangle belongs to (a JSON mesh entry, a glTF node, a Cornell box wall or
  // block), for the object_id layer. Triangles past its end (all of them when it is empty, or
  // those a program added to a loaded scene) form one more object: scene_object_of.
  std::vector<uint32_t> triangle_object;
  std::vector<std::string> object_names;  // by object index, as loaded (may be empty)
  std::vector<MaterialDesc> materials;
  // Textures: the decoded images, the (image, wrap) pairs materials refer to, and three texture
  // coordinates per triangle (in triangle order). Triangles past triangle_uvs' end (all of them
  // when it is empty) have (0, 0) at every corner.
  std::vector<TextureImage> images;
  std::vector<TextureRef> textures;
  std::vector<Float2> triangle_uvs;
  std::vector<LightDesc> lights;
  EnvironmentDesc environment;  // none unless the scene asks for one
  CameraDesc camera;            // the camera where no camera track says otherwise
  SceneAnimation animation;     // disabled by default: one still frame

  size_t triangle_count() const { return indices.size() / 3; }
  // True when some material has a base-colour texture or an alpha mask: the renderer then
  // uploads texture coordinates and texels.
  bool has_textures() const {
    for (const MaterialDesc& m : materials)
      if (m.base_color_texture >= 0 || m.alpha_mask) return true;
    return false;
  }
  // True when some material reflects as a perfect mirror: eye rays may continue past a hit.
  bool has_mirrors() const {
    for (const MaterialDesc& m : materials)
      if (m.has_mirror()) return true;
    return false;
  }
  // True when some triangle's material emits: the scene has area lights.
  bool has_emitters() const;
  // True when some point or spot light has power above zero, the scene has emitters or its
  // environment emits: there is light to render (loaders refuse scenes without).
  bool has_light() const;
};

// The object of triangle t: triangle_object[t], or past its end the object after the named ones
// (object 0 of a scene without objects).
inline uint32_t scene_object_of(const Scene& scene, size_t t) {
  return t < scene.triangle_object.size() ? scene.triangle_object[t] : uint32_t(scene.object_names.size());
}

}  // namespace pm

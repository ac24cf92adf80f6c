// Owns the data of the built-in Cornell box (see cornell_box.h): Cornell's measured geometry in
// millimetres, their measured reflectances reduced to RGB, the camera of the reference images,
// and a point light standing in for the area light.
#include "scene_io/cornell_box.h"

#include <cstdint>

namespace pm {
namespace {

constexpr float kMetresPerMillimetre = 0.001f;

struct Millimetres {
  float x, y, z;
};

Float3 to_metres(const Millimetres& p) {
  return Float3{p.x * kMetresPerMillimetre, p.y * kMetresPerMillimetre, p.z * kMetresPerMillimetre};
}

// Walls as published, each corner order already giving a normal that points into the room.
// The red wall is at x ~ 550 and the green wall at x = 0: seen from the camera (looking down +z
// with +y up, right-handed) +x is on the left, as in the reference photographs.
const Millimetres kFloor[4] = {{552.8f, 0, 0}, {0, 0, 0}, {0, 0, 559.2f}, {549.6f, 0, 559.2f}};
const Millimetres kCeiling[4] = {
    {556, 548.8f, 0}, {556, 548.8f, 559.2f}, {0, 548.8f, 559.2f}, {0, 548.8f, 0}};
const Millimetres kBackWall[4] = {
    {549.6f, 0, 559.2f}, {0, 0, 559.2f}, {0, 548.8f, 559.2f}, {556, 548.8f, 559.2f}};
const Millimetres kGreenWall[4] = {{0, 0, 559.2f}, {0, 0, 0}, {0, 548.8f, 0}, {0, 548.8f, 559.2f}};
const Millimetres kRedWall[4] = {
    {552.8f, 0, 0}, {549.6f, 0, 559.2f}, {556, 548.8f, 559.2f}, {556, 548.8f, 0}};

// Block tops; the sides run straight down from each top edge to the floor (y = 0). The corners
// are in the order whose normal (p1 - p0) x (p2 - p0) points up (+y).
const Millimetres kShortBlockTop[4] = {{130, 165, 65}, {82, 165, 225}, {240, 165, 272}, {290, 165, 114}};
const Millimetres kTallBlockTop[4] = {{423, 330, 247}, {265, 330, 296}, {314, 330, 456}, {472, 330, 406}};

// Diffuse reflectances: Cornell's measured spectra averaged over 600-700 nm (R), 500-600 nm (G)
// and 400-500 nm (B).
const Float3 kWhite{0.7339f, 0.7358f, 0.6978f};
const Float3 kRed{0.5761f, 0.0832f, 0.0562f};
const Float3 kGreen{0.1329f, 0.3508f, 0.1136f};

// The light's measured emission spectrum is 0 / 8 / 15.6 / 18.4 at 400 / 500 / 600 / 700 nm.
// Averaged (linearly interpolated) over the same bands: R (15.6 + 18.4) / 2 = 17.0,
// G (8 + 15.6) / 2 = 11.8, B (0 + 8) / 2 = 4.0. Scaled so green is 3 W: x 3 / 11.8, giving
// R 4.3220 W, G 3.0 W, B 1.0169 W.
const Float3 kLightPower{17.0f * 3.0f / 11.8f, 3.0f, 4.0f * 3.0f / 11.8f};
// Centred under the ceiling (y = 548.8) where the area light hangs, 10 mm below it so it does
// not sit on the ceiling's surface.
const Millimetres kLightPosition{278, 548.8f - 10, 279.6f};

// Camera of the published reference images.
const Millimetres kCameraPosition{278, 273, -800};
const Millimetres kCameraLookAt{278, 273, -799};
constexpr float kCameraVerticalFovDegrees = 39.3077f;
constexpr int kImageSize = 512;

MaterialDesc diffuse_material(const char* name, const Float3& reflectance) {
  MaterialDesc material;
  material.name = name;
  material.diffuse = reflectance;
  material.glossy = Float3{0, 0, 0};
  material.mirror = Float3{0, 0, 0};
  return material;
}

// Adds the quad a-b-c-d as triangles (a, b, c) and (a, c, d), keeping its winding.
void add_quad(Scene& scene, const Millimetres& a, const Millimetres& b, const Millimetres& c,
              const Millimetres& d, uint32_t material) {
  const uint32_t base = static_cast<uint32_t>(scene.positions.size());
  for (const Millimetres* corner : {&a, &b, &c, &d}) scene.positions.push_back(to_metres(*corner));
  const uint32_t triangles[6] = {base, base + 1, base + 2, base, base + 2, base + 3};
  scene.indices.insert(scene.indices.end(), triangles, triangles + 6);
  scene.triangle_material.push_back(material);
  scene.triangle_material.push_back(material);
}

// Closes the object the quads added since the last call belong to (the object_id layer).
void name_object(Scene& scene, const char* name) {
  scene.triangle_object.resize(scene.triangle_material.size(), uint32_t(scene.object_names.size()));
  scene.object_names.push_back(name);
}

void add_wall(Scene& scene, const Millimetres (&corners)[4], uint32_t material) {
  add_quad(scene, corners[0], corners[1], corners[2], corners[3], material);
}

// Top plus four sides. For the top edge t0 -> t1 (counter-clockwise seen from above), the side
// t1, t0, b0, b1 has an outward normal.
void add_block(Scene& scene, const Millimetres (&top)[4], uint32_t material) {
  add_wall(scene, top, material);
  for (int i = 0; i < 4; ++i) {
    const Millimetres& t0 = top[i];
    const Millimetres& t1 = top[(i + 1) % 4];
    const Millimetres b0{t0.x, 0, t0.z};
    const Millimetres b1{t1.x, 0, t1.z};
    add_quad(scene, t1, t0, b0, b1, material);
  }
}

}  // namespace

Scene builtin_cornell_box() {
  Scene scene;
  scene.name = "cornell-box";
  scene.source = "builtin:cornell-box";

  enum : uint32_t { kWhiteMaterial, kRedMaterial, kGreenMaterial };
  scene.materials = {diffuse_material("white", kWhite), diffuse_material("red", kRed),
                     diffuse_material("green", kGreen)};

  add_wall(scene, kFloor, kWhiteMaterial);
  name_object(scene, "floor");
  add_wall(scene, kCeiling, kWhiteMaterial);
  name_object(scene, "ceiling");
  add_wall(scene, kBackWall, kWhiteMaterial);
  name_object(scene, "back wall");
  add_wall(scene, kGreenWall, kGreenMaterial);
  name_object(scene, "green wall");
  add_wall(scene, kRedWall, kRedMaterial);
  name_object(scene, "red wall");
  add_block(scene, kShortBlockTop, kWhiteMaterial);
  name_object(scene, "short block");
  add_block(scene, kTallBlockTop, kWhiteMaterial);
  name_object(scene, "tall block");

  LightDesc light;
  light.name = "ceiling";
  light.position = to_metres(kLightPosition);
  light.power = kLightPower;
  scene.lights.push_back(light);

  scene.camera.position = to_metres(kCameraPosition);
  scene.camera.look_at = to_metres(kCameraLookAt);
  scene.camera.up = Float3{0, 1, 0};
  scene.camera.vertical_fov_degrees = kCameraVerticalFovDegrees;
  scene.camera.width = kImageSize;
  scene.camera.height = kImageSize;
  return scene;
}

}  // namespace pm

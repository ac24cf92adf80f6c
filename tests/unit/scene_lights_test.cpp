// Loading spot lights and emitting materials (area lights): JSON spot fields and their
// defaults, JSON and MTL emission, glTF KHR_lights_punctual spot lights (cone angles, candela,
// the node's -z axis and its animation) and emissive materials (emissiveFactor times
// KHR_materials_emissive_strength, in nits), a glTF lit by emission alone, the spot falloff and
// emitted fraction, and the area-light records built for the device.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "kernels/common/compat_host.h"
#include "kernels/common/spot_light.h"
#include "render/scene_emitters.h"
#include "render/scene_frame.h"
#include "scene_io/scene_file.h"
#include "gltf_test_support.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

const char kSpotScene[] = R"({
  "format": "pmrender-scene", "version": 1, "meters_per_unit": 0.01,
  "meshes": [ { "file": "tri.obj" } ],
  "materials": { "lamp": { "diffuse": [0, 0, 0], "emission": [2, 3, 4] } },
  "lights": [ { "name": "spot", "type": "spot", "position": [0, 200, 0], "power": [5, 5, 5],
                "direction": [0, -2, 0], "inner_cone_angle": 20, "outer_cone_angle": 30 },
              { "name": "plain", "type": "spot", "position": [0, 100, 0], "power": [1, 1, 1], "direction": [1, 0, 0] },
              { "name": "bulb", "position": [0, 100, 0], "power": [1, 1, 1] } ],
  "camera": { "position": [0, 0, -500], "look_at": [0, 0, 0] },
  "animation": { "lights": { "spot": { "direction": { "keys": [ { "time": 0, "value": [0, -1, 0] },
                                                               { "time": 1, "value": [1, 0, 0] } ] } } } }
})";

using SceneLights = Gltf;

TEST_F(SceneLights, JsonSpotFieldsDefaultsAndDirectionTrack) {
  write("tri.obj", "usemtl lamp\nv 0 0 0\nv 100 0 0\nv 0 100 0\nf 1 2 3\n");
  const Scene scene = load_scene_file(write("spot.json", kSpotScene));
  ASSERT_EQ(scene.lights.size(), 3u);
  const LightDesc& spot = scene.lights[0];
  EXPECT_EQ(spot.type, LightType::spot);
  EXPECT_FLOAT_EQ(spot.position.y, 2.0f);  // metres
  EXPECT_FLOAT_EQ(spot.direction.y, -2.0f);  // a direction: not scaled
  EXPECT_FLOAT_EQ(spot.inner_cone, float(20 * M_PI / 180));
  EXPECT_FLOAT_EQ(spot.outer_cone, float(30 * M_PI / 180));
  EXPECT_FLOAT_EQ(scene.lights[1].inner_cone, 0.0f);  // glTF's defaults: 0 and pi / 4
  EXPECT_FLOAT_EQ(scene.lights[1].outer_cone, float(M_PI / 4));
  EXPECT_EQ(scene.lights[2].type, LightType::point);
  // The emission of a JSON material the OBJ's usemtl names.
  EXPECT_FLOAT_EQ(scene.materials[0].emission.z, 4.0f);
  EXPECT_TRUE(scene.has_emitters());
  // The direction track turns the spot; the other lights keep theirs.
  EXPECT_NEAR(lights_at_frame(scene, 12)[0].direction.x, 0.5f, 1e-6);
  EXPECT_NEAR(lights_at_frame(scene, 24)[0].direction.x, 1.0f, 1e-6);
  EXPECT_FALSE(same_lights(lights_at_frame(scene, 0), lights_at_frame(scene, 1)));
}

TEST_F(SceneLights, MtlKeIsEmission) {
  write("lamp.obj", "mtllib lamp.mtl\nusemtl glow\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  write("lamp.mtl", "newmtl glow\nKd 0.1 0.1 0.1\nKe 5 6 7\n");
  const std::string json_path = write("lamp.json", R"({
    "format": "pmrender-scene", "version": 1, "meshes": [ { "file": "lamp.obj" } ],
    "camera": { "position": [0, 0, -5], "look_at": [0, 0, 0] } })");
  const Scene scene = load_scene_file(json_path);
  EXPECT_TRUE(scene.lights.empty());  // lit by its emitting triangle alone
  EXPECT_FLOAT_EQ(scene.materials[0].emission.y, 6.0f);
  write("lamp.mtl", "newmtl glow\nKd 0.1 0.1 0.1\nKe 5 -6 7\n");
  try {
    load_scene_file(json_path);
    ADD_FAILURE() << "a negative Ke loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("lamp.mtl: material 'glow': Ke[1] is negative"), std::string::npos) << e.what();
  }
}

TEST_F(SceneLights, GltfSpotLightConesCandelaAndAxis) {
  GltfBuilder b;
  b.node({{"mesh", b.triangle_mesh()}});
  b.add_camera_and_light();
  const double h = std::sqrt(0.5);
  // Turned -90 degrees about x: its -z axis points down (-y).
  const int node = b.add_light({{"type", "spot"}, {"intensity", 683.0 / (4 * M_PI)}, {"color", {1.0, 0.5, 0.25}},
                                {"spot", {{"innerConeAngle", 0.25}, {"outerConeAngle", 0.5}}}},
                               {0, 2, 0});
  b.doc()["nodes"][size_t(node)]["rotation"] = {-h, 0, 0, h};
  const Scene scene = load(b);
  ASSERT_EQ(scene.lights.size(), 2u);
  const LightDesc& spot = scene.lights[1];
  EXPECT_EQ(spot.type, LightType::spot);
  EXPECT_FLOAT_EQ(spot.inner_cone, 0.25f);
  EXPECT_FLOAT_EQ(spot.outer_cone, 0.5f);
  // Candela as for a point light: the power of the isotropic light of the same intensity.
  EXPECT_NEAR(spot.power.x, 1.0f, 1e-6);
  EXPECT_NEAR(spot.power.z, 0.25f, 1e-6);
  EXPECT_NEAR(spot.direction.y, -1.0f, 1e-6);
  EXPECT_NEAR(spot.direction.z, 0.0f, 1e-6);
  // A rotation track turns the spot's axis with its node.
  b.animate(node, "rotation", {0, 1}, {float(-h), 0, 0, float(h), 0, 0, 0, 1});
  const Scene animated = load(b);
  EXPECT_NEAR(lights_at_frame(animated, 0)[1].direction.y, -1.0f, 1e-5);
  EXPECT_NEAR(lights_at_frame(animated, 24)[1].direction.z, -1.0f, 1e-5);
}

TEST_F(SceneLights, GltfBadConeAnglesNameTheField) {
  GltfBuilder b;
  b.node({{"mesh", b.triangle_mesh()}});
  b.add_camera_and_light();
  b.add_light({{"type", "spot"}, {"intensity", 1.0}, {"spot", {{"innerConeAngle", 0.6}, {"outerConeAngle", 0.5}}}}, {0, 2, 0});
  expect_error(b, "extensions.KHR_lights_punctual.lights[1].spot.innerConeAngle: must be in [0, outerConeAngle = 0.5) radians, got 0.6");
  b.doc()["extensions"]["KHR_lights_punctual"]["lights"][1]["spot"] = {{"outerConeAngle", 2.0}};
  expect_error(b, "extensions.KHR_lights_punctual.lights[1].spot.outerConeAngle: must be in (0, pi/2] radians, got 2");
}

TEST_F(SceneLights, GltfLitByEmissionAloneAndEmissiveStrength) {
  GltfBuilder b;
  b.doc()["materials"] = {{{"emissiveFactor", {1.0, 0.5, 0.0}},
                           {"emissiveTexture", {{"index", 0}}},
                           {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 683.0}}}}}}};
  b.doc()["textures"] = {{{"source", 0}}};
  b.doc()["images"] = {{{"uri", "never_read.png"}}};
  b.node({{"mesh", b.triangle_mesh({{"material", 0}})}});
  b.doc()["cameras"].push_back({{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.01}}}});
  b.node({{"camera", 0}, {"translation", {0, 0, 5}}});
  SceneLoadReport report;
  const Scene scene = load(b, &report);
  EXPECT_TRUE(scene.lights.empty());
  // 683 nits: 1 W sr^-1 m^-2 per unit of emissiveFactor.
  EXPECT_FLOAT_EQ(scene.materials[0].emission.x, 1.0f);
  EXPECT_FLOAT_EQ(scene.materials[0].emission.y, 0.5f);
  EXPECT_TRUE(has_warning(report, "materials[0]: emissiveTexture is not rendered (1 materials have one)"));
  EXPECT_FALSE(has_warning(report, "KHR_materials_emissive_strength"));
  b.doc()["materials"][0]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] = -1.0;
  expect_error(b, "materials[0].extensions.KHR_materials_emissive_strength.emissiveStrength: must be a finite number >= 0, got -1");
  b.doc()["materials"][0]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] = 1.0;
  b.doc()["materials"][0]["emissiveFactor"] = {0.0, 0.0, 0.0};
  expect_error(b, "extensions.KHR_lights_punctual: no light: no KHR_lights_punctual point or spot light with intensity "
                  "above zero and no emissive material");
}

TEST(SpotFalloff, GltfSmoothFalloffAndEmittedFraction) {
  const float co = std::cos(0.5f), ci = std::cos(0.25f);
  EXPECT_EQ(spot_falloff_cos(1.0f, co, ci), 1.0f);
  EXPECT_EQ(spot_falloff_cos(ci, co, ci), 1.0f);
  EXPECT_EQ(spot_falloff_cos(co, co, ci), 0.0f);
  EXPECT_NEAR(spot_falloff_cos(0.5f * (co + ci), co, ci), 0.25f, 1e-6f);
  // The emitted fraction is the falloff's mean over the sphere: T / 2, integrated numerically.
  LightDesc light;
  light.type = LightType::spot;
  light.inner_cone = 0.25f;
  light.outer_cone = 0.5f;
  double integral = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) integral += spot_falloff_cos(float(-1 + 2 * (i + 0.5) / n), co, ci) * 2.0 / n;
  EXPECT_NEAR(light_emitted_fraction(light), integral / 2, 1e-5);
  // The sampled cosines follow f / T: their share above the inner cone is (1 - ci) / T.
  int above = 0;
  for (int i = 0; i < n; ++i) above += spot_sample_cos((i + 0.5f) / n, co, ci) >= ci;
  EXPECT_NEAR(double(above) / n, (1 - ci) / spot_cone_mass(co, ci), 1e-3);
  EXPECT_NEAR(spot_sample_cos(0.9999999f, co, ci), co, 1e-3);
}

TEST(SceneEmitters, RecordsPowerAndCumulativeShares) {
  Scene scene;
  MaterialDesc grey, lamp;
  lamp.emission = {1, 2, 3};
  scene.materials = {grey, lamp};
  scene.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 2}, {2, 0, 2}, {0, 2, 2}};
  scene.indices = {0, 1, 2, 3, 4, 5, 0, 1, 2};
  scene.triangle_material = {1, 1, 0};
  const SceneEmitters e = build_scene_emitters(scene);
  ASSERT_EQ(e.count, 2u);
  ASSERT_EQ(e.records.size(), 2u * PM_EMITTER_FLOAT4S);
  EXPECT_NEAR(e.power, M_PI * (0.5 + 2.0) * 2.0, 1e-5);  // pi A mean(L_e)
  EXPECT_NEAR(e.records[0].w, 0.2f, 1e-6);                 // 0.5 of 2.5 m^2
  EXPECT_EQ(e.records[PM_EMITTER_FLOAT4S].w, 1.0f);
  EXPECT_FLOAT_EQ(e.records[2].w, 0.5f);                   // area
  EXPECT_FLOAT_EQ(e.records[3].w, 2.0f);                   // mean radiance
  ASSERT_EQ(e.material_emission.size(), 2u);
  EXPECT_EQ(e.material_emission[0].x, 0.0f);
  scene.triangle_material = {0, 0, 0};
  EXPECT_EQ(build_scene_emitters(scene).count, 0u);
  EXPECT_FALSE(scene.has_light());
}

}  // namespace
}  // namespace pm

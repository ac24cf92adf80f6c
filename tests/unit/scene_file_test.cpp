// Tests that valid JSON scenes load into the right pm::Scene: counts, unit conversion, material
// resolution (MTL mapping incl. illum 3 -> mirror, JSON before MTL, mesh overrides, default
// material), degenerate triangles, defaults and triangulation. Error cases: scene_*_errors_test.
#include "scene_io/scene_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "render/errors.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

std::string data_scene(const std::string& relative) {
  return std::string(PM_TEST_DATA_DIR) + "/scenes/" + relative;
}

const MaterialDesc* find_material(const Scene& scene, const std::string& name) {
  for (const MaterialDesc& m : scene.materials) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

// Materials of triangles whose three corners all satisfy `where`.
template <typename Predicate>
std::vector<std::string> materials_of_triangles(const Scene& scene, Predicate where) {
  std::vector<std::string> names;
  for (size_t t = 0; t < scene.triangle_count(); ++t) {
    bool all = true;
    for (int k = 0; k < 3; ++k) all = all && where(scene.positions[scene.indices[3 * t + k]]);
    if (all) names.push_back(scene.materials[scene.triangle_material[t]].name);
  }
  return names;
}

void expect_float3(const Float3& actual, float x, float y, float z, float tolerance = 1e-6f) {
  EXPECT_NEAR(actual.x, x, tolerance);
  EXPECT_NEAR(actual.y, y, tolerance);
  EXPECT_NEAR(actual.z, z, tolerance);
}

Float3 triangle_normal(const Scene& scene, size_t t) {
  const Float3& a = scene.positions[scene.indices[3 * t]];
  const Float3& b = scene.positions[scene.indices[3 * t + 1]];
  const Float3& c = scene.positions[scene.indices[3 * t + 2]];
  const float e1[3] = {b.x - a.x, b.y - a.y, b.z - a.z};
  const float e2[3] = {c.x - a.x, c.y - a.y, c.z - a.z};
  Float3 n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  const float length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  return Float3{n.x / length, n.y / length, n.z / length};
}

class SceneFileRoomTest : public ::testing::Test {
 protected:
  void SetUp() override { scene_ = load_scene_file(data_scene("units_room/room.json"), &report_); }
  Scene scene_;
  SceneLoadReport report_;
};

TEST_F(SceneFileRoomTest, CountsNameAndSource) {
  EXPECT_EQ(scene_.name, "units-room");
  EXPECT_EQ(scene_.source, data_scene("units_room/room.json"));
  // room.obj: 5 quads = 10 triangles kept, 2 degenerate dropped; block.obj: 4 triangles.
  EXPECT_EQ(scene_.triangle_count(), 14u);
  EXPECT_EQ(scene_.indices.size(), 42u);
  EXPECT_EQ(scene_.triangle_material.size(), 14u);
  EXPECT_EQ(scene_.positions.size(), 9u + 4u);
  for (uint32_t index : scene_.indices) EXPECT_LT(index, scene_.positions.size());
  for (uint32_t material : scene_.triangle_material) EXPECT_LT(material, scene_.materials.size());
  EXPECT_EQ(scene_.lights.size(), 2u);
}

TEST_F(SceneFileRoomTest, DegenerateTrianglesAreDroppedAndCounted) {
  EXPECT_EQ(report_.degenerate_triangles_dropped, 2u);
  bool warned = false;
  for (const std::string& w : report_.warnings)
    warned = warned || w.find("room.obj: 2 degenerate") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST_F(SceneFileRoomTest, PositionsAreConvertedToMetres) {
  float max_coordinate = 0;
  for (const Float3& p : scene_.positions) max_coordinate = std::max({max_coordinate, p.x, p.y, p.z});
  EXPECT_FLOAT_EQ(max_coordinate, 1.0f);                     // 1000 mm
  expect_float3(scene_.positions[1], 1, 0, 0);               // room.obj vertex 2 = (1000, 0, 0) mm
  expect_float3(scene_.positions[9 + 3], 0.3f, 0.2f, 0.3f);  // block.obj vertex 4
  expect_float3(scene_.lights[0].position, 0.5f, 0.9f, 0.5f);
  expect_float3(scene_.lights[1].position, 0.1f, 0.1f, 0.1f);
  expect_float3(scene_.camera.position, 0.5f, 0.5f, -1.0f);
  expect_float3(scene_.camera.look_at, 0.5f, 0.5f, 0.0f);
}

TEST_F(SceneFileRoomTest, LightsAndCameraKeepTheirValues) {
  EXPECT_EQ(scene_.lights[0].name, "key");
  EXPECT_EQ(scene_.lights[1].name, "light1");         // default name: "light" + index
  expect_float3(scene_.lights[0].power, 10, 10, 10);  // watts, not scaled
  expect_float3(scene_.lights[1].power, 1, 2, 3);
  expect_float3(scene_.camera.up, 0, 1, 0);
  EXPECT_FLOAT_EQ(scene_.camera.vertical_fov_degrees, 50.0f);
  EXPECT_EQ(scene_.camera.width, 320);
  EXPECT_EQ(scene_.camera.height, 240);
}

TEST_F(SceneFileRoomTest, MaterialsAreTheUsedOnesInFirstUseOrder) {
  std::vector<std::string> names;
  for (const MaterialDesc& m : scene_.materials) names.push_back(m.name);
  EXPECT_EQ(names, (std::vector<std::string>{"default", "wall", "mirror", "carpet", "bright", "painted"}));
}

TEST_F(SceneFileRoomTest, FacesWithoutUsemtlGetTheDefaultGrey) {
  auto on_floor = [](const Float3& p) { return p.y == 0; };
  auto floor = materials_of_triangles(scene_, on_floor);
  // The block's base triangle also lies on y = 0 and is "painted".
  EXPECT_EQ(std::count(floor.begin(), floor.end(), "default"), 2);
  const MaterialDesc* grey = find_material(scene_, "default");
  ASSERT_NE(grey, nullptr);
  expect_float3(grey->diffuse, 0.8f, 0.8f, 0.8f);
  expect_float3(grey->glossy, 0, 0, 0);
  expect_float3(grey->mirror, 0, 0, 0);
}

TEST_F(SceneFileRoomTest, MtlKdKsNsMapToDiffuseGlossyExponent) {
  const MaterialDesc* wall = find_material(scene_, "wall");
  ASSERT_NE(wall, nullptr);
  expect_float3(wall->diffuse, 0.6f, 0.5f, 0.4f);
  expect_float3(wall->glossy, 0.2f, 0.2f, 0.2f);
  expect_float3(wall->mirror, 0, 0, 0);
  EXPECT_FLOAT_EQ(wall->glossy_exponent, 30.0f);
  auto on_back_wall = [](const Float3& p) { return p.z == 1.0f; };
  EXPECT_EQ(materials_of_triangles(scene_, on_back_wall), (std::vector<std::string>{"wall", "wall"}));
}

TEST_F(SceneFileRoomTest, MtlIllum3MakesKsAMirror) {
  const MaterialDesc* mirror = find_material(scene_, "mirror");
  ASSERT_NE(mirror, nullptr);
  expect_float3(mirror->diffuse, 0.1f, 0.1f, 0.1f);
  expect_float3(mirror->mirror, 0.8f, 0.7f, 0.6f);
  expect_float3(mirror->glossy, 0, 0, 0);
  auto on_left_wall = [](const Float3& p) { return p.x == 0; };
  EXPECT_EQ(materials_of_triangles(scene_, on_left_wall), (std::vector<std::string>{"mirror", "mirror"}));
}

TEST_F(SceneFileRoomTest, JsonMaterialWinsOverMtlOfTheSameName) {
  const MaterialDesc* carpet = find_material(scene_, "carpet");
  ASSERT_NE(carpet, nullptr);
  expect_float3(carpet->diffuse, 0.3f, 0.2f, 0.1f);  // room.mtl says 0.9 0.1 0.1
  auto on_right_wall = [](const Float3& p) { return p.x == 1.0f; };
  EXPECT_EQ(materials_of_triangles(scene_, on_right_wall), (std::vector<std::string>{"carpet", "carpet"}));
}

TEST_F(SceneFileRoomTest, OverBrightMtlMaterialIsScaledPerChannelWithAWarning) {
  const MaterialDesc* bright = find_material(scene_, "bright");
  ASSERT_NE(bright, nullptr);
  const float scale = 0.99f / 1.2f;
  expect_float3(bright->diffuse, 0.9f * scale, 0.9f * scale, 0.5f);
  expect_float3(bright->glossy, 0.3f * scale, 0.3f * scale, 0.3f);
  EXPECT_NEAR(bright->diffuse.x + bright->glossy.x + bright->mirror.x, 0.99f, 1e-6f);
  bool warned = false;
  for (const std::string& w : report_.warnings) {
    warned = warned || (w.find("room.mtl: material 'bright'") != std::string::npos &&
                        w.find("scaled down to 0.99") != std::string::npos);
  }
  EXPECT_TRUE(warned);
}

TEST_F(SceneFileRoomTest, MeshMaterialOverridesEveryFace) {
  const MaterialDesc* painted = find_material(scene_, "painted");
  ASSERT_NE(painted, nullptr);
  expect_float3(painted->diffuse, 0.2f, 0.3f, 0.4f);
  expect_float3(painted->glossy, 0.1f, 0.1f, 0.1f);
  EXPECT_FLOAT_EQ(painted->glossy_exponent, 50.0f);
  // block.obj's four triangles are the last four.
  for (size_t t = 10; t < 14; ++t) EXPECT_EQ(scene_.materials[scene_.triangle_material[t]].name, "painted");
}

TEST_F(SceneFileRoomTest, WindingIsKept) {
  // The floor quad "f 1 4 3 2" winds to an upward normal; triangulation must keep that.
  EXPECT_NEAR(triangle_normal(scene_, 0).y, 1.0f, 1e-6f);
  EXPECT_NEAR(triangle_normal(scene_, 1).y, 1.0f, 1e-6f);
}

// Inputs written by the test itself, in a fresh folder.
class SceneFileInlineTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) / (std::string("pm_scene_file_") + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
  }

  fs::path dir_;
};

const char kMinimalScene[] = R"({
  "format": "pmrender-scene", "version": 1,
  "meshes": [ { "file": "shapes/tri.obj" } ],
  "lights": [ { "position": [0, 2, 0], "power": [1, 1, 1] } ],
  "camera": { "position": [0, 0, -5], "look_at": [0, 0, 0] }
})";

TEST_F(SceneFileInlineTest, OptionalKeysTakeTheirDefaults) {
  write("shapes/tri.obj", "v 0 0 0\nv 2 0 0\nv 0 3 0\nf 1 2 3\n");
  const Scene scene = load_scene_file(write("my-minimal.json", kMinimalScene));
  EXPECT_EQ(scene.name, "my-minimal");  // the file stem
  ASSERT_EQ(scene.triangle_count(), 1u);
  expect_float3(scene.positions[1], 2, 0, 0);  // meters_per_unit 1
  expect_float3(scene.camera.up, 0, 1, 0);
  EXPECT_FLOAT_EQ(scene.camera.vertical_fov_degrees, 45.0f);
  EXPECT_EQ(scene.camera.width, 512);
  EXPECT_EQ(scene.camera.height, 512);
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(scene.materials[0].name, "default");
}

TEST_F(SceneFileInlineTest, JsonMaterialNamedDefaultReplacesTheBuiltInGrey) {
  write("shapes/tri.obj", "v 0 0 0\nv 2 0 0\nv 0 3 0\nf 1 2 3\n");
  std::string text = kMinimalScene;
  text.insert(text.rfind('}'), R"(, "materials": { "default": { "diffuse": [0.1, 0.2, 0.3] } })");
  const Scene scene = load_scene_file(write("scene.json", text));
  ASSERT_EQ(scene.materials.size(), 1u);
  expect_float3(scene.materials[0].diffuse, 0.1f, 0.2f, 0.3f);
}

TEST_F(SceneFileInlineTest, UsemtlNamesResolveToJsonMaterialsWithoutAnyMtl) {
  write("shapes/tri.obj",
        "v 0 0 0\nv 2 0 0\nv 0 3 0\nv 2 3 0\nusemtl gold\nf 1 2 3\nusemtl\tsilver\nf 2 4 3\n");
  std::string text = kMinimalScene;
  text.insert(text.rfind('}'),
              R"(, "materials": { "gold": { "glossy": [0.9, 0.8, 0.1], "diffuse": [0, 0, 0] },
                                                   "silver": { "mirror": [0.9, 0.9, 0.9], "diffuse": [0, 0, 0] } })");
  const Scene scene = load_scene_file(write("scene.json", text));
  ASSERT_EQ(scene.triangle_count(), 2u);
  EXPECT_EQ(scene.materials[scene.triangle_material[0]].name, "gold");
  EXPECT_EQ(scene.materials[scene.triangle_material[1]].name, "silver");
  expect_float3(scene.materials[scene.triangle_material[1]].mirror, 0.9f, 0.9f, 0.9f);
}

TEST_F(SceneFileInlineTest, MaterialNamesMayContainBlanks) {
  // tinyobjloader reads "newmtl" names to the end of the line but "usemtl" names only to the first
  // blank; the loader matches whole names, so these two stay distinct.
  write("shapes/tri.obj",
        "mtllib words.mtl\nv 0 0 0\nv 2 0 0\nv 0 3 0\nv 2 3 0\n"
        "usemtl Material #0\nf 1 2 3\nusemtl Material #1  \nf 2 4 3\n");
  write("shapes/words.mtl", "newmtl Material #0\nKd 0.1 0.2 0.3\n\nnewmtl Material #1\nKd 0.4 0.5 0.6\n");
  const Scene scene = load_scene_file(write("scene.json", kMinimalScene));
  ASSERT_EQ(scene.triangle_count(), 2u);
  const MaterialDesc& first = scene.materials[scene.triangle_material[0]];
  const MaterialDesc& second = scene.materials[scene.triangle_material[1]];
  EXPECT_EQ(first.name, "Material #0");
  expect_float3(first.diffuse, 0.1f, 0.2f, 0.3f);
  EXPECT_EQ(second.name, "Material #1");
  expect_float3(second.diffuse, 0.4f, 0.5f, 0.6f);
}

TEST_F(SceneFileInlineTest, PolygonsAreTriangulatedKeepingTheirWinding) {
  // A convex pentagon and a quad in the z = 0 plane, both wound counter-clockwise seen from +z,
  // with CRLF line ends.
  write("shapes/tri.obj",
        "v 0 0 0\r\nv 2 0 0\r\nv 3 1 0\r\nv 1 2 0\r\nv -1 1 0\r\nf 1 2 3 4 5\r\n"
        "v 5 0 0\r\nv 6 0 0\r\nv 6 1 0\r\nv 5 1 0\r\nf 6 7 8 9\r\n");
  const Scene scene = load_scene_file(write("scene.json", kMinimalScene));
  ASSERT_EQ(scene.triangle_count(), 3u + 2u);
  for (size_t t = 0; t < scene.triangle_count(); ++t) {
    SCOPED_TRACE("triangle " + std::to_string(t));
    EXPECT_NEAR(triangle_normal(scene, t).z, 1.0f, 1e-6f);
  }
}

TEST_F(SceneFileInlineTest, IntegralFloatsAreAcceptedWhereIntegersAreExpected) {
  write("shapes/tri.obj", "v 0 0 0\nv 2 0 0\nv 0 3 0\nf 1 2 3\n");
  std::string text = kMinimalScene;
  text.replace(text.find(R"("look_at": [0, 0, 0] })"), std::string(R"("look_at": [0, 0, 0] })").size(),
               R"("look_at": [0, 0, 0], "resolution": [640.0, 480] })");
  const Scene scene = load_scene_file(write("scene.json", text));
  EXPECT_EQ(scene.camera.width, 640);
  EXPECT_EQ(scene.camera.height, 480);
}

}  // namespace
}  // namespace pm

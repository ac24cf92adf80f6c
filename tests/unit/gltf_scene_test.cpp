// glTF 2.0 scenes (scene_io/gltf_scene.h): the hand-written twin of a JSON scene loads into the
// same pm::Scene, and small glTF files written by the test cover index types, primitive modes,
// node transforms, the material mapping, cameras, KHR_lights_punctual lights, node animations
// (STEP, LINEAR, CUBICSPLINE, rotations, hierarchies), .glb containers and errors.
#include "gltf_test_support.h"

namespace pm {
namespace {

bool same(const Float3& a, const Float3& b) { return std::memcmp(&a, &b, sizeof(Float3)) == 0; }

TEST_F(Gltf, TwinFileGivesTheSameSceneAsItsJsonTwin) {
  const std::string data = test::test_data_dir() + "/animation/";
  SceneLoadReport report;
  const Scene g = load_scene_file(data + "twin.gltf", &report);
  const Scene j = load_scene_file(data + "twin.json");
  EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
  EXPECT_EQ(g.name, "twin");
  ASSERT_EQ(g.triangle_count(), 20u);
  ASSERT_EQ(g.triangle_count(), j.triangle_count());
  for (size_t t = 0; t < g.triangle_count(); ++t) {
    for (int c = 0; c < 3; ++c)
      EXPECT_TRUE(same(g.positions[g.indices[3 * t + c]], j.positions[j.indices[3 * t + c]])) << "triangle " << t;
    EXPECT_EQ(g.triangle_material[t], j.triangle_material[t]);
  }
  ASSERT_EQ(g.materials.size(), j.materials.size());
  for (size_t m = 0; m < g.materials.size(); ++m) {
    SCOPED_TRACE(g.materials[m].name);
    EXPECT_EQ(g.materials[m].name, j.materials[m].name);
    EXPECT_TRUE(same(g.materials[m].diffuse, j.materials[m].diffuse));
    EXPECT_TRUE(same(g.materials[m].glossy, j.materials[m].glossy));
    EXPECT_TRUE(same(g.materials[m].mirror, j.materials[m].mirror));
    EXPECT_EQ(g.materials[m].glossy_exponent, j.materials[m].glossy_exponent);
  }
  ASSERT_TRUE(g.animation.enabled);
  EXPECT_EQ(g.animation.frame_rate, j.animation.frame_rate);
  EXPECT_EQ(g.animation.first_frame, j.animation.first_frame);
  EXPECT_EQ(g.animation.last_frame, 24);
  EXPECT_EQ(j.animation.last_frame, 24);
  for (int f = 0; f <= 24; ++f) {
    SCOPED_TRACE("frame " + std::to_string(f));
    const CameraDesc cg = camera_at_frame(g, f), cj = camera_at_frame(j, f);
    EXPECT_TRUE(same(cg.position, cj.position));
    EXPECT_TRUE(same(cg.look_at, cj.look_at));
    EXPECT_TRUE(same(cg.up, cj.up));
    EXPECT_EQ(cg.vertical_fov_degrees, cj.vertical_fov_degrees);
    EXPECT_EQ(cg.width, cj.width);
    EXPECT_EQ(cg.height, cj.height);
    EXPECT_TRUE(same_lights(lights_at_frame(g, f), lights_at_frame(j, f)));
  }
  EXPECT_EQ(lights_at_frame(g, 12)[0].position.x, 1.0f);
  EXPECT_EQ(camera_at_frame(g, 12).position.y, 1.125f);  // rig (0, 1, 0) plus the node's 0.125
}

TEST_F(Gltf, IndexTypesStripsFansAndNodeTransforms) {
  GltfBuilder b;
  const std::vector<float> square = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const int pos = b.floats(square, "VEC3");
  json primitives = json::array();
  primitives.push_back({{"attributes", {{"POSITION", pos}}}, {"indices", b.accessor(std::vector<uint8_t>{0, 1, 2, 0, 2, 3}, 5121, "SCALAR")}});
  primitives.push_back({{"attributes", {{"POSITION", pos}}}, {"indices", b.accessor(std::vector<uint16_t>{0, 1, 2}, 5123, "SCALAR")}});
  primitives.push_back({{"attributes", {{"POSITION", pos}}}, {"indices", b.accessor(std::vector<uint32_t>{0, 2, 3}, 5125, "SCALAR")}});
  primitives.push_back({{"attributes", {{"POSITION", pos}}}, {"mode", 5}, {"indices", b.accessor(std::vector<uint16_t>{0, 1, 3, 2}, 5123, "SCALAR")}});
  primitives.push_back({{"attributes", {{"POSITION", pos}}}, {"mode", 6}});  // fan 0 1 2 3: two triangles
  primitives.push_back({{"attributes", {{"POSITION", pos}}}, {"mode", 1}});  // lines: skipped with a warning
  const int mesh = b.mesh(primitives);
  const double h = std::sqrt(0.5);
  // A parent that moves by +10 x, a child turned 90 degrees about +z and scaled by 2.
  const int child = b.node({{"mesh", mesh}, {"rotation", {0, 0, h, h}}, {"scale", {2, 2, 2}}}, false);
  b.node({{"translation", {10, 0, 0}}, {"children", {child}}});
  b.node({{"mesh", mesh}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -3, 1}}});
  b.add_camera_and_light();
  SceneLoadReport report;
  const Scene scene = load(b, &report);
  EXPECT_EQ(scene.triangle_count(), 2u * (2 + 1 + 1 + 2 + 2));
  EXPECT_TRUE(has_warning(report, "points and lines are not rendered"));
  // The parented instance: local (1, 0, 0) -> scaled (2, 0, 0) -> turned (0, 2, 0) -> moved (10, 2, 0).
  const Float3 p = scene.positions[1];
  EXPECT_NEAR(p.x, 10.0f, 1e-6);
  EXPECT_NEAR(p.y, 2.0f, 1e-6);
  EXPECT_EQ(scene.positions[5 * 4 + 1].z, -3.0f);  // the matrix node's instance, second vertex
  // Strip: (0 1 3), then (3 1 2) with the winding kept.
  const size_t strip = 2 + 1 + 1;
  EXPECT_EQ(scene.indices[3 * strip + 0] % 4, 0u);
  EXPECT_EQ(scene.indices[3 * strip + 2] % 4, 3u);
  EXPECT_EQ(scene.indices[3 * strip + 3] % 4, 3u);
  EXPECT_EQ(scene.indices[3 * strip + 4] % 4, 1u);
  EXPECT_EQ(scene.indices[3 * strip + 5] % 4, 2u);
}

TEST_F(Gltf, MetallicRoughnessMapsOntoModifiedPhong) {
  EXPECT_NEAR(roughness_to_phong_exponent(0.5), 30.0, 1e-12);
  EXPECT_EQ(roughness_to_phong_exponent(1.0), 0.0);
  EXPECT_TRUE(std::isinf(roughness_to_phong_exponent(0.0)));
  GltfBuilder b;
  b.doc()["materials"] = {
      {{"name", "paint"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.4, 0.3, 1}}, {"metallicFactor", 0.0}}}},
      {{"name", "chrome"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.9, 0.9, 0.9, 1}}, {"roughnessFactor", 0.05}}}},
      {{"name", "brushed"},
       {"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.6, 0.4, 1}}, {"metallicFactor", 0.25}, {"roughnessFactor", 0.5}}}},
      {{"name", "textured"},
       {"pbrMetallicRoughness", {{"metallicFactor", 0.0}}},
       {"normalTexture", {{"index", 0}}},
       {"emissiveFactor", {1, 1, 1}}}};
  b.doc()["textures"] = {{{"source", 0}}};
  b.doc()["images"] = {{{"uri", "missing.png"}}};
  for (int m = 0; m < 4; ++m) b.node({{"mesh", b.triangle_mesh({{"material", m}})}});
  b.node({{"mesh", b.triangle_mesh()}});  // no material
  b.add_camera_and_light();
  SceneLoadReport report;
  const Scene scene = load(b, &report);
  ASSERT_EQ(scene.materials.size(), 5u);
  const MaterialDesc& paint = scene.materials[0];
  EXPECT_EQ(paint.diffuse.x, 0.5f);
  EXPECT_EQ(paint.glossy.x, 0.0f);
  EXPECT_EQ(paint.mirror.x, 0.0f);
  const MaterialDesc& chrome = scene.materials[1];  // metallic defaults to 1; smooth: a mirror
  EXPECT_EQ(chrome.diffuse.x, 0.0f);
  EXPECT_EQ(chrome.mirror.y, 0.9f);
  EXPECT_EQ(chrome.glossy.y, 0.0f);
  const MaterialDesc& brushed = scene.materials[2];
  EXPECT_FLOAT_EQ(brushed.diffuse.x, 0.6f);
  EXPECT_FLOAT_EQ(brushed.glossy.x, 0.2f);
  EXPECT_FLOAT_EQ(brushed.glossy.z, 0.1f);
  EXPECT_FLOAT_EQ(brushed.glossy_exponent, 30.0f);
  EXPECT_EQ(scene.materials[3].diffuse.x, 1.0f);  // baseColorFactor defaults to white
  // An image only an ignored feature names is never read: missing.png is no error.
  EXPECT_TRUE(has_warning(report, "materials[3] ('textured'): ignored: normalTexture"));
  // emissiveFactor makes it an area light: 1 nit per channel at 683 lm/W.
  EXPECT_FLOAT_EQ(scene.materials[3].emission.x, float(1.0 / 683.0));
  EXPECT_EQ(scene.materials[0].emission.x, 0.0f);
  EXPECT_EQ(scene.materials[4].name, "default");
  EXPECT_EQ(scene.materials[4].diffuse.x, 0.8f);
}

TEST_F(Gltf, CamerasLightsAndTheirConversions) {
  EXPECT_NEAR(candela_to_watts(683.0 / (4 * M_PI), 1.0), 1.0, 1e-12);
  GltfBuilder b;
  b.node({{"mesh", b.triangle_mesh()}});
  const double h = std::sqrt(0.5);
  b.doc()["cameras"] = {{{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 10}}}},
                        {{"type", "perspective"}, {"name", "wide"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.01}}}},
                        {{"type", "perspective"}, {"perspective", {{"yfov", M_PI / 4}, {"aspectRatio", 4.0 / 3.0}, {"znear", 0.01}}}}};
  b.node({{"camera", 0}});
  // Turned 90 degrees about +y: it looks down -x.
  b.node({{"name", "side"}, {"camera", 2}, {"translation", {1, 2, 3}}, {"rotation", {0, h, 0, h}}});
  b.node({{"name", "front"}, {"camera", 1}, {"translation", {0, 0, 4}}});
  b.add_light({{"type", "point"}, {"intensity", 683.0 / (4 * M_PI)}, {"color", {1.0, 0.5, 0.0}}, {"name", "bulb"}}, {0, 3, 0});
  b.add_light({{"type", "spot"}, {"intensity", 5.0}, {"spot", json::object()}}, {0, 3, 0});
  b.add_light({{"type", "directional"}, {"intensity", 5.0}}, {0, 3, 0});
  SceneLoadReport report;
  Scene scene = load(b, &report);
  // The first perspective camera in the node order; the orthographic one is passed over.
  EXPECT_NEAR(scene.camera.position.x, 1.0f, 1e-6);
  EXPECT_NEAR(scene.camera.look_at.x - scene.camera.position.x, -1.0f, 1e-6);
  EXPECT_NEAR(scene.camera.look_at.z - scene.camera.position.z, 0.0f, 1e-6);
  EXPECT_NEAR(scene.camera.up.y, 1.0f, 1e-6);
  EXPECT_NEAR(scene.camera.vertical_fov_degrees, 45.0f, 1e-5);
  EXPECT_EQ(scene.camera.height, 512);
  EXPECT_EQ(scene.camera.width, 683);  // 512 * 4/3 rounded
  ASSERT_EQ(scene.lights.size(), 2u);  // the point and the spot light; the directional one is skipped
  EXPECT_EQ(scene.lights[1].type, LightType::spot);
  EXPECT_EQ(scene.lights[0].name, "bulb");
  EXPECT_NEAR(scene.lights[0].power.x, 1.0f, 1e-6);
  EXPECT_NEAR(scene.lights[0].power.y, 0.5f, 1e-6);
  EXPECT_EQ(scene.lights[0].power.z, 0.0f);
  EXPECT_EQ(scene.lights[0].position.y, 3.0f);
  EXPECT_FALSE(has_warning(report, "spot lights are not supported"));
  EXPECT_TRUE(has_warning(report, "directional lights are not supported"));
  EXPECT_FALSE(scene.animation.enabled);

  // The camera the scene's extras name, and the resolution they set.
  b.doc()["scenes"][0]["extras"] = {{"pmrender", {{"camera", "wide"}, {"resolution", {64, 32}}}}};
  scene = load(b);
  EXPECT_EQ(scene.camera.position.z, 4.0f);
  EXPECT_NEAR(scene.camera.vertical_fov_degrees, 57.29578f, 1e-4);
  EXPECT_EQ(scene.camera.width, 64);
  EXPECT_EQ(scene.camera.height, 32);
  b.doc()["scenes"][0]["extras"] = {{"pmrender", {{"camera", "nobody"}}}};
  expect_error(b, "scenes[0].extras.pmrender.camera: no camera node named 'nobody' (camera nodes: nodes[1], side, front)");
  b.doc()["scenes"][0]["extras"] = {{"pmrender", {{"fps", 30}}}};
  expect_error(b, "scenes[0].extras.pmrender.fps: unknown key");
}

TEST_F(Gltf, NodeAnimationsBecomeTracksSampledAtEveryFrame) {
  GltfBuilder b;
  b.node({{"mesh", b.triangle_mesh()}});
  b.doc()["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.01}}}}};
  const int camera = b.node({{"camera", 0}, {"translation", {0, 0, 5}}});
  const int rig = b.node({{"translation", {0, 0, 0}}, {"children", json::array()}});
  b.doc()["extensionsUsed"] = {"KHR_lights_punctual"};
  b.doc()["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}, {"intensity", 1.0}}};
  b.doc()["nodes"].push_back({{"translation", {1, 0, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  b.doc()["nodes"][size_t(rig)]["children"].push_back(b.doc()["nodes"].size() - 1);
  const double s = std::sqrt(0.5);
  // The camera turns 90 degrees about +y over 1 s (slerp); it steps up by 1 at 0.5 s.
  b.animate(camera, "rotation", {0, 1}, {0, 0, 0, 1, 0, float(s), 0, float(s)});
  b.animate(camera, "translation", {0, 0.5f}, {0, 0, 5, 0, 1, 5}, "STEP");
  // The light's parent turns 180 degrees about +y over 2 s: the light circles the origin.
  b.animate(rig, "rotation", {0, 2}, {0, 0, 0, 1, 0, 1, 0, 0});
  b.doc()["scenes"][0]["extras"] = {{"pmrender", {{"frame_rate", 4}}}};
  Scene scene = load(b);
  ASSERT_TRUE(scene.animation.enabled);
  EXPECT_EQ(scene.animation.last_frame, 8);  // 2 s at 4 frames per second
  const CameraDesc c2 = camera_at_frame(scene, 2);  // 0.5 s: 45 degrees, stepped up
  EXPECT_EQ(c2.position.y, 1.0f);
  EXPECT_EQ(camera_at_frame(scene, 1).position.y, 0.0f);
  EXPECT_NEAR(c2.look_at.x - c2.position.x, -std::sqrt(0.5f), 1e-6);
  EXPECT_NEAR(c2.look_at.z - c2.position.z, -std::sqrt(0.5f), 1e-6);
  const CameraDesc c8 = camera_at_frame(scene, 8);
  EXPECT_NEAR(c8.look_at.x - c8.position.x, -1.0f, 1e-6);
  EXPECT_NEAR(lights_at_frame(scene, 4)[0].position.z, -1.0f, 1e-6);  // 90 degrees: (1,0,0) -> (0,0,-1)
  EXPECT_NEAR(lights_at_frame(scene, 8)[0].position.x, -1.0f, 1e-6);
  EXPECT_EQ(scene.lights[0].position.x, 1.0f);  // the static light is the first frame's

  b.doc()["scenes"][0]["extras"] = {{"pmrender", {{"frame_rate", 4}, {"frames", {2, 3}}}}};
  scene = load(b);
  EXPECT_EQ(scene.animation.first_frame, 2);
  EXPECT_EQ(scene.animation.last_frame, 3);
  EXPECT_EQ(scene.camera.position.y, 1.0f);  // frame 2's camera
}

TEST_F(Gltf, CubicSplineAnimationsAndAnimatedMeshes) {
  GltfBuilder b;
  const int mesh_node = b.node({{"mesh", b.triangle_mesh()}});
  b.add_camera_and_light();
  // Camera x: 0 -> 4 over 2 s, out-tangent 1 at the start, in-tangent 3 at the end.
  b.animate(1, "translation", {0, 2}, {0, 0, 0, 0, 0, 5, 1, 0, 0, 3, 0, 0, 4, 0, 5, 0, 0, 0}, "CUBICSPLINE");
  b.animate(mesh_node, "translation", {0, 1}, {0, 0, 0, 0, 0, 1});
  b.doc()["scenes"][0]["extras"] = {{"pmrender", {{"frame_rate", 2}}}};
  SceneLoadReport report;
  const Scene scene = load(b, &report);
  EXPECT_NEAR(camera_at_frame(scene, 2).position.x, 1.5f, 1e-6);  // as GltfAnimation.CubicSplineUsesTheTangents
  EXPECT_TRUE(has_warning(report, "meshes do not move"));
  EXPECT_EQ(scene.positions[0].z, 0.0f);  // the mesh stays at rest
}

TEST_F(Gltf, BinaryGlbLoadsLikeTheTextForm) {
  GltfBuilder b;
  b.node({{"mesh", b.triangle_mesh()}});
  b.add_camera_and_light({0, 1, 6});
  const Scene text = load(b);
  const Scene binary = load_scene_file(write("scene.GLB", b.glb()));
  ASSERT_EQ(binary.triangle_count(), 1u);
  EXPECT_TRUE(same(binary.positions[1], text.positions[1]));
  EXPECT_EQ(binary.camera.position.z, 6.0f);
  EXPECT_EQ(binary.name, "scene");
}

TEST_F(Gltf, ErrorsNameTheFileAndThePlace) {
  {
    const std::string missing = (dir_ / "missing.gltf").string();
    try {
      load_scene_file(missing);
      ADD_FAILURE() << "loaded a missing file";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(missing + ": cannot open (No such file"), std::string::npos) << e.what();
    }
    try {
      load_scene_file(write("broken.gltf", "{ \"asset\": "));
      ADD_FAILURE() << "loaded broken JSON";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("broken.gltf: glTF: "), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  }
  {
    GltfBuilder b;
    b.node({{"mesh", b.triangle_mesh({{"indices", b.accessor(std::vector<uint16_t>{0, 1, 7}, 5123, "SCALAR")}})}});
    b.add_camera_and_light();
    expect_error(b, "meshes[0].primitives[0].indices: index 7 at position 2 out of range (3 vertices)");
  }
  {
    GltfBuilder b;
    b.node({{"mesh", b.triangle_mesh({{"attributes", {{"POSITION", 42}}}})}});
    b.add_camera_and_light();
    expect_error(b, "meshes[0].primitives[0].attributes.POSITION: accessor 42 out of range");
  }
  {
    GltfBuilder b;
    b.node({{"mesh", b.triangle_mesh({{"indices", b.accessor(std::vector<int16_t>{0, 1, 2}, 5122, "SCALAR")}})}});
    b.add_camera_and_light();
    expect_error(b, "indices must be UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
  }
  {
    GltfBuilder b;
    b.node({{"mesh", b.triangle_mesh()}});
    expect_error(b, "cameras: the scene has no node with a perspective camera");
  }
  {
    GltfBuilder b;
    b.node({{"mesh", b.triangle_mesh()}});
    b.add_camera_and_light();
    b.doc()["extensions"]["KHR_lights_punctual"]["lights"][0]["type"] = "directional";
    expect_error(b, "extensions.KHR_lights_punctual: no light: no KHR_lights_punctual point or spot light with intensity "
                    "above zero and no emissive material");
  }
  {
    GltfBuilder b;
    b.node({{"mesh", b.triangle_mesh()}});
    b.add_camera_and_light();
    b.animate(1, "translation", {0, 1, 1}, {0, 0, 5, 0, 0, 6, 0, 0, 7});
    expect_error(b, "animations[0].samplers[0].input: key times must increase");
  }
  {
    GltfBuilder b;
    b.node({{"mesh", b.triangle_mesh()}});
    b.add_camera_and_light();
    b.doc()["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {1.5, 0, 0, 1}}}}}};
    b.doc()["meshes"][0]["primitives"][0]["material"] = 0;
    expect_error(b, "materials[0].pbrMetallicRoughness.baseColorFactor[0]: must be in [0, 1], got 1.5");
  }
  {
    GltfBuilder b;
    b.node({{"mesh", b.triangle_mesh()}});
    b.add_camera_and_light();
    b.doc()["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    b.doc()["extensionsUsed"].push_back("KHR_draco_mesh_compression");
    expect_error(b, "extensionsRequired: extension 'KHR_draco_mesh_compression' is required by the file but not supported");
  }
  {
    // A vertex 2e15 m out once its node is scaled: refused as OBJ and JSON positions are, where it
    // was once kept as long as it stayed within float range.
    GltfBuilder b;
    b.node({{"mesh", b.triangle_mesh()}, {"scale", {2e15, 2e15, 2e15}}});
    b.add_camera_and_light();
    expect_error(b, "meshes[0].primitives[0].attributes.POSITION: vertex 1 is 2e+15 m from the origin after its node "
                    "transform; at most 1e15 m renders");
  }
}

}  // namespace
}  // namespace pm

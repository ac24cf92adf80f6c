// Tests that bad OBJ and MTL content fails with a one-line pm::InputError naming the mesh (or
// MTL) file and the line (or material): out-of-range, zero and malformed indices, non-finite or
// missing vertex coordinates, short faces, unopenable mtllib files, bad MTL values, and
// tinyobjloader's own errors reported at the file's line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "render/errors.h"
#include "scene_io/scene_file.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

const char kScene[] = R"({
  "format": "pmrender-scene", "version": 1,
  "meshes": [ { "file": "mesh.obj" } ],
  "lights": [ { "position": [0, 2, 0], "power": [1, 1, 1] } ],
  "camera": { "position": [0, 0, -5], "look_at": [0, 0, 0] }
})";

// Eight cube corners; lines 1-8 of every test mesh.
const char kCubeVertices[] = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";

class SceneObjErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) / (std::string("pm_scene_obj_errors_") + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    scene_path_ = write("scene.json", kScene);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
  }

  // Writes mesh.obj and returns the InputError message of loading the scene.
  std::string error_with_mesh(const std::string& obj_text) {
    write("mesh.obj", obj_text);
    try {
      load_scene_file(scene_path_);
    } catch (const InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "the scene loaded without an InputError";
    return "";
  }

  // The message starts with the path of `file` and contains `expected` (which repeats the file
  // name, so the file and the line or field are checked together), on one line.
  void expect_message(const std::string& message, const std::string& file, const std::string& expected) {
    EXPECT_EQ(message.rfind((dir_ / file).string() + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(file + ": " + expected), std::string::npos)
        << "message: " << message << "\nexpected part: " << file << ": " << expected;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }

  fs::path dir_;
  std::string scene_path_;
};

TEST_F(SceneObjErrors, ValidCubeFaceLoads) {
  write("mesh.obj", std::string(kCubeVertices) + "f 1 2 3 4\n");
  EXPECT_EQ(load_scene_file(scene_path_).triangle_count(), 2u);
}

TEST_F(SceneObjErrors, FaceIndexBeyondTheVertexCount) {
  // tinyobjloader would pass a triangle's bad index through, or warn with the file's last line.
  const std::string obj = std::string(kCubeVertices) + "f 1 2 3\n# padding\nf 1 2 3\nf 1 99 3\nf 4 5 6\n";
  expect_message(error_with_mesh(obj), "mesh.obj", "line 12: face index 99 out of range (8 vertices)");
}

TEST_F(SceneObjErrors, NegativeFaceIndexReachingBeforeTheFirstVertex) {
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\nv 0 0 1\n";
  expect_message(error_with_mesh(obj), "mesh.obj",
                 "line 4: face index -4 out of range (3 vertices before this line)");
}

TEST_F(SceneObjErrors, ZeroFaceIndex) {
  expect_message(error_with_mesh(std::string(kCubeVertices) + "f 0 1 2\n"), "mesh.obj",
                 "line 9: face index 0 is invalid (OBJ indices start at 1)");
}

TEST_F(SceneObjErrors, MalformedFaceCorners) {
  expect_message(error_with_mesh(std::string(kCubeVertices) + "f 1 2 x\n"), "mesh.obj",
                 "line 9: face index 'x' is not an integer");
  expect_message(error_with_mesh(std::string(kCubeVertices) + "f 1 2 3/1/1/1\n"), "mesh.obj",
                 "line 9: face corner '3/1/1/1' is not of the form");
  expect_message(error_with_mesh(std::string(kCubeVertices) + "f 1 2 3 # note\n"), "mesh.obj",
                 "line 9: face index '#' is not an integer");
}

TEST_F(SceneObjErrors, MalformedTextureCoordinateIndexIsAnError) {
  const std::string obj = std::string(kCubeVertices) + "vt 0 0\nf 1/1 2/0 3/1\n";
  expect_message(error_with_mesh(obj), "mesh.obj", "line 10: face texture coordinate index 0 is invalid");
}

TEST_F(SceneObjErrors, OutOfRangeTextureCoordinateAndNormalIndicesAreOnlyWarnings) {
  // Nothing reads them, and converted scenes in the wild have one vt too few; a warning names
  // the first bad line and counts the rest.
  write("mesh.obj",
        std::string(kCubeVertices) + "vt 0 0\nvt 1 0\nvn 0 0 1\nf 1/1 2/2 3/5\nf 1//1 3//2 4//1\n");
  SceneLoadReport report;
  EXPECT_EQ(load_scene_file(scene_path_, &report).triangle_count(), 2u);
  ASSERT_EQ(report.warnings.size(), 1u);
  const std::string& warning = report.warnings[0];
  EXPECT_NE(
      warning.find("mesh.obj: line 12: face texture coordinate index 5 out of range (2 texture coordinates) "
                   "(and 1 more); ignored"),
      std::string::npos)
      << warning;
}

TEST_F(SceneObjErrors, FaceWithTwoCorners) {
  expect_message(error_with_mesh(std::string(kCubeVertices) + "f 1 2\n"), "mesh.obj",
                 "line 9: face has 2 corners (need at least 3)");
}

TEST_F(SceneObjErrors, LineElementIndicesAreCheckedToo) {
  expect_message(error_with_mesh(std::string(kCubeVertices) + "f 1 2 3\nl 1 0\n"), "mesh.obj",
                 "line 10: line element index 0 is invalid");
}

TEST_F(SceneObjErrors, NonFiniteVertexCoordinates) {
  // tinyobjloader would read nan/inf as 0 and 1e999 as inf; each is rejected at its line.
  for (const char* bad : {"nan", "inf", "-inf", "1e999", "1e39", "0x10"}) {
    SCOPED_TRACE(bad);
    const std::string obj = std::string("v 0 0 0\nv 1 ") + bad + " 0\nv 0 1 0\nf 1 2 3\n";
    expect_message(error_with_mesh(obj), "mesh.obj", std::string("line 2: vertex coordinate '") + bad + "'");
  }
}

TEST_F(SceneObjErrors, VertexWithTooFewCoordinates) {
  expect_message(error_with_mesh("v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n"), "mesh.obj",
                 "line 2: vertex has 2 coordinates (need x y z)");
}

TEST_F(SceneObjErrors, LineNumbersCountCrLfLinesOnce) {
  const std::string obj = "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\n\r\nf 1 2 7\r\n";
  expect_message(error_with_mesh(obj), "mesh.obj", "line 5: face index 7 out of range (3 vertices)");
}

TEST_F(SceneObjErrors, MtllibThatCannotBeOpened) {
  expect_message(error_with_mesh("mtllib missing.mtl\n" + std::string(kCubeVertices) + "f 1 2 3\n"),
                 "mesh.obj", "line 1: mtllib: cannot open 'missing.mtl'");
}

TEST_F(SceneObjErrors, UsemtlWithoutAName) {
  expect_message(error_with_mesh(std::string(kCubeVertices) + "usemtl\nf 1 2 3\n"), "mesh.obj",
                 "line 9: usemtl without a material name");
}

TEST_F(SceneObjErrors, UsemtlNotInTheMtlFile) {
  write("mesh.mtl", "newmtl red\nKd 1 0 0\n");
  const std::string obj =
      "mtllib mesh.mtl\n" + std::string(kCubeVertices) + "usemtl red\nf 1 2 3\nusemtl blue\nf 1 3 4\n";
  expect_message(error_with_mesh(obj), "mesh.obj", "line 12: usemtl 'blue': no such material");
}

TEST_F(SceneObjErrors, NegativeMtlReflectance) {
  write("mesh.mtl", "newmtl ok\nKd 0.5 0.5 0.5\n\nnewmtl odd\nKd 0.5 -0.2 0.5\n");
  const std::string obj = "mtllib mesh.mtl\n" + std::string(kCubeVertices) + "usemtl odd\nf 1 2 3\n";
  expect_message(error_with_mesh(obj), "mesh.mtl", "material 'odd': Kd[1] is negative");
}

TEST_F(SceneObjErrors, NonFiniteMtlExponent) {
  write("mesh.mtl", "newmtl shiny\nKd 0.5 0.5 0.5\nKs 0.2 0.2 0.2\nNs 1e999\n");
  const std::string obj = "mtllib mesh.mtl\n" + std::string(kCubeVertices) + "usemtl shiny\nf 1 2 3\n";
  expect_message(error_with_mesh(obj), "mesh.mtl", "material 'shiny': Ns is not a finite number");
}

TEST_F(SceneObjErrors, TinyobjloaderErrorsAreReportedAtTheFilesLine) {
  // A skin weight with a negative joint is one of tinyobjloader's own errors; the loader feeds it
  // one extra line, so this checks the line number is mapped back to the file's.
  const std::string obj = std::string(kCubeVertices) + "vw 1 -1 0.5\nf 1 2 3\n";
  expect_message(error_with_mesh(obj), "mesh.obj", "line 9: ");
}

}  // namespace
}  // namespace pm

// OBJ input at the edges: faces of 100,000 corners in linear time (convex ones fanned out, large
// non-convex ones refused), a UTF-8 byte order mark, coordinates too large for single-precision
// geometry, and meters_per_unit values that would collapse or overflow the scene.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "render/errors.h"
#include "scene_io/obj_large_faces.h"
#include "scene_io/obj_mesh.h"
#include "scene_io/scene_file.h"
#include "support/scene_load_error.h"
#include "support/test_folder.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

class ObjHostile : public test::FolderTest {
 protected:
  ObjHostile() : FolderTest("pm_obj_hostile_") {}
  std::string scene(const std::string& extra = "") {
    return write("scene.json", R"({"format": "pmrender-scene", "version": 1, "meshes": [{"file": "mesh.obj"}],)" + extra +
                                   R"( "lights": [{"position": [0, 2, 0], "power": [1, 1, 1]}],
      "camera": {"position": [0, 0.5, -5], "look_at": [0, 0, 0]}})");
  }
  static std::string error_of(const std::string& path) { return test::scene_load_error(path); }
  // A polygon of n corners on the unit circle in the y = 0 plane; every other corner pulled in to
  // radius `inner` (1: convex).
  static std::string circle_face(size_t n, double inner = 1) {
    std::string text;
    char line[96];
    for (size_t i = 0; i < n; ++i) {
      const double a = 2 * M_PI * double(i) / double(n), r = (i % 2 && inner != 1) ? inner : 1;
      std::snprintf(line, sizeof(line), "v %.9f 0 %.9f\n", r * std::cos(a), r * std::sin(a));
      text += line;
    }
    text += "f";
    for (size_t i = 1; i <= n; ++i) text += " " + std::to_string(i);
    return text + "\n";
  }
  static double area(const ObjMesh& mesh) {
    double total = 0;
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
      const Float3& a = mesh.positions[mesh.indices[3 * t]];
      const Float3& b = mesh.positions[mesh.indices[3 * t + 1]];
      const Float3& c = mesh.positions[mesh.indices[3 * t + 2]];
      // The y = 0 plane: the cross product's y component is the (unsigned) doubled area.
      total += std::fabs(double(b.z - a.z) * (c.x - a.x) - double(b.x - a.x) * (c.z - a.z)) / 2;
    }
    return total;
  }
};

TEST_F(ObjHostile, AConvexFaceOfAHundredThousandCornersLoadsInLinearTime) {
  const size_t n = 100000;
  const std::string path = write("mesh.obj", "usemtl first\n" + circle_face(n));
  const auto start = std::chrono::steady_clock::now();
  const ObjMesh mesh = load_obj_mesh(path, false);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 3.0);  // quadratic ear clipping took 22 s
  // A fan of n - 2 triangles (thin ones near the first corner may drop as degenerate) covering
  // the polygon: area n/2 sin(2 pi / n), within float rounding.
  EXPECT_GT(mesh.triangle_count(), n - 2 - 100);
  EXPECT_LE(mesh.triangle_count(), n - 2);
  EXPECT_NEAR(area(mesh), 0.5 * double(n) * std::sin(2 * M_PI / double(n)), 1e-4);
  for (int32_t usemtl : mesh.triangle_usemtl) ASSERT_EQ(usemtl, 0);
}

TEST_F(ObjHostile, SmallAndModerateNonConvexFacesAreStillTriangulatedExactly) {
  // A 100-corner star (non-convex): tinyobjloader's ear clipping, area of the star.
  const size_t n = 100;
  const ObjMesh mesh = load_obj_mesh(write("mesh.obj", circle_face(n, 0.5)), false);
  double expected = 0;  // n triangles (centre, corner i, corner i+1), each of radii 1 and 0.5
  expected = double(n) * 0.5 * 1.0 * 0.5 * std::sin(2 * M_PI / double(n));
  EXPECT_EQ(mesh.triangle_count(), n - 2);
  EXPECT_NEAR(area(mesh), expected, 1e-4);
}

TEST_F(ObjHostile, ALargeNonConvexFaceIsRefusedWithItsLine) {
  write("mesh.obj", "# star\n" + circle_face(5000, 0.5));
  const std::string message = error_of(scene());
  EXPECT_NE(message.find("mesh.obj: line 5002: face of 5000 corners is not convex; faces of more than 2048 corners must be convex"),
            std::string::npos) << message;
}

TEST(ObjLargeFaces, ConvexityIsJudgedInTheFacesPlaneAndByItsWinding) {
  // A tilted plane (x + y + z = 1) so no coordinate axis is special.
  auto on_plane = [](double u, double v) { return std::array<double, 3>{u, v, 1 - u - v}; };
  const std::vector<std::array<double, 3>> p = {on_plane(0, 0), on_plane(1, 0), on_plane(1, 1), on_plane(0, 1),
                                                on_plane(0.5, 0.5), on_plane(0.5, 0), on_plane(2, 2)};
  EXPECT_TRUE(is_convex_polygon(p, {0, 1, 2, 3}));
  EXPECT_TRUE(is_convex_polygon(p, {3, 2, 1, 0}));        // either orientation
  EXPECT_TRUE(is_convex_polygon(p, {0, 5, 1, 2, 3}));     // a collinear corner
  EXPECT_FALSE(is_convex_polygon(p, {0, 1, 4, 2, 3}));    // a reflex corner (the dent at the centre)
  EXPECT_TRUE(is_convex_polygon(p, {0, 4, 6}));           // no area: a line
  // A pentagram turns left at every corner but winds around twice.
  std::vector<std::array<double, 3>> star;
  for (int i = 0; i < 5; ++i) star.push_back(on_plane(std::cos(4 * M_PI * i / 5), std::sin(4 * M_PI * i / 5)));
  EXPECT_FALSE(is_convex_polygon(star, {0, 1, 2, 3, 4}));
}

TEST_F(ObjHostile, AByteOrderMarkDoesNotHideTheFirstLine) {
  const ObjMesh mesh = load_obj_mesh(write("mesh.obj", "\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n"), false);
  EXPECT_EQ(mesh.positions.size(), 3u);
  EXPECT_EQ(mesh.triangle_count(), 1u);
  // In the MTL file too: the first newmtl used to be lost.
  write("mesh.mtl", "\xEF\xBB\xBFnewmtl red\nKd 0.8 0.1 0.1\n");
  const std::string path = write("with_mtl.obj", "mtllib mesh.mtl\nv 0 0 0\nv 1 0 0\nv 0 0 1\nusemtl red\nf 1 2 3\n");
  const ObjMesh with_mtl = load_obj_mesh(path, true);
  ASSERT_EQ(with_mtl.mtl_materials.count("red"), 1u);
  EXPECT_FLOAT_EQ(with_mtl.mtl_materials.at("red").kd[0], 0.8f);
}

TEST_F(ObjHostile, CoordinatesTooLargeToRenderAreRefusedNotCalledDegenerate) {
  write("mesh.obj", "v -1e38 0 -1e38\nv 1e38 0 -1e38\nv 1e38 0 1e38\nf 1 3 2\n");
  const std::string message = error_of(scene());
  EXPECT_NE(message.find("mesh.obj: line 1: vertex coordinate '-1e38' is too large to render"), std::string::npos)
      << message;
}

TEST_F(ObjHostile, MetersPerUnitOutsideNanometresToGigametresIsBlamedOnItself) {
  write("mesh.obj", "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nf 1 3 2\n");
  for (const char* value : {"1e-300", "1e300", "1e-10", "2e9"}) {
    const std::string message = error_of(scene(std::string(R"( "meters_per_unit": )") + value + ","));
    EXPECT_NE(message.find("scene.json: meters_per_unit: must be from 1e-9 to 1e9"), std::string::npos)
        << value << ": " << message;
  }
  // In range, but the product leaves the renderable range: named on the converted field.
  write("mesh.obj", "v -1e12 0 -1e12\nv 1e12 0 -1e12\nv 1e12 0 1e12\nf 1 3 2\n");
  const std::string message = error_of(scene(R"( "meters_per_unit": 1e6,)"));
  EXPECT_NE(message.find("meshes[0].file: a position is"), std::string::npos) << message;
  EXPECT_NE(message.find("at most 1e15 m renders"), std::string::npos) << message;
}

}  // namespace
}  // namespace pm

// Tests the built-in Cornell box: triangle count, that every normal faces into the room or out
// of its block (checked against geometry built here independently of the winding), wall colours,
// the point light under the ceiling, its power ratios, and the reference camera.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "scene_io/cornell_box.h"

namespace pm {
namespace {

struct Vec {
  double x, y, z;
};
Vec operator-(Vec a, Vec b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec operator+(Vec a, Vec b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec operator*(Vec a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(Vec a, Vec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec cross(Vec a, Vec b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
Vec from_mm(double x, double y, double z) { return {x * 1e-3, y * 1e-3, z * 1e-3}; }
Vec to_vec(const Float3& f) { return {f.x, f.y, f.z}; }

// A plane through three published corners; "inside" is the side the room centre is on. Built
// from the data, not from the scene's triangles, so it does not trust the winding under test.
struct WallPlane {
  Vec point, normal;
  bool room_side(Vec p, Vec room_centre) const {
    return (dot(normal, p - point) > 0) == (dot(normal, room_centre - point) > 0);
  }
};

struct Block {
  std::vector<Vec> top;  // four corners, y = top height
  double height;
  // Inside when between floor and top and on the centroid's side of every edge (convex top).
  bool contains(Vec p) const {
    if (p.y <= 0 || p.y >= height) return false;
    Vec centre{0, 0, 0};
    for (const Vec& c : top) centre = centre + c * 0.25;
    for (size_t i = 0; i < 4; ++i) {
      Vec a = top[i], b = top[(i + 1) % 4];
      double side_p = (b.x - a.x) * (p.z - a.z) - (b.z - a.z) * (p.x - a.x);
      double side_c = (b.x - a.x) * (centre.z - a.z) - (b.z - a.z) * (centre.x - a.x);
      if ((side_p > 0) != (side_c > 0)) return false;
    }
    return true;
  }
};

class CornellBoxTest : public ::testing::Test {
 protected:
  CornellBoxTest() : scene_(builtin_cornell_box()) {
    auto plane = [](Vec a, Vec b, Vec c) { return WallPlane{a, cross(b - a, c - a)}; };
    walls_ = {plane(from_mm(552.8, 0, 0), from_mm(0, 0, 0), from_mm(0, 0, 559.2)),              // floor
              plane(from_mm(556, 548.8, 0), from_mm(556, 548.8, 559.2), from_mm(0, 548.8, 0)),  // ceiling
              plane(from_mm(549.6, 0, 559.2), from_mm(0, 0, 559.2), from_mm(0, 548.8, 559.2)),  // back
              plane(from_mm(0, 0, 559.2), from_mm(0, 0, 0), from_mm(0, 548.8, 0)),              // green
              plane(from_mm(552.8, 0, 0), from_mm(549.6, 0, 559.2), from_mm(556, 548.8, 0))};   // red
    blocks_ = {
        {{from_mm(130, 165, 65), from_mm(82, 165, 225), from_mm(240, 165, 272), from_mm(290, 165, 114)},
         0.165},
        {{from_mm(423, 330, 247), from_mm(265, 330, 296), from_mm(314, 330, 456), from_mm(472, 330, 406)},
         0.330}};
  }

  // Empty space: inside the room (the open front z < 0 counts as outside) and in no block.
  bool in_free_space(Vec p) const {
    const Vec room_centre = from_mm(278, 274, 280);
    for (const WallPlane& wall : walls_) {
      if (!wall.room_side(p, room_centre)) return false;
    }
    for (const Block& block : blocks_) {
      if (block.contains(p)) return false;
    }
    return p.z > 0;
  }

  Vec corner(size_t triangle, int k) const {
    return to_vec(scene_.positions[scene_.indices[3 * triangle + k]]);
  }
  Vec centroid(size_t t) const { return (corner(t, 0) + corner(t, 1) + corner(t, 2)) * (1.0 / 3.0); }
  Vec unit_normal(size_t t) const {
    Vec n = cross(corner(t, 1) - corner(t, 0), corner(t, 2) - corner(t, 0));
    return n * (1.0 / std::sqrt(dot(n, n)));
  }
  const std::string& material_name(size_t t) const {
    return scene_.materials[scene_.triangle_material[t]].name;
  }

  Scene scene_;
  std::vector<WallPlane> walls_;
  std::vector<Block> blocks_;
};

TEST_F(CornellBoxTest, NameSourceAndCounts) {
  EXPECT_EQ(scene_.name, "cornell-box");
  EXPECT_EQ(scene_.source, "builtin:cornell-box");
  // 5 walls x 2 triangles + 2 blocks x 5 faces x 2 triangles = 10 + 20.
  EXPECT_EQ(scene_.triangle_count(), 30u);
  EXPECT_EQ(scene_.indices.size(), 90u);
  EXPECT_EQ(scene_.triangle_material.size(), 30u);
  for (uint32_t index : scene_.indices) EXPECT_LT(index, scene_.positions.size());
  for (uint32_t material : scene_.triangle_material) EXPECT_LT(material, scene_.materials.size());
  ASSERT_EQ(scene_.lights.size(), 1u);
}

TEST_F(CornellBoxTest, EveryNormalFacesFreeSpace) {
  // Probe points 5 mm either side of the surface over a grid on each triangle. Where exactly one
  // side is empty space (inside the room, outside the blocks), it must be the side the normal
  // points to. Where both or neither are (floor under a block), the sample decides nothing.
  // 5 mm clears the red wall, whose published corners are up to 3.2 mm off one plane.
  const double probe = 5e-3;
  const int grid = 6;
  for (size_t t = 0; t < scene_.triangle_count(); ++t) {
    SCOPED_TRACE("triangle " + std::to_string(t));
    const Vec a = corner(t, 0), ab = corner(t, 1) - a, ac = corner(t, 2) - a;
    const Vec n = unit_normal(t);
    int decisive = 0, facing_away = 0;
    for (int i = 0; i < grid; ++i) {
      for (int j = 0; i + j < grid - 1; ++j) {
        const Vec p = a + ab * ((i + 0.5) / grid) + ac * ((j + 0.5) / grid);
        const bool front_free = in_free_space(p + n * probe);
        const bool back_free = in_free_space(p - n * probe);
        if (front_free == back_free) continue;
        ++decisive;
        if (back_free) ++facing_away;
      }
    }
    EXPECT_GT(decisive, 0);
    EXPECT_EQ(facing_away, 0);
  }
}

TEST_F(CornellBoxTest, GeometryIsInMetres) {
  double max_coordinate = 0;
  for (const Float3& p : scene_.positions)
    max_coordinate = std::max({max_coordinate, double(p.x), double(p.y), double(p.z)});
  EXPECT_NEAR(max_coordinate, 0.5592, 1e-6);  // back wall z = 559.2 mm
}

TEST_F(CornellBoxTest, WallColoursAndWhiteBlocks) {
  for (size_t t = 0; t < scene_.triangle_count(); ++t) {
    SCOPED_TRACE("triangle " + std::to_string(t));
    const Vec c = centroid(t);
    if (c.x < 1e-6) {
      EXPECT_EQ(material_name(t), "green");
    } else if (c.x > 0.549) {
      EXPECT_EQ(material_name(t), "red");
    } else {
      EXPECT_EQ(material_name(t), "white");
    }
  }
  for (const MaterialDesc& m : scene_.materials) {
    SCOPED_TRACE(m.name);
    EXPECT_EQ(m.glossy.x + m.glossy.y + m.glossy.z + m.mirror.x + m.mirror.y + m.mirror.z, 0.0f);
    if (m.name == "red") {
      EXPECT_FLOAT_EQ(m.diffuse.x, 0.5761f);
      EXPECT_FLOAT_EQ(m.diffuse.y, 0.0832f);
      EXPECT_FLOAT_EQ(m.diffuse.z, 0.0562f);
    }
    if (m.name == "green") {
      EXPECT_FLOAT_EQ(m.diffuse.y, 0.3508f);
    }
    if (m.name == "white") {
      EXPECT_FLOAT_EQ(m.diffuse.x, 0.7339f);
    }
  }
}

TEST_F(CornellBoxTest, LightHangsJustUnderTheCeilingWithTheWarmSpectrum) {
  const LightDesc& light = scene_.lights[0];
  EXPECT_NEAR(light.position.x, 0.278, 1e-6);
  EXPECT_NEAR(light.position.y, 0.5388, 1e-6);
  EXPECT_NEAR(light.position.z, 0.2796, 1e-6);
  EXPECT_LT(light.position.y, 0.5488f);
  EXPECT_TRUE(in_free_space(to_vec(light.position)));
  // Band averages of the emission spectrum: 17.0 / 11.8 / 4.0, green normalised to 3 W.
  EXPECT_FLOAT_EQ(light.power.y, 3.0f);
  EXPECT_NEAR(light.power.x, 3.0 * 17.0 / 11.8, 1e-5);
  EXPECT_NEAR(light.power.z, 3.0 * 4.0 / 11.8, 1e-5);
}

TEST_F(CornellBoxTest, ReferenceCamera) {
  const CameraDesc& camera = scene_.camera;
  EXPECT_NEAR(camera.position.x, 0.278, 1e-6);
  EXPECT_NEAR(camera.position.y, 0.273, 1e-6);
  EXPECT_NEAR(camera.position.z, -0.8, 1e-6);
  EXPECT_NEAR(camera.look_at.z - camera.position.z, 0.001, 1e-6);  // looking down +z
  EXPECT_EQ(camera.look_at.x, camera.position.x);
  EXPECT_EQ(camera.look_at.y, camera.position.y);
  EXPECT_EQ(camera.up.y, 1.0f);
  EXPECT_FLOAT_EQ(camera.vertical_fov_degrees, 39.3077f);
  EXPECT_EQ(camera.width, 512);
  EXPECT_EQ(camera.height, 512);
}

}  // namespace
}  // namespace pm

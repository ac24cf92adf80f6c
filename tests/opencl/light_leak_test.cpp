// Light must not leak through closed zero-thickness geometry: a point light inside a closed box
// leaves its outside black, and a camera inside a closed box lit from outside sees black. Photon
// footprints near a box's edges would otherwise reach across them: along the floor under a wall,
// or around an edge onto the other side of the adjoining wall (kernels/common/footprint_clip.h
// clips footprints against blocking geometry; kernels/common/gather_reach.h accepts a photon only
// on a surface that faces like the one it hit). For every estimator: the radius and knn photons
// get the same clipped reach.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>

#include "support/render_settings.h"
#include "support/device_checks.h"
#include "support/room_scenes.h"
#include "support/still_render.h"

namespace pm {
namespace {

Device& device() { return test::shared_opencl_device(); }

// A closed white 10 x 4 x 10 m room (floor y = 0) and a closed white 1 m box standing on its floor
// at the origin: with `bottom`, the box has its own bottom face on the floor's plane; without,
// the floor closes it.
Scene box_on_floor(bool bottom) {
  Scene s;
  s.name = "box on a floor";
  s.source = "test";
  s.materials = {test::diffuse_material("white", {0.75f, 0.75f, 0.75f})};
  test::add_box(s, {-5, 0, -5}, {5, 4, 5});
  test::add_box(s, {-0.5f, 0, -0.5f}, {0.5f, 1, 0.5f}, 0, bottom);
  return s;
}

struct Estimator {
  const char* name;
  int id;
};
const Estimator kEstimators[] = {{"pd", PM_ESTIMATOR_PD}, {"radius", PM_ESTIMATOR_RADIUS}, {"knn", PM_ESTIMATOR_KNN}};

RenderSettings settings_for(int estimator, bool clip = true) {
  PhotonSettings photons;
  photons.photons = 20000;
  photons.estimator = estimator;
  photons.footprint_clip = clip;
  return test::photon_render_settings(photons);
}

double lit_fraction(const test::StillRender& r, const std::string& layer) {
  return 1.0 - test::black_fraction(r.image, layer);
}

TEST(LightLeaks, ALightInsideAClosedBoxLeavesItsOutsideBlack) {
  for (bool bottom : {false, true}) {
    Scene s = box_on_floor(bottom);
    s.lights = {LightDesc{"inside", {0.1f, 0.5f, -0.1f}, {20, 20, 20}}};
    s.camera.position = {2.2f, 1.8f, -3.0f};
    s.camera.look_at = {0, 0.4f, 0};
    s.camera.vertical_fov_degrees = 40;
    for (const Estimator& e : kEstimators) {
      const test::StillRender r = test::render_still(device(), s, settings_for(e.id), 48, 48);
      ASSERT_GT(r.stats.method.get("hits"), 5000.0);
      const double lit = lit_fraction(r, ""), indirect = lit_fraction(r, "indirect");
      std::printf("light in a box%s, %-6s: %5.2f %% of the pixels lit (indirect %5.2f %%)\n",
                  bottom ? " with a bottom" : " closed by the floor", e.name, 100.0 * lit, 100.0 * indirect);
      EXPECT_EQ(test::layer_mean(r.image, "direct"), 0.0);
      EXPECT_EQ(lit, 0.0) << e.name << (bottom ? ", box with a bottom" : ", box closed by the floor");
    }
  }
}

TEST(LightLeaks, ACameraInsideAClosedBoxSeesBlack) {
  for (bool bottom : {false, true}) {
    Scene s = box_on_floor(bottom);
    s.lights = {LightDesc{"outside", {0.3f, 2.5f, 0.6f}, {40, 40, 40}}};
    s.camera.position = {0.3f, 0.3f, 0.3f};
    s.camera.look_at = {-0.5f, 0.8f, -0.5f};  // up into a corner: two top edges and a side edge
    s.camera.vertical_fov_degrees = 90;
    for (const Estimator& e : kEstimators) {
      const test::StillRender r = test::render_still(device(), s, settings_for(e.id), 48, 48);
      ASSERT_GT(r.stats.method.get("hits"), 5000.0);
      const double lit = lit_fraction(r, "");
      std::printf("camera in a box%s, %-6s: %5.2f %% of the pixels lit\n",
                  bottom ? " with a bottom" : " closed by the floor", e.name, 100.0 * lit);
      EXPECT_EQ(lit, 0.0) << e.name << (bottom ? ", box with a bottom" : ", box closed by the floor");
    }
  }
}

// --footprint-clip off: the paper's whole ellipses reach along the floor under the box's walls,
// so the light inside lights the floor outside (what the clipping above prevents).
TEST(LightLeaks, UnclippedFootprintsLeakUnderTheWalls) {
  Scene s = box_on_floor(false);
  s.lights = {LightDesc{"inside", {0.1f, 0.5f, -0.1f}, {20, 20, 20}}};
  s.camera.position = {2.2f, 1.8f, -3.0f};
  s.camera.look_at = {0, 0.4f, 0};
  s.camera.vertical_fov_degrees = 40;
  const test::StillRender r = test::render_still(device(), s, settings_for(PM_ESTIMATOR_PD, false), 48, 48);
  const double lit = lit_fraction(r, "indirect");
  std::printf("light in a box closed by the floor, pd, unclipped: %5.2f %% of the pixels lit\n", 100.0 * lit);
  EXPECT_GT(lit, 0.01);
}

}  // namespace
}  // namespace pm

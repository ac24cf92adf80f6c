// A scene's physical size must not change its image: the same room scaled by k (lights' power by
// k^2, so every radiance stays the same) renders the same at default settings from 1e-4 to 1e6
// (footprint size chosen per batch, render/footprint_scale.h), and secondary rays leave surfaces
// cleanly wherever they lie: on the coordinate planes of a large scene, and a few micrometres from
// a light in a tiny one (offsets relative to the hit and the scene, kernels/common/ray.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "render/image_metrics.h"
#include "support/render_settings.h"
#include "support/device_checks.h"
#include "support/room_scenes.h"
#include "support/still_render.h"

namespace pm {
namespace {

Device& device() { return test::shared_opencl_device(); }

// The tightest golden tolerance (golden/README.md): mean HDR-FLIP at 67 pixels per degree.
constexpr double kSameImage = 0.042;

double mean_flip(const FrameImage& reference, const FrameImage& test, const std::string& layer = "") {
  return compare_images(reference.find(layer)->rgb, test.find(layer)->rgb, reference.width, reference.height).flip;
}

// Pixels lit in the reference but black in the test, as a fraction of the pixels lit in the
// reference (shadow acne when the layer is the direct light).
double lost_fraction(const FrameImage& reference, const FrameImage& test, const std::string& layer) {
  const std::vector<float>& a = reference.find(layer)->rgb;
  const std::vector<float>& b = test.find(layer)->rgb;
  size_t lit = 0, lost = 0;
  for (size_t i = 0; i + 2 < a.size(); i += 3) {
    if (a[i] + a[i + 1] + a[i + 2] <= 0.0f) continue;
    ++lit;
    lost += b[i] + b[i + 1] + b[i + 2] <= 0.0f;
  }
  return lit ? double(lost) / double(lit) : 0.0;
}

TEST(SceneScale, TheSameRoomAtEveryScaleGivesTheSameImage) {
  const Scene base = test::closed_room();
  PhotonSettings photons;  // defaults, but for the photon count: seconds on PoCL
  photons.photons = 50000;
  const RenderSettings settings = test::photon_render_settings(photons);
  const test::StillRender reference = test::render_still(device(), base, settings, 48, 48);
  const double indirect1 = test::layer_mean(reference.image, "indirect");
  ASSERT_GT(indirect1, 0.0);
  EXPECT_EQ(test::black_fraction(reference.image, "indirect"), 0.0) << "scale 1";
  for (double k : {1e-4, 1e-2, 1e2, 1e4, 1e6}) {
    const test::StillRender r = test::render_still(device(), test::scaled(base, k), settings, 48, 48);
    const double zero_indirect = test::black_fraction(r.image, "indirect");
    const double flip = mean_flip(reference.image, r.image);
    const double indirect = test::layer_mean(r.image, "indirect") / indirect1;
    std::printf("scale %-6g zero-indirect pixels %5.1f %%  indirect x%.4f  mean HDR-FLIP %.4f\n", k,
                100.0 * zero_indirect, indirect, flip);
    EXPECT_EQ(zero_indirect, 0.0) << "scale " << k;
    EXPECT_LE(flip, kSameImage) << "scale " << k;
    EXPECT_NEAR(indirect, 1.0, 0.02) << "scale " << k;
  }
}

TEST(SceneScale, NoShadowAcneOnTheCoordinatePlanes) {
  // The room's floor and two walls lie on x = 0, y = 0 and z = 0; moved away from the origin, the
  // same room is the reference. Direct light only.
  RenderSettings settings;  // no indirect-light method: direct light only
  for (double k : {1.0, 1e3}) {
    const Scene at_origin = test::scaled(test::closed_room(), k);
    const Scene moved = test::translated(at_origin, {float(7 * k), float(3 * k), float(11 * k)});
    const test::StillRender a = test::render_still(device(), at_origin, settings, 64, 64);
    const test::StillRender b = test::render_still(device(), moved, settings, 64, 64);
    const double acne = lost_fraction(b.image, a.image, "direct");
    const double ratio = test::layer_mean(a.image, "direct") / test::layer_mean(b.image, "direct");
    std::printf("scale %-6g direct-light pixels black at the origin but lit when moved: %5.2f %%, direct x%.4f\n", k,
                100.0 * acne, ratio);
    EXPECT_LE(acne, 0.002) << "scale " << k;
    EXPECT_NEAR(ratio, 1.0, 0.01) << "scale " << k;
  }
}

TEST(SceneScale, LightMicrometresUnderTheCeilingKeepsItsHotspot) {
  // Scale 1e-4: the light hangs 20 micrometres under the ceiling (0.2 m in the unscaled room).
  // Looking up at the ceiling above it, the direct light must match the unscaled render.
  Scene room = test::closed_room();
  room.lights[0].position.y = 2.3f;
  room.camera.position = {2.0f, 1.0f, 4.5f};
  room.camera.look_at = {2.0f, 2.5f, 2.5f};
  RenderSettings settings;  // no indirect-light method: direct light only
  const test::StillRender unscaled = test::render_still(device(), room, settings, 64, 64);
  const test::StillRender tiny = test::render_still(device(), test::scaled(room, 1e-4), settings, 64, 64);
  const double ratio = test::layer_mean(tiny.image, "direct") / test::layer_mean(unscaled.image, "direct");
  const double flip = mean_flip(unscaled.image, tiny.image, "direct");
  std::printf("light 20 um under the ceiling at scale 1e-4: direct x%.4f, mean HDR-FLIP %.4f\n", ratio, flip);
  EXPECT_NEAR(ratio, 1.0, 0.01);
  EXPECT_LE(flip, kSameImage);
}

}  // namespace
}  // namespace pm

// The renderer's film on the host (render/renderer_film.cpp), on the OpenCL backend: its last
// guard, which repairs a pixel whose sums are not finite black in every layer and counts it, and a
// film without mirrors, which keeps no caustic sum and refuses sums that carry caustic light.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "render/errors.h"
#include "render/renderer.h"
#include "scene_io/cornell_box.h"
#include "support/device_checks.h"
#include "support/render_settings.h"

namespace pm {
namespace {

Device& device() { return test::shared_opencl_device(); }

// An 8 x 8 photon render of 20,000 photons: films small enough to fill by hand.
RenderSettings film_test_settings() {
  PhotonSettings p;
  p.photons = 20000;
  RenderSettings settings = test::photon_render_settings(p, 1);
  settings.width = settings.height = 8;
  return settings;
}

// The film's last guard: a pixel whose sums are not finite comes out black in every layer and
// counted, the other pixels resolved as sums over passes (the host resolves the film when it reads
// it back: Renderer::read_image, film.h).
TEST(RendererFilm, ANonFiniteFilmSumIsRepairedBlackInEveryLayer) {
  RenderSettings settings = film_test_settings();
  // A mirror in the green wall gives the film a caustic sum (only mirrors make caustics, film.h).
  Scene scene = builtin_cornell_box();  // the renderer reads it for as long as it lives
  scene.materials.back().mirror = {0.5f, 0.5f, 0.5f};
  Renderer renderer(device(), scene, settings);
  ASSERT_TRUE(renderer.has_caustic_film());
  renderer.render_frame(0);
  FilmSums sums = renderer.film_sums();
  ASSERT_EQ(sums.indirect.size(), 64u);
  for (size_t i = 0; i < sums.indirect.size(); ++i) {
    sums.indirect[i] = float4{0.5f, 0.25f, 1.0f, 0.0f};
    sums.caustic[i] = float4{0.125f, 0.0f, 0.0f, 0.0f};
  }
  sums.indirect[9].y = std::nanf("");
  sums.caustic[20].z = INFINITY;
  sums.passes = 2;
  sums.odd_passes = 1;
  renderer.set_film_sums(sums);
  renderer.wait();
  FrameStats stats;
  const FrameImage image = renderer.read_image(&stats);
  EXPECT_EQ(stats.repaired_pixels, 2);
  for (const char* name : {"", "direct", "indirect", "caustic"}) {
    const ImageLayer* layer = image.find(name);
    ASSERT_NE(layer, nullptr) << name;
    for (size_t px : {size_t(9), size_t(20)})
      for (int c = 0; c < 3; ++c) EXPECT_EQ(layer->rgb[3 * px + c], 0.0f) << "layer '" << name << "' pixel " << px;
  }
  const ImageLayer* indirect = image.find("indirect");
  const ImageLayer* caustic = image.find("caustic");
  EXPECT_EQ(indirect->rgb[3 * 10 + 0], 0.25f);  // the sums over 2 passes
  EXPECT_EQ(indirect->rgb[3 * 10 + 2], 0.5f);
  EXPECT_EQ(caustic->rgb[3 * 10 + 0], 0.0625f);
}

// A scene without mirrors makes no caustics: its film keeps no caustic sum, still writes the
// caustic layer (zero), and refuses film sums that carry caustic light (a checkpoint of another
// scene) before it changes anything.
TEST(RendererFilm, AFilmWithoutMirrorsKeepsNoCausticSumAndRefusesCausticLight) {
  RenderSettings settings = film_test_settings();
  const Scene scene = builtin_cornell_box();  // the renderer reads it for as long as it lives
  Renderer renderer(device(), scene, settings);
  EXPECT_FALSE(renderer.has_caustic_film());
  const FrameImage first = renderer.render_frame(0);
  const ImageLayer* caustic = first.find("caustic");
  ASSERT_NE(caustic, nullptr);
  EXPECT_TRUE(std::all_of(caustic->rgb.begin(), caustic->rgb.end(), [](float v) { return v == 0.0f; }));
  FilmSums sums = renderer.film_sums();
  sums.caustic[5].y = 0.5f;
  EXPECT_THROW(renderer.set_film_sums(sums), DeviceError);
  const FrameImage again = renderer.read_image();
  for (const char* name : {"", "direct", "indirect"})
    EXPECT_EQ(first.find(name)->rgb, again.find(name)->rgb) << "layer '" << name << "'";
}

}  // namespace
}  // namespace pm

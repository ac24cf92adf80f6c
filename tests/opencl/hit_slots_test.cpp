// Hit records sized by what the scene's materials allow (render/photon/photon_settings.h): a photon
// records a hit after each bounce, so without mirror reflectance `bounces` records per photon hold
// every hit, and mirrors add two. Proved by rendering the built-in Cornell box (no mirrors) and the
// same box with a mirror reflectance of 1e-7 on every material, which no photon of the seed
// chooses: the second reserves two more records per photon, and both must record the same hits
// and give the same image, bit for bit (fixed smoothing: no reduction over the record layout).
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <stdexcept>

#include "render/renderer.h"
#include "scene_io/cornell_box.h"
#include "support/device_checks.h"
#include "support/render_settings.h"

namespace pm {
namespace {

struct Rendered {
  FrameImage image;
  double hits = 0;
  uint64_t peak_bytes = 0;
};

Rendered render(const Scene& scene) {
  std::unique_ptr<Device> device = test::open_first_device("opencl");
  if (!device) throw std::runtime_error("no OpenCL device");
  PhotonSettings photons;
  photons.photons = 65536;
  photons.bounces = 2;
  photons.smoothing = 8;
  RenderSettings settings = test::photon_render_settings(photons);
  settings.width = settings.height = 48;
  settings.mirror_depth = 0;  // the camera follows no mirror, so the tiny one changes no shading point
  Rendered r;
  {
    Renderer renderer(*device, scene, settings);
    FrameStats stats;
    r.image = renderer.render_frame(0, &stats);
    r.hits = stats.method.get("hits");
  }
  r.peak_bytes = device->peak_allocated_bytes();
  return r;
}

TEST(HitSlots, AMirrorFreeSceneLosesNoHitInBounceManyRecords) {
  const Scene plain = builtin_cornell_box();
  Scene with_mirror = plain;
  for (MaterialDesc& m : with_mirror.materials) m.mirror = {1e-7f, 1e-7f, 1e-7f};
  const Rendered a = render(plain), b = render(with_mirror);
  EXPECT_GT(a.hits, 20000.0);
  EXPECT_EQ(a.hits, b.hits) << "two records per photon fewer, and no hit lost";
  for (const char* layer : {"indirect", "caustic", ""}) {
    const std::vector<float>& x = a.image.find(layer)->rgb;
    const std::vector<float>& y = b.image.find(layer)->rgb;
    ASSERT_EQ(x.size(), y.size());
    EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(float)), 0) << "layer '" << layer << "'";
  }
  // Six float4 per record: 96 bytes for each of the two records per photon not reserved.
  EXPECT_GE(b.peak_bytes, a.peak_bytes + uint64_t(65536) * 2 * 96);
  std::printf("peak device memory: %.1f MiB without mirrors, %.1f MiB with\n", a.peak_bytes / 1048576.0,
              b.peak_bytes / 1048576.0);
}

}  // namespace
}  // namespace pm

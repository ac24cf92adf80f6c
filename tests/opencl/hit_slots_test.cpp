// The photon group's memory sized by what a pass needs. Hit slots by what the scene's materials
// allow (render/photon/photon_settings.h): a photon records a hit after each bounce, so without
// mirror reflectance `bounces` slots per photon hold every hit, and mirrors add two. Proved by
// rendering the built-in Cornell box (no mirrors) and the same box with a mirror reflectance of
// 1e-7 on every material, which no photon of the seed chooses: the second reserves two more
// slots per photon, and both must record the same hits and give the same image, bit for bit
// (fixed smoothing: no reduction over the slot layout). And the hit records and the photon map by
// the valid hits a pass records, not by its photons, while the memory checks before the first
// frame still count them at the most hits a pass is expected to record (DeviceMemoryPromise).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <stdexcept>

#include "render/photon/photon_mapping.h"
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

std::unique_ptr<Device> opencl_device() {
  std::unique_ptr<Device> device = test::open_first_device("opencl");
  if (!device) throw std::runtime_error("no OpenCL device");
  return device;
}

// 65536 photons of two bounces at a fixed footprint size (no reduction over the slots), size^2 pixels.
RenderSettings photons_of_two_bounces(int size) {
  PhotonSettings photons;
  photons.photons = 65536;
  photons.bounces = 2;
  photons.smoothing = 8;
  RenderSettings settings = test::photon_render_settings(photons);
  settings.width = settings.height = size;
  return settings;
}

Rendered render(const Scene& scene) {
  std::unique_ptr<Device> device = opencl_device();
  RenderSettings settings = photons_of_two_bounces(48);
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
  // One word per slot (the records are taken per valid hit): 4 bytes for each of the two slots
  // per photon not reserved.
  EXPECT_GE(b.peak_bytes, a.peak_bytes + uint64_t(65536) * 2 * 4);
  std::printf("peak device memory: %.1f MiB without mirrors, %.1f MiB with\n", a.peak_bytes / 1048576.0,
              b.peak_bytes / 1048576.0);
}

// A photon map entry: nine float4 of footprint and gather data (two of which hold the sort's
// input first), the sorted Morton keys and slots (8 bytes; the tree's visit counters take over the
// slots). A hit record: five float4, which the tree's nodes and parent links take over
// (kernels/common/buffers.h).
constexpr uint64_t kMapBytesPerHit = 152, kRecordBytes = 80;

// Renders the built-in box (every diffuse reflectance set to `albedo` when given) with 65536
// photons of two bounces, twice; returns the valid hits, and the room of the map and of the hit
// records, in hits. The records start with room for 32768 hits (half the photons): a pass that
// records more traces again with more room, and the frame rendered again, with room from the
// start, must give the same bits.
struct MapRoom {
  uint64_t hits = 0, room = 0, records = 0;
};

MapRoom render_and_measure_map(float albedo) {
  std::unique_ptr<Device> device = opencl_device();
  const RenderSettings settings = photons_of_two_bounces(32);
  Scene scene = builtin_cornell_box();
  if (albedo > 0)
    for (MaterialDesc& m : scene.materials) m.diffuse = Float3{albedo, albedo, albedo};
  Renderer renderer(*device, scene, settings);
  // Before the first pass no map is held; the checks count the map and the records for 5/4 of
  // the photons' hits (no more than the slots of each photon).
  const uint64_t counted = 81920 * (kMapBytesPerHit + kRecordBytes);
  EXPECT_EQ(renderer.buffers()[BufferSlot::map_center].bytes(), 0u);
  EXPECT_EQ(renderer.buffers()[BufferSlot::hit_records].bytes(), 32768 * kRecordBytes);
  EXPECT_EQ(device->needed_bytes() - device->allocated_bytes(), counted - 32768 * kRecordBytes);
  FrameStats stats;
  const FrameImage first = renderer.render_frame(0, &stats);
  MapRoom r;
  r.hits = uint64_t(stats.method.get("hits"));
  r.room = renderer.buffers()[BufferSlot::map_center].bytes() / sizeof(float4);
  r.records = renderer.buffers()[BufferSlot::hit_records].bytes() / kRecordBytes;
  // The checks still count what the photons could need, less what is held.
  const uint64_t held = r.room * kMapBytesPerHit + r.records * kRecordBytes;
  EXPECT_EQ(device->needed_bytes() - device->allocated_bytes(), held < counted ? counted - held : 0);
  const FrameImage again = renderer.render_frame(0);
  for (const char* layer : {"indirect", "caustic"}) {
    const std::vector<float>& x = first.find(layer)->rgb;
    const std::vector<float>& y = again.find(layer)->rgb;
    EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(float)), 0) << "layer '" << layer << "'";
  }
  return r;
}

TEST(HitSlots, ThePhotonMapAndTheHitRecordsAreSizedByTheHitsAPassRecords) {
  // The box as it is: fewer valid hits than photons (but more than the records' first room),
  // room for them and their noise (hit_room, no margin for change: the first pass measured them).
  const MapRoom dark = render_and_measure_map(0);
  ASSERT_GT(dark.hits, 32768u);
  ASSERT_LT(dark.hits, 65536u) << "the box's photons record fewer valid hits than there are photons";
  EXPECT_EQ(dark.room, hit_room(dark.hits, false));
  EXPECT_EQ(dark.records, dark.room);
  // Brighter walls: more valid hits than photons, within the 5/4 of them the checks counted, but
  // too many for their margin to fit in it: the map keeps that room and no more.
  const MapRoom bright = render_and_measure_map(0.93f);
  ASSERT_GT(hit_room(bright.hits, false), 81920u);
  ASSERT_LE(bright.hits, 81920u);
  EXPECT_EQ(bright.room, 81920u);
  EXPECT_EQ(bright.records, 81920u);
  // Brighter still: more than 5/4 of the photons; the map grows to the hits and their margin, up
  // to the two records of each photon.
  const MapRoom brightest = render_and_measure_map(1.0f);
  ASSERT_GT(brightest.hits, 81920u);
  EXPECT_EQ(brightest.room, std::min<uint64_t>(hit_room(brightest.hits, false), 131072u));
  EXPECT_EQ(brightest.records, brightest.room);
  std::printf("valid hits of 65536 photons: %llu, %llu, %llu; map room %llu, %llu, %llu\n",
              (unsigned long long)dark.hits, (unsigned long long)bright.hits, (unsigned long long)brightest.hits,
              (unsigned long long)dark.room, (unsigned long long)bright.room, (unsigned long long)brightest.room);
}

// Once a pass has sized the rooms by its hits, a pass that records more than they hold means the
// hits change (here the light moves from far outside the box into it between two frames), and the
// rooms grow with a margin for what the animation changes next (hit_room's `changing`).
TEST(HitSlots, RoomsThatGrowAfterTheFirstPassKeepAMarginForChange) {
  std::unique_ptr<Device> device = opencl_device();
  Scene scene = builtin_cornell_box();
  const Float3 inside = scene.lights[0].position, camera = scene.camera.position;
  LightAnimation light;
  light.position.keys = {{0.0, {camera.x, camera.y, camera.z - 20.0f}}, {1.0 / 24.0, {inside.x, inside.y, inside.z}}};
  scene.animation.enabled = true;
  scene.animation.first_frame = 0;
  scene.animation.last_frame = 1;
  scene.animation.lights = {light};
  Renderer renderer(*device, scene, photons_of_two_bounces(32));
  const auto map_room = [&] { return renderer.buffers()[BufferSlot::map_center].bytes() / sizeof(float4); };
  const auto record_room = [&] { return renderer.buffers()[BufferSlot::hit_records].bytes() / kRecordBytes; };
  FrameStats far, near;
  renderer.render_frame(0, &far);
  const uint64_t far_hits = uint64_t(far.method.get("hits"));
  ASSERT_GT(far_hits, 0u);
  ASSERT_LT(hit_room(far_hits, true), 32768u) << "the light far outside: the records' first room holds its hits";
  EXPECT_EQ(map_room(), hit_room(far_hits, false));
  EXPECT_EQ(record_room(), 32768u);
  renderer.render_frame(1, &near);
  const uint64_t near_hits = uint64_t(near.method.get("hits"));
  ASSERT_GT(near_hits, 32768u);
  ASSERT_LT(hit_room(near_hits, true), 81920u);
  EXPECT_EQ(map_room(), hit_room(near_hits, true));
  EXPECT_EQ(record_room(), hit_room(near_hits, true));
  std::printf("valid hits of 65536 photons: %llu with the light outside, %llu inside; rooms %llu, %llu\n",
              (unsigned long long)far_hits, (unsigned long long)near_hits,
              (unsigned long long)hit_room(far_hits, false), (unsigned long long)map_room());
}

}  // namespace
}  // namespace pm

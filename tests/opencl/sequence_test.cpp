// Animation sequences on the OpenCL backend, through the renderer: photon reuse over camera-only
// motion (flagged, tracing skipped, the image equal to a fresh render of the frame), frames
// independent of the frames rendered before them, a glTF scene rendering exactly like its JSON
// twin, and the flicker of random against Halton photon sequences. The command line over
// sequences: sequence_cli_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "render/image_metrics.h"
#include "render/scene_frame.h"
#include "render/exr_io.h"
#include "render/renderer.h"
#include "render/stage_timer.h"
#include "scene_io/scene_file.h"
#include "support/device_checks.h"
#include "support/image_stats.h"
#include "support/render_settings.h"
#include "support/paths.h"
#include "support/same_image.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

std::string data(const std::string& name) { return test::test_data_dir() + "/animation/" + name; }

RenderSettings small_settings(int width = 48, int height = 36, uint64_t photons = 20000,
                              int sequence = PM_PHOTON_SEQUENCE_RANDOM, uint32_t passes = 1) {
  PhotonSettings photon;
  photon.photons = photons;
  photon.sequence = sequence;
  RenderSettings settings = test::photon_render_settings(photon, passes);
  settings.width = width;
  settings.height = height;
  settings.control_paths = 0;  // these tests read images and photons, not the error estimate
  return settings;
}

bool photons_reused(const FrameStats& stats) { return stats.method.get("photons_reused") != 0; }
int photon_frame(const FrameStats& stats) { return int(stats.method.get("photon_frame", -1)); }

double stage_ms(const std::vector<StageTime>& times, const std::string& stage) {
  double ms = 0;
  for (const StageTime& t : times)
    if (t.stage == stage) ms += t.ms;
  return ms;
}

using test::expect_same_image;

class Sequence : public ::testing::Test {
 protected:
  void SetUp() override {
    device_ = test::open_first_device("opencl");
    if (!device_) GTEST_SKIP() << "no OpenCL device";
  }
  std::unique_ptr<Device> device_;
};

// moving_room.json: the lamp moves until 0.5 s (frame 12 at 24 fps) and then holds, while the
// camera keeps moving: frames 12-23 are one run of unchanged lights.
TEST_F(Sequence, CameraOnlyFramesReuseThePhotonsAndEqualAFreshRender) {
  const Scene scene = load_scene_file(data("moving_room.json"));
  const RenderSettings settings = small_settings();
  Renderer renderer(*device_, scene, settings);
  StageTimer timer(*device_);
  renderer.set_stage_timer(&timer);
  FrameImage previous;
  for (int f = 10; f <= 16; ++f) {
    SCOPED_TRACE("frame " + std::to_string(f));
    FrameStats stats;
    FrameImage image = renderer.render_frame(f, &stats);
    const double trace_ms = stage_ms(timer.collect(), "photon trace");
    const bool expect_reuse = f >= 13;
    EXPECT_EQ(photons_reused(stats), expect_reuse);
    EXPECT_EQ(photon_frame(stats), f >= 12 ? 12 : f);
    if (expect_reuse) EXPECT_EQ(trace_ms, 0.0) << "a reused frame traced photons";
    else EXPECT_GT(trace_ms, 0.0);
    EXPECT_GT(stats.method.get("hits"), 0.0);

    // A fresh Renderer that rendered nothing before traces the same photons (keyed by frame 12).
    Renderer fresh(*device_, scene, settings);
    FrameStats fresh_stats;
    expect_same_image(image, fresh.render_frame(f, &fresh_stats), "reused against fresh");
    EXPECT_FALSE(photons_reused(fresh_stats));
    if (f > 10) {
      EXPECT_NE(image.find("")->rgb, previous.find("")->rgb) << "the camera moved; the image must too";
    }
    previous = image;
  }
}

TEST_F(Sequence, WithoutReuseEveryFrameDrawsItsOwnPhotons) {
  const Scene scene = load_scene_file(data("moving_room.json"));
  RenderSettings settings = small_settings();
  settings.reuse_lighting = false;
  Renderer renderer(*device_, scene, settings);
  RenderSettings reusing = small_settings();
  Renderer reference(*device_, scene, reusing);
  for (int f = 12; f <= 14; ++f) {
    FrameStats stats;
    const FrameImage own = renderer.render_frame(f, &stats);
    EXPECT_FALSE(photons_reused(stats));
    EXPECT_EQ(photon_frame(stats), f);
    const FrameImage shared = reference.render_frame(f);
    EXPECT_EQ(own.find("direct")->rgb, shared.find("direct")->rgb) << "the same camera and lights";
    if (f > 12) EXPECT_NE(own.find("indirect")->rgb, shared.find("indirect")->rgb) << "other photons";
    else EXPECT_EQ(own.find("indirect")->rgb, shared.find("indirect")->rgb) << "frame 12 keys both";
  }
}

TEST_F(Sequence, SeveralPassesTraceEveryFrameAgain) {
  const Scene scene = load_scene_file(data("moving_room.json"));
  // 3 passes: the device only ever holds the last pass's map, and a frame starts with pass 0.
  const RenderSettings settings = small_settings(48, 36, 6667, PM_PHOTON_SEQUENCE_RANDOM, 3);
  Renderer renderer(*device_, scene, settings);
  for (int f = 12; f <= 14; ++f) {
    FrameStats stats;
    const FrameImage image = renderer.render_frame(f, &stats);
    EXPECT_FALSE(photons_reused(stats));
    EXPECT_EQ(stats.passes, 3u);
    Renderer fresh(*device_, scene, settings);
    expect_same_image(image, fresh.render_frame(f), "frame " + std::to_string(f));
  }
}

TEST_F(Sequence, FramesDoNotDependOnTheFramesRenderedBefore) {
  const Scene scene = load_scene_file(data("moving_room.json"));
  const RenderSettings settings = small_settings();
  Renderer in_order(*device_, scene, settings);
  std::map<int, FrameImage> images;
  for (int f = 0; f <= 23; f += 1) images[f] = in_order.render_frame(f);
  Renderer backwards(*device_, scene, settings);
  for (int f : {23, 17, 12, 11, 3, 0, 16}) expect_same_image(backwards.render_frame(f), images[f], "frame " + std::to_string(f));
}

TEST_F(Sequence, GltfSceneRendersExactlyLikeItsJsonTwin) {
  const Scene gltf = load_scene_file(data("twin.gltf"));
  const Scene json = load_scene_file(data("twin.json"));
  const RenderSettings settings = small_settings(0, 0);  // the files' 48 x 36
  Renderer a(*device_, gltf, settings), b(*device_, json, settings);
  for (int f : {0, 7, 24}) {
    const FrameImage ia = a.render_frame(f), ib = b.render_frame(f);
    EXPECT_EQ(ia.width, 48);
    EXPECT_GT(test::mean(ia.find("indirect")->rgb), 0.0);
    expect_same_image(ia, ib, "frame " + std::to_string(f));
  }
}

TEST_F(Sequence, HaltonPhotonsAreUnbiasedAndTheSameInEveryFrame) {
  Scene scene = load_scene_file(data("moving_room.json"));
  scene.animation.camera = CameraAnimation{};
  scene.animation.lights.clear();  // a static sequence
  RenderSettings settings = small_settings(48, 36, 200000, PM_PHOTON_SEQUENCE_HALTON);
  settings.reuse_lighting = false;
  Renderer halton(*device_, scene, settings);
  RenderSettings random_settings = small_settings(48, 36, 200000, PM_PHOTON_SEQUENCE_RANDOM);
  random_settings.reuse_lighting = false;
  Renderer random(*device_, scene, random_settings);
  const FrameImage h3 = halton.render_frame(3), h4 = halton.render_frame(4);
  const FrameImage r3 = random.render_frame(3), r4 = random.render_frame(4);
  expect_same_image(h3, h4, "halton frames 3 and 4");
  EXPECT_NE(r3.find("indirect")->rgb, r4.find("indirect")->rgb);
  // Same expected brightness: the Halton photons estimate the same indirect light.
  const double mean_h = test::mean(h3.find("indirect")->rgb), mean_r = test::mean(r3.find("indirect")->rgb);
  EXPECT_GT(mean_h, 0.0);
  EXPECT_NEAR(mean_h / mean_r, 1.0, 0.03);
  // Another seed gives other (rotated) Halton points.
  settings.seed = 7;
  Renderer other_seed(*device_, scene, settings);
  EXPECT_NE(other_seed.render_frame(3).find("indirect")->rgb, h3.find("indirect")->rgb);
}

// Flicker (render/scene_frame.h, sequence_flicker) of a static-camera sequence. Sizes can
// be raised through PM_FLICKER_WIDTH, PM_FLICKER_HEIGHT, PM_FLICKER_PHOTONS and PM_FLICKER_FRAMES
// (docs/animation.md lists the numbers measured that way).
int env_int(const char* name, int fallback) {
  const char* v = std::getenv(name);
  return v ? std::atoi(v) : fallback;
}

struct FlickerRow {
  FlickerStats combined, indirect, direct;
};

FlickerRow measure_flicker(Device& device, const Scene& scene, const RenderSettings& settings, int frames) {
  Renderer renderer(device, scene, settings);
  std::vector<std::vector<float>> combined, indirect, direct;
  for (int f = 0; f < frames; ++f) {
    const FrameImage image = renderer.render_frame(f);
    combined.push_back(image.find("")->rgb);
    indirect.push_back(image.find("indirect")->rgb);
    direct.push_back(image.find("direct")->rgb);
  }
  return {sequence_flicker(combined), sequence_flicker(indirect), sequence_flicker(direct)};
}

TEST_F(Sequence, HaltonPhotonsReduceFlicker) {
  const int width = env_int("PM_FLICKER_WIDTH", 64), height = env_int("PM_FLICKER_HEIGHT", 48);
  const int photons = env_int("PM_FLICKER_PHOTONS", 50000), frames = env_int("PM_FLICKER_FRAMES", 8);
  // The camera stays at its frame-0 place; the lamp moves in a straight line over the whole
  // sequence, 2.5 m (fast) or a tenth of that (slow), or not at all (static).
  Scene fast = load_scene_file(data("moving_room.json"));
  fast.animation.camera = CameraAnimation{};
  fast.animation.first_frame = 0;
  fast.animation.last_frame = frames - 1;
  auto& keys = fast.animation.lights[0].position.keys;
  keys[1].time = double(frames - 1) / fast.animation.frame_rate;
  Scene slow = fast;
  for (int c = 0; c < 3; ++c) {
    auto& end = slow.animation.lights[0].position.keys[1].value[c];
    end = keys[0].value[c] + 0.1f * (end - keys[0].value[c]);
  }
  Scene still = fast;
  still.animation.lights.clear();
  auto per_frame_cm = [&](const Scene& scene) {
    const auto& k = scene.animation.lights[0].position.keys;
    double d2 = 0;
    for (int c = 0; c < 3; ++c) d2 += double(k[1].value[c] - k[0].value[c]) * (k[1].value[c] - k[0].value[c]);
    return 100 * std::sqrt(d2) / (frames - 1);
  };

  std::printf("flicker at %dx%d, %d photons per frame, %d frames: mean relative frame-to-frame change of the\n"
              "combined image (mean / largest pair), and the mean of the indirect and direct layers\n",
              width, height, photons, frames);
  std::map<std::string, FlickerRow> rows;
  const std::pair<const Scene*, std::string> scenes[] = {
      {&fast, "fast light"}, {&slow, "slow light"}, {&still, "static"}};
  for (const auto& [scene, label] : scenes) {
    if (scene != &still) std::printf("  %s: %.1f cm per frame\n", label.c_str(), per_frame_cm(*scene));
    for (int sequence : {PM_PHOTON_SEQUENCE_RANDOM, PM_PHOTON_SEQUENCE_HALTON}) {
      for (bool reuse : {false, true}) {
        if (scene != &still && reuse) continue;  // the light moves every frame: nothing to reuse
        RenderSettings settings = small_settings(width, height, uint64_t(photons), sequence);
        settings.reuse_lighting = reuse;
        const FlickerRow row = measure_flicker(*device_, *scene, settings, frames);
        const std::string name = label + ", " + (sequence == PM_PHOTON_SEQUENCE_HALTON ? "halton" : "random") +
                                 (reuse ? ", reuse" : "");
        rows[name] = row;
        std::printf("  %-24s combined %7.4f%% / %7.4f%%   indirect %7.4f%%   direct %7.4f%%\n", name.c_str(),
                    100 * row.combined.mean, 100 * row.combined.max, 100 * row.indirect.mean, 100 * row.direct.mean);
      }
    }
  }
  EXPECT_GT(rows["static, random"].combined.mean, 0.0);
  EXPECT_EQ(rows["static, halton"].combined.max, 0.0);
  EXPECT_EQ(rows["static, random, reuse"].combined.max, 0.0);
  EXPECT_EQ(rows["static, halton, reuse"].combined.max, 0.0);
  EXPECT_LT(rows["fast light, halton"].indirect.mean, rows["fast light, random"].indirect.mean);
  EXPECT_LT(rows["slow light, halton"].indirect.mean, 0.5 * rows["slow light, random"].indirect.mean);
  EXPECT_LT(rows["slow light, halton"].combined.mean, 0.5 * rows["slow light, random"].combined.mean);
  EXPECT_EQ(rows["slow light, halton"].direct.mean, rows["slow light, random"].direct.mean);
}

}  // namespace
}  // namespace pm

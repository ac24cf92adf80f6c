// Animation sequences on the OpenCL backend: photon reuse over camera-only motion (flagged,
// tracing skipped, the image equal to a fresh render of the frame), frames independent of the
// frames rendered before them (chunked runs equal one run, through the command line too), a glTF
// scene rendering exactly like its JSON twin, batch behaviour of `pmrender render` (frame specs,
// --resume after a SIGKILL, failed frames, progress only on a terminal) and the flicker of
// random against Halton photon sequences.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <pty.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

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
#include "support/pmrender_process.h"
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

// --- the command line ---------------------------------------------------------------------

using Process = test::ProcessResult;
using test::read_text;

class SequenceCli : public test::PmrenderProcessTest {
 protected:
  void SetUp() override {
    PmrenderProcessTest::SetUp();
    fs::create_directories(dir_ / "out");
  }

  std::string out(const std::string& pattern) { return (dir_ / "out" / pattern).string(); }
  std::set<std::string> files() {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_ / "out")) names.insert(e.path().filename().string());
    return names;
  }
  // Frames whose "wrote" line is in a run's standard output.
  static std::set<int> written_frames(const std::string& stdout_text) {
    std::set<int> frames;
    std::istringstream lines(stdout_text);
    for (std::string line; std::getline(lines, line);) {
      const size_t at = line.find("(frame ");
      if (line.rfind("wrote ", 0) == 0 && at != std::string::npos) frames.insert(std::stoi(line.substr(at + 7)));
    }
    return frames;
  }
  void expect_usage_error(const std::string& args, const std::string& expected) {
    const Process r = pmrender(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(files().empty()) << args;
  }

};

const char kSmall[] = " --backend opencl --resolution 40x30 --photons 20000";

TEST_F(SequenceCli, BadFrameSelectionsExitWith2AndWriteNothing) {
  const std::string scene = data("moving_room.json") + kSmall + " -o " + out("f_####.exr");
  expect_usage_error("render " + scene + " --frames 5-2", "--frames: '5-2': range end is before its start");
  expect_usage_error("render " + scene + " --frames 20-24", "--frames: '20-24': outside the scene's frames 0-23");
  expect_usage_error("render " + scene + " --frames 1,,2", "--frames:");
  expect_usage_error("render " + scene + " --frames x", "--frames: 'x'");
  expect_usage_error("render " + scene + " --frame 24", "--frame: 24 is outside the scene's frames 0-23");
  expect_usage_error("render " + scene + " --frame 1 --frames 2", "--frame and --frames");
  expect_usage_error("render " + data("moving_room.json") + kSmall + " --frames 0-1 -o " + out("single.exr"),
                     "has no # for the frame number, but 2 frames are selected");
  const Process r = pmrender("render " + scene + " --photon-sequence sobol");  // CLI11's usage message
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--photon-sequence"), std::string::npos) << r.err;
  EXPECT_TRUE(files().empty());
  expect_usage_error("render " + data("missing.gltf") + " -o " + out("f_#.exr"), "missing.gltf: cannot open");
}

TEST_F(SequenceCli, StillScenesTakeAnyFrameAndSequencesDefaultToAllTheirFrames) {
  Process r = pmrender(std::string("render") + kSmall + " --frames 3,7 -o " + out("cb_####.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(files(), (std::set<std::string>{"cb_0003.exr", "cb_0007.exr"}));
  EXPECT_NE(r.out.find("rendered 2 of 2 frames"), std::string::npos) << r.out;
  fs::remove_all(dir_ / "out");
  fs::create_directories(dir_ / "out");
  r = pmrender("render " + data("twin.json") + " --backend opencl --photons 5000 -o " + out("t_##.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(files().size(), 25u);  // frames 0-24: the keys end at 1 s, 24 frames per second
  EXPECT_NE(r.out.find("rendered 25 of 25 frames"), std::string::npos) << r.out;
  const FrameImage f7 = read_exr(out("t_07.exr"));
  bool frame_attribute = false;
  for (const auto& [key, value] : f7.attributes) frame_attribute |= key == "pmrender/frame" && value == "7";
  EXPECT_TRUE(frame_attribute);
}

TEST_F(SequenceCli, ChunkedRunsWriteTheSamePixelsAsOneRun) {
  const std::string scene = "render " + data("moving_room.json") + kSmall + " --float";
  ASSERT_EQ(pmrender(scene + " --frames 8-16 -o " + out("one_####.exr")).exit_code, 0);
  ASSERT_EQ(pmrender(scene + " --frames 8-10 -o " + out("chunk_####.exr")).exit_code, 0);
  ASSERT_EQ(pmrender(scene + " --frames 14-16,11-13 -o " + out("chunk_####.exr")).exit_code, 0);
  for (int f = 8; f <= 16; ++f) {
    char one[32], chunk[32];
    std::snprintf(one, sizeof(one), "one_%04d.exr", f);
    std::snprintf(chunk, sizeof(chunk), "chunk_%04d.exr", f);
    const FrameImage a = read_exr(out(one)), b = read_exr(out(chunk));
    expect_same_image(a, b, "frame " + std::to_string(f));
  }
}

TEST_F(SequenceCli, FailedFramesAreNamedAndTheOthersStillRender) {
  // A target that cannot be written is refused before rendering (output_checks_test.cpp), so
  // frame 2 is made to fail in its write instead: its temporary, ".f_0002.exr.tmp-<pid>-2" (the
  // third file this process writes), is taken by a folder made as soon as the pid is known, long
  // before pmrender has opened its device.
  const pid_t pid = test::start_pmrender(
      "render " + data("moving_room.json") + kSmall + " --frames 0-4 -o " + out("f_####.exr"), dir_);
  ASSERT_GT(pid, 0);
  fs::create_directories(dir_ / "out" / (".f_0002.exr.tmp-" + std::to_string(pid) + "-2"));
  const test::ProcessResult r = test::wait_pmrender(pid, dir_);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("pmrender: frame 2: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("1 of 5 frames failed: 2"), std::string::npos) << r.err;
  for (int f : {0, 1, 3, 4}) EXPECT_TRUE(exr_is_complete(out("f_000" + std::to_string(f) + ".exr"))) << f;
  EXPECT_EQ(written_frames(r.out), (std::set<int>{0, 1, 3, 4}));
}

TEST_F(SequenceCli, ResumeAfterAKilledRunRendersOnlyTheMissingFrames) {
  // The done-when sequence: 24 frames whose camera and lamp both move, killed part-way through.
  const std::string pattern = out("f_####.exr");
  const std::string binary = test::pmrender_binary();
  const std::string scene = data("moving_room.json");
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const int null_in = open("/dev/null", O_RDONLY), null_out = open("/dev/null", O_WRONLY);
    dup2(null_in, 0);
    dup2(null_out, 1);
    dup2(null_out, 2);
    execl(binary.c_str(), binary.c_str(), "render", scene.c_str(), "--backend", "opencl", "--resolution", "64x48",
          "--photons", "60000", "--frames", "0-23", "-o", pattern.c_str(), (char*)nullptr);
    _exit(127);
  }
  auto complete_frames = [&] {
    std::set<int> frames;
    for (int f = 0; f < 24; ++f) {
      char name[32];
      std::snprintf(name, sizeof(name), "f_%04d.exr", f);
      if (fs::exists(dir_ / "out" / name)) frames.insert(f);
    }
    return frames;
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (complete_frames().size() < 3 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_EQ(kill(pid, SIGKILL), 0);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "pmrender finished before it could be killed";
  const std::set<int> before = complete_frames();
  ASSERT_GE(before.size(), 3u);
  ASSERT_LT(before.size(), 24u) << "the whole sequence was written before the kill";
  for (int f : before) {
    char name[32];
    std::snprintf(name, sizeof(name), "f_%04d.exr", f);
    EXPECT_TRUE(exr_is_complete(out(name))) << name << ": a target file is never partial";
  }
  // A partial file (as a copy interrupted by hand would leave) is not complete, so it renders again.
  const int truncated = *before.begin();
  char truncated_name[32];
  std::snprintf(truncated_name, sizeof(truncated_name), "f_%04d.exr", truncated);
  fs::resize_file(dir_ / "out" / truncated_name, fs::file_size(dir_ / "out" / truncated_name) / 2);
  std::map<int, fs::file_time_type> mtimes;
  for (int f : before) {
    char name[32];
    std::snprintf(name, sizeof(name), "f_%04d.exr", f);
    mtimes[f] = fs::last_write_time(dir_ / "out" / name);
  }

  const Process r = pmrender("render " + scene + " --backend opencl --resolution 64x48 --photons 60000 --frames 0-23 "
                             "--resume -v -o " + pattern);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::set<int> expected;
  for (int f = 0; f < 24; ++f)
    if (!before.count(f) || f == truncated) expected.insert(f);
  EXPECT_EQ(written_frames(r.out), expected) << r.out;
  for (int f : before) {
    if (f == truncated) continue;
    char name[32];
    std::snprintf(name, sizeof(name), "f_%04d.exr", f);
    EXPECT_NE(r.out.find(std::string("skipped ") + out(name) + " (complete)"), std::string::npos) << r.out;
    EXPECT_EQ(fs::last_write_time(dir_ / "out" / name), mtimes[f]) << name << " was rewritten";
  }
  for (int f = 0; f < 24; ++f) {
    char name[32];
    std::snprintf(name, sizeof(name), "f_%04d.exr", f);
    EXPECT_TRUE(exr_is_complete(out(name))) << name;
  }
  for (const std::string& name : files()) EXPECT_EQ(name.find(".tmp-"), std::string::npos) << "left behind: " << name;
  EXPECT_EQ(files().size(), 24u);
}

TEST_F(SequenceCli, StaleTemporariesOfDeadProcessesAreRemoved) {
  // What write_exr leaves when killed mid-write: ".<name>.tmp-<pid>-<n>" of a process that is gone.
  pid_t dead = fork();
  if (dead == 0) _exit(0);
  waitpid(dead, nullptr, 0);
  const std::string stale = ".f_0001.exr.tmp-" + std::to_string(dead) + "-0";
  const std::string live = ".f_0001.exr.tmp-" + std::to_string(getpid()) + "-0";  // ours: alive
  std::ofstream(dir_ / "out" / stale) << "partial";
  std::ofstream(dir_ / "out" / live) << "partial";
  const Process r = pmrender("render " + data("moving_room.json") + kSmall + " --frames 1 -v -o " + out("f_####.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(files(), (std::set<std::string>{"f_0001.exr", live}));
  EXPECT_NE(r.out.find("removed stale temporary"), std::string::npos) << r.out;
}

// Runs pmrender with its standard error on a pseudo-terminal and returns what it printed there.
std::string run_on_terminal(const std::vector<std::string>& args) {
  int master = -1;
  const pid_t pid = forkpty(&master, nullptr, nullptr, nullptr);
  if (pid == 0) {
    const int null_fd = open("/dev/null", O_RDWR);
    dup2(null_fd, 0);
    dup2(null_fd, 1);  // only standard error stays on the terminal
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  std::string text;
  char buffer[4096];
  for (;;) {
    const ssize_t n = read(master, buffer, sizeof(buffer));
    if (n <= 0) break;  // EIO once the child has closed the terminal
    text.append(buffer, size_t(n));
  }
  waitpid(pid, nullptr, 0);
  close(master);
  return text;
}

TEST_F(SequenceCli, ProgressGoesToATerminalOnlyAndQuietSilencesIt) {
  const std::vector<std::string> base = {test::pmrender_binary(), "render", data("moving_room.json"), "--backend",
                                         "opencl", "--resolution", "40x30", "--photons", "20000", "--frames", "0-3",
                                         "-o", out("f_####.exr")};
  const std::string terminal = run_on_terminal(base);
  EXPECT_NE(terminal.find("4/4 (100%)"), std::string::npos) << terminal;
  EXPECT_NE(terminal.find("/frame  ETA "), std::string::npos) << terminal;
  std::vector<std::string> quiet = base;
  quiet.push_back("--quiet");
  EXPECT_EQ(run_on_terminal(quiet), "");
  const Process piped = pmrender("render " + data("moving_room.json") + kSmall + " --frames 12-15 -o " + out("f_####.exr"));
  ASSERT_EQ(piped.exit_code, 0);
  EXPECT_EQ(piped.err.find("ETA"), std::string::npos) << piped.err;
  EXPECT_NE(piped.out.find("rendered 4 of 4 frames"), std::string::npos) << piped.out;
  EXPECT_NE(piped.out.find("photons reused in 3"), std::string::npos) << piped.out;  // 13-15 share 12's lamp
}

}  // namespace
}  // namespace pm

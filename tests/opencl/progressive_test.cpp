// Progressive rendering (docs/progressive.md) on the OpenCL backend: passes that average or
// shrink, convergence on the closed diffuse sphere (exact answer known), the error estimate
// against the true error, time and error budgets, memory bounded by one pass, and checkpoints
// that continue exactly where an uninterrupted run would.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>
#include <vector>
#include <thread>

#include "render/exr_io.h"
#include "render/progressive.h"
#include "render/renderer.h"
#include "scene_io/cornell_box.h"
#include "support/analytic_scenes.h"
#include "support/device_checks.h"
#include "support/lit_boxes.h"
#include "support/pmrender_process.h"
#include "support/render_settings.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

Device& device() {
  static std::unique_ptr<Device> d = test::open_first_device("opencl");
  if (!d) throw std::runtime_error("no OpenCL device");
  return *d;
}

const test::LitSphere& sphere() { return test::lit_sphere(); }

// Errors of a render of the sphere's indirect light against the exact answer.
struct SphereError {
  double bias = 0;      // relative error of the image mean: what remains once noise averages out
  double mean_abs = 0;  // mean relative absolute error per pixel and channel: bias and noise
  double estimate = -1; // the renderer's own estimate of the relative error
  ProgressiveResult result;
};

// Whether a render also makes the frame's error estimate. Tests that read only the image leave its
// control paths out: at 64 passes of 20000 photons they would cost as much as the passes.
enum class Estimate { kMade, kLeftOut };

SphereError render_sphere(PhotonSettings photons, const PassBudget& budget, Estimate estimate = Estimate::kMade) {
  const test::LitSphere& s = sphere();
  RenderSettings settings = test::photon_render_settings(photons, budget.max_passes);
  if (estimate == Estimate::kLeftOut) settings.control_paths = 0;
  Renderer renderer(device(), s.scene, settings);
  SphereError e;
  e.result = render_progressive(renderer, 0, budget, nullptr, 0);
  const std::vector<float> indirect = renderer.read_image().find("indirect")->rgb;
  double sum = 0;
  for (float v : indirect) {
    sum += v;
    e.mean_abs += std::fabs(v - s.expected);
  }
  e.bias = sum / double(indirect.size()) / s.expected - 1.0;
  e.mean_abs /= double(indirect.size()) * s.expected;
  e.estimate = e.result.error;
  return e;
}

SphereError render_sphere(int estimator, int mode, uint32_t passes, float alpha = 2.0f / 3.0f, float rmax = 0,
                          Estimate estimate = Estimate::kMade) {
  PhotonSettings p;
  p.photons = 20000;
  p.estimator = estimator;
  p.progressive = mode;
  p.alpha = alpha;
  p.rmax = rmax;
  PassBudget budget;
  budget.max_passes = passes;
  SphereError e = render_sphere(p, budget, estimate);
  std::printf("%s %s, %3u passes: bias %+.4f, mean |error| %.4f, estimate %.4f\n", name_of(kEstimatorNames, estimator),
              name_of(kProgressiveNames, mode), passes, e.bias, e.mean_abs, e.estimate);
  return e;
}

TEST(ProgressiveSettings, ShrinkFollowsKnausZwicker) {
  PhotonSettings p;
  EXPECT_EQ(p.footprint_scale(0), 1.0);
  EXPECT_EQ(p.footprint_scale(5), 1.0) << "average: every pass alike";
  p.progressive = kProgressiveShrink;
  p.alpha = 0.5f;
  // r_i^2 = r_(i-1)^2 (i + alpha) / (i + 1): areas scale by the product, semiaxes by its root.
  double area = 1;
  for (uint32_t i = 1; i <= 1000; ++i) {
    area *= (i + 0.5) / (i + 1.0);
    if (i == 1 || i == 10 || i == 1000) {
      EXPECT_NEAR(p.footprint_scale(i), std::sqrt(area), 1e-12 * std::sqrt(area)) << i;
    }
  }
  EXPECT_GT(p.footprint_scale(1000000), 0.0);
}

// pd's shrinking passes have their own defaults (docs/accuracy.md, "Shrink that converges"): a
// first pass at half of one pass's footprint area (overlap 50), alpha 0.2 and facet weighting;
// averaged passes and the other estimators keep theirs, final gathering's map its overlap 200;
// values given are kept.
TEST(ProgressiveSettings, PdShrinkingPassesHaveTheirOwnDefaults) {
  SceneMeasures measures;
  measures.diagonal = 10;
  PhotonSettings average;
  PhotonSettings r = average.resolved(measures);
  EXPECT_EQ(r.overlap, kAutoSmoothingOverlap);
  EXPECT_EQ(r.facet_weighting, 0);
  PhotonSettings shrink;
  shrink.progressive = kProgressiveShrink;
  r = shrink.resolved(measures);
  EXPECT_EQ(r.overlap, kShrinkStartOverlap);
  EXPECT_EQ(r.alpha, kShrinkAlphaPd);
  EXPECT_EQ(r.facet_weighting, 1);
  EXPECT_DOUBLE_EQ(shrink.footprint_scale(1), std::sqrt((1 + double(kShrinkAlphaPd)) / 2)) << "unresolved alike";
  PhotonSettings gathered = shrink;
  gathered.final_gather = 4;
  r = gathered.resolved(measures);
  EXPECT_EQ(r.overlap, kFinalGatherOverlap);
  EXPECT_EQ(r.alpha, kShrinkAlpha);
  EXPECT_EQ(r.facet_weighting, 0);
  PhotonSettings knn = shrink;
  knn.estimator = PM_ESTIMATOR_KNN;
  EXPECT_EQ(knn.resolved(measures).alpha, kShrinkAlpha);
  PhotonSettings given = shrink;
  given.overlap = 400;
  given.alpha = 0.5f;
  given.facet_weighting = 0;
  r = given.resolved(measures);
  EXPECT_EQ(r.overlap, 400);
  EXPECT_EQ(r.alpha, 0.5f);
  EXPECT_EQ(r.facet_weighting, 0);
}

// Average: every pass has the same footprints, so the noise falls as 1/sqrt(passes) while the
// bias stays; the estimate tracks the true error, bias included.
TEST(Progressive, AverageLowersNoiseButKeepsTheBias) {
  const SphereError r2 = render_sphere(PM_ESTIMATOR_RADIUS, kProgressiveAverage, 2);
  const SphereError r32 = render_sphere(PM_ESTIMATOR_RADIUS, kProgressiveAverage, 32);
  // 16x the passes: the noise (nearly all of the radius estimator's error here) falls 4x.
  EXPECT_NEAR(r2.mean_abs / r32.mean_abs, 4.0, 1.2);
  for (const SphereError* e : {&r2, &r32}) {
    EXPECT_GT(e->estimate, e->mean_abs / 2) << "the estimate is within a factor of 2 of the true error";
    EXPECT_LT(e->estimate, e->mean_abs * 2);
  }
  // A deliberately biased pd (flux spread over the whole flat ellipse, which the curved sphere
  // leaves before its rim: footprint coverage off) keeps its bias over passes, and the estimate
  // (its bias control, render/bias_control.h) reports it. At the automatic smoothing's former
  // overlap, 200 (-4.6 % at one pass on PoCL; -2.9 % at today's 100, closer to the test's noise).
  PhotonSettings biased;
  biased.photons = 20000;
  biased.footprint_coverage = false;
  biased.overlap = 200;
  PassBudget budget;
  budget.max_passes = 32;
  const SphereError p32 = render_sphere(biased, budget);
  budget.max_passes = 1;
  const SphereError p1 = render_sphere(biased, budget, Estimate::kLeftOut);
  std::printf("pd without coverage: bias %+.4f (1 pass), %+.4f (32 passes), estimate %.4f, mean |error| %.4f\n",
              p1.bias, p32.bias, p32.estimate, p32.mean_abs);
  EXPECT_LT(p32.bias, -0.03);
  EXPECT_NEAR(p32.bias, p1.bias, 0.04);
  EXPECT_GE(p32.estimate, 2.0 / 3.0 * std::fabs(p32.bias)) << "the estimate sees the bias";
  EXPECT_LT(p32.estimate, 1.5 * p32.mean_abs);
}

// Shrink: footprints (pd), radii (radius) and the k-NN bound shrink from pass to pass, so the
// bias falls as passes grow. alpha = 0.2 shrinks fast enough to show it in 32 passes.
TEST(Progressive, ShrinkLowersTheBiasOfEveryEstimator) {
  // pd's shrinking passes weigh photons on tilted facets (facet weighting, their default): on
  // this tight concave curve the first pass's large footprints read +1.8 % with it (+0.1 %
  // without, the same photons; PoCL), and shrinking takes it under half a percent (+0.3 %).
  const Estimate none = Estimate::kLeftOut;
  const SphereError pd1 = render_sphere(PM_ESTIMATOR_PD, kProgressiveShrink, 1, 0.2f, 0, none);
  const SphereError pd32 = render_sphere(PM_ESTIMATOR_PD, kProgressiveShrink, 32, 0.2f, 0, none);
  EXPECT_LT(std::fabs(pd1.bias), 0.025);
  EXPECT_LT(std::fabs(pd32.bias), 0.01);
  EXPECT_LT(std::fabs(pd32.bias), std::fabs(pd1.bias));
  // k-NN's bias (k photons counted inside the radius of the k-th: +1/(k-1)) goes once the
  // shrinking bound, here started at about the 64th neighbour's distance, cuts below it.
  const SphereError knn1 = render_sphere(PM_ESTIMATOR_KNN, kProgressiveShrink, 1, 0.2f, 0.15f, none);
  const SphereError knn32 = render_sphere(PM_ESTIMATOR_KNN, kProgressiveShrink, 32, 0.2f, 0.15f, none);
  EXPECT_LT(std::fabs(knn32.bias), std::fabs(knn1.bias));
  EXPECT_LT(std::fabs(knn32.bias), 0.01);
  const SphereError radius32 = render_sphere(PM_ESTIMATOR_RADIUS, kProgressiveShrink, 32, 0.2f);
  EXPECT_LT(std::fabs(radius32.bias), 0.01);
  EXPECT_GT(radius32.estimate, radius32.mean_abs / 2);
  EXPECT_LT(radius32.estimate, radius32.mean_abs * 2);
}

// At the paper's s = 8 and 200,000 photons a pass (the analytic sphere test's settings) pd starts
// close to the exact answer; shrinking takes it under 0.5 %, where noise and the tessellation's
// flat facets are what is left. Measured on PoCL: -0.44 % at 1 pass, -0.24 % at 16.
TEST(Progressive, ShrinkTakesPdUnderHalfAPercentAtThePapersSmoothing) {
  PhotonSettings p;
  p.photons = 200000;
  p.estimator = PM_ESTIMATOR_PD;
  p.smoothing = 8;
  p.progressive = kProgressiveShrink;
  p.alpha = 0.2f;
  // The schedule at the paper's footprints, without the facet weighting of pd's shrinking passes
  // (ShrinkLowersTheBiasOfEveryEstimator renders those): on this finely tessellated sphere every
  // footprint reaches tilted facets, and their lit-area probes took the test from 18 to 65 s on
  // PoCL (+0.13 % at one pass, -0.04 % at 16 with them).
  p.facet_weighting = 0;
  double bias[2] = {0, 0};
  const uint32_t passes[2] = {1, 16};
  for (int i = 0; i < 2; ++i) {
    PassBudget budget;
    budget.max_passes = passes[i];
    bias[i] = render_sphere(p, budget, Estimate::kLeftOut).bias;
    std::printf("pd s = 8 shrink, %2u passes of 200000: bias %+.4f\n", passes[i], bias[i]);
  }
  EXPECT_LT(std::fabs(bias[1]), 0.005);
  EXPECT_LT(std::fabs(bias[1]), std::fabs(bias[0]));
}

// The same in a real room, against a high-pass-count render: the Cornell box at 32 x 32, whose
// pd footprints lose light in its corners and along its edges and whose k-NN radii reach across
// them. The reference is the least biased estimator here (fixed radius 2 cm, 32 passes of 65536
// photons; 0.7 % under a 4096-path render, path_trace_test.cpp). Measured: pd -4.0 % at one pass,
// -0.2 % at 64; knn -8.6 %, -3.1 %; radius within 1 % throughout.
TEST(Progressive, ShrinkLowersTheBiasInTheCornellBox) {
  const Scene scene = builtin_cornell_box();
  auto indirect_mean = [&](PhotonSettings photons, uint32_t passes) {
    RenderSettings settings = test::photon_render_settings(photons, passes);
    settings.width = settings.height = 32;
    settings.control_paths = 0;  // the image only: no error estimate
    Renderer renderer(device(), scene, settings);
    PassBudget budget;
    budget.max_passes = passes;
    render_progressive(renderer, 0, budget, nullptr, 0);
    double sum = 0;
    const std::vector<float> indirect = renderer.read_image().find("indirect")->rgb;
    for (float v : indirect) sum += v;
    return sum / double(indirect.size());
  };
  PhotonSettings fine;
  fine.photons = 65536;
  fine.estimator = PM_ESTIMATOR_RADIUS;
  fine.radius = 0.02f;
  const double reference = indirect_mean(fine, 32);
  auto bias = [&](int estimator, uint32_t passes) {
    PhotonSettings p;
    p.photons = 20000;
    p.estimator = estimator;
    p.progressive = kProgressiveShrink;
    p.alpha = 0.2f;
    const double b = indirect_mean(p, passes) / reference - 1.0;
    std::printf("Cornell box, %s shrink, %2u passes: indirect mean %+.4f against the reference\n",
                name_of(kEstimatorNames, estimator), passes, b);
    return b;
  };
  // pd's footprints are normalised about each shading point at the walls (gather_reach.h) and
  // by their covered share at edges: its corners are not dark at one pass, and shrinking keeps it.
  const double pd1 = bias(PM_ESTIMATOR_PD, 1), pd64 = bias(PM_ESTIMATOR_PD, 64);
  EXPECT_LT(std::fabs(pd1), 0.02);
  EXPECT_LT(std::fabs(pd64), 0.01);
  const double knn1 = bias(PM_ESTIMATOR_KNN, 1), knn64 = bias(PM_ESTIMATOR_KNN, 64);
  EXPECT_LT(std::fabs(knn64), 0.6 * std::fabs(knn1));
  for (uint32_t passes : {1u, 64u}) EXPECT_LT(std::fabs(bias(PM_ESTIMATOR_RADIUS, passes)), 0.015);
}

TEST(Progressive, TimeBudgetStopsWithinOnePass) {
  PhotonSettings p;
  p.photons = 20000;
  p.estimator = PM_ESTIMATOR_RADIUS;
  RenderSettings settings = test::photon_render_settings(p, 1000);
  settings.control_paths = 0;  // no error control after the passes: the budget is what is tested
  // A budget of several passes wherever it runs (under the sanitizers a pass takes many times
  // longer): two passes timed first on a renderer of their own (the second: the first warms up).
  Renderer timing(device(), sphere().scene, settings);
  PassBudget two;
  two.max_passes = 2;
  std::vector<double> pass_ends;
  ProgressiveCallbacks timed;
  timed.after_pass = [&](const PassReport& r) { pass_ends.push_back(r.seconds); };
  render_progressive(timing, 0, two, nullptr, 0, timed);
  ASSERT_EQ(pass_ends.size(), 2u);
  const double pass_seconds = pass_ends[1] - pass_ends[0];
  Renderer renderer(device(), sphere().scene, settings);
  PassBudget budget;
  budget.max_passes = 1000;
  budget.seconds = std::max(0.5, 6 * pass_seconds);
  double longest_pass = 0, previous = 0;
  ProgressiveCallbacks callbacks;
  callbacks.after_pass = [&](const PassReport& r) {
    longest_pass = std::max(longest_pass, r.seconds - previous);
    previous = r.seconds;
  };
  const ProgressiveResult r = render_progressive(renderer, 0, budget, nullptr, 0, callbacks);
  EXPECT_EQ(r.stopped_by, "time");
  EXPECT_GE(r.seconds, budget.seconds);
  EXPECT_LT(previous - longest_pass, budget.seconds) << "one pass fewer would not have reached the budget";
  EXPECT_GT(r.passes, 1u);
}

TEST(Progressive, TargetErrorStopsAtTheTarget) {
  PhotonSettings p;
  p.photons = 20000;
  p.estimator = PM_ESTIMATOR_RADIUS;
  PassBudget budget;
  budget.max_passes = 1000;
  budget.target_error = 0.03;
  const SphereError e = render_sphere(p, budget);
  std::printf("target 0.03: %u passes, estimate %.4f, true mean |error| %.4f\n", e.result.passes, e.estimate, e.mean_abs);
  EXPECT_EQ(e.result.stopped_by, "error");
  EXPECT_LE(e.estimate, budget.target_error);
  EXPECT_GE(e.result.passes, kMinPassesForError);
  // The true error against the exact answer: at the target, up to the estimate's own noise.
  EXPECT_LE(e.mean_abs, budget.target_error * 1.1);
}

TEST(Progressive, AFrameStoppedByItsErrorEndsWithItsFinalEstimateUnderTheTarget) {
  // A pass's reading adds a few control paths at a time, and read through a control that noisy
  // (the spot-lit box: a small lamp's paths are heavy-tailed) the estimate can dip under the
  // target and rise over it again once the frame's final estimate tops the control up: final
  // gathering over photons stopped after 14 passes of seed 2 on a reading under 2 % whose final
  // estimate read 2.05 %. The frame stops only once the topped-up control agrees (15 passes,
  // 1.88 %).
  PhotonSettings p;
  p.photons = 20000;
  p.progressive = kProgressiveShrink;
  p.final_gather = 16;
  PassBudget budget;
  budget.max_passes = 400;
  budget.target_error = 0.02;
  const Scene box = test::spot_box();
  for (uint32_t seed = 1; seed <= 4; ++seed) {
    RenderSettings settings = test::photon_render_settings(p, budget.max_passes);
    settings.width = settings.height = 48;
    settings.control_paths = 256;
    settings.seed = seed;
    Renderer renderer(device(), box, settings);
    const ProgressiveResult result = render_progressive(renderer, 0, budget, nullptr, 0);
    std::printf("seed %u: %u passes, stopped by %s, estimate %.4f\n", seed, result.passes, result.stopped_by.c_str(),
                result.error);
    EXPECT_EQ(result.stopped_by, "error") << seed;
    EXPECT_LE(result.error, budget.target_error) << seed;
  }
}

TEST(Progressive, DeviceMemoryDoesNotGrowWithPasses) {
  PhotonSettings p;
  p.photons = 20000;
  // The device keeps its sort's scratch between renderers (sized by the map's room): one render
  // first, so that both measured renders find it as a frame leaves it.
  Renderer(device(), sphere().scene, test::photon_render_settings(p, 1)).render(0);
  uint64_t peak[2];
  for (uint32_t passes : {1u, 8u}) {
    device().reset_peak();
    const uint64_t before = device().allocated_bytes();
    Renderer renderer(device(), sphere().scene, test::photon_render_settings(p, passes));
    renderer.render(0);
    peak[passes > 1] = device().peak_allocated_bytes() - before;
  }
  EXPECT_EQ(peak[0], peak[1]);
}

// A checkpointed frame killed with SIGKILL and resumed ends bit for bit as an uninterrupted run.
class ProgressiveCli : public test::PmrenderProcessTest {};

// Under a budget (--time, --target-error) photon passes shrink unless --progressive says
// otherwise: a budget asks for as much accuracy as the time buys, and averaged passes keep their
// bias however many there are. A fixed --passes keeps averaging.
TEST_F(ProgressiveCli, ABudgetMakesPhotonPassesShrinkUnlessToldOtherwise) {
  auto progressive_of = [&](const std::string& args) {
    const std::string file = (dir_ / "budget.exr").string();
    const test::ProcessResult r =
        pmrender("render --backend opencl --resolution 16x16 --photons 2000 --control-paths 0 " + args + " -o " + file);
    EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
    for (const auto& [name, value] : read_exr(file).attributes) {
      if (name != "pmrender/settings") continue;
      const size_t at = value.find("progressive=");
      return at == std::string::npos ? value : value.substr(at, value.find(' ', at) - at);
    }
    return std::string("no settings attribute");
  };
  EXPECT_EQ(progressive_of("--time 0.05"), "progressive=shrink");
  EXPECT_EQ(progressive_of("--target-error 0.9"), "progressive=shrink");
  EXPECT_EQ(progressive_of("--passes 2"), "progressive=average");
  EXPECT_EQ(progressive_of("--time 0.05 --progressive average"), "progressive=average");
  EXPECT_EQ(progressive_of("--passes 2 --progressive shrink"), "progressive=shrink");
}

// Under a target error --verbose prints the control's reading as the passes double, with the part
// of the error that is bias at least, and the header carries that floor beside the estimate.
TEST_F(ProgressiveCli, UnderATargetErrorVerboseShowsTheControlsReadingsAndTheHeaderTheBiasFloor) {
  const std::string file = (dir_ / "readings.exr").string();
  // 32 x 32: at 16 x 16 the control's own noise can exceed the film's whole error, and then no
  // part of it is known to be bias.
  const test::ProcessResult r = pmrender("render --backend opencl --resolution 32x32 --photons 2000 "
                                         "--target-error 0.001 --passes 8 --verbose -o " + file);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* passes : {"frame 0: 4 passes in ", "frame 0: 8 passes in "}) {
    const size_t at = r.out.find(passes);
    ASSERT_NE(at, std::string::npos) << r.out;
    const std::string line = r.out.substr(at, r.out.find('\n', at) - at);
    EXPECT_NE(line.find("error "), std::string::npos) << line;
    EXPECT_NE(line.find("bias at least "), std::string::npos) << line;
  }
  EXPECT_EQ(r.out.find("frame 0: 6 passes in "), std::string::npos) << "only as the passes double";
  std::map<std::string, std::string> h;
  for (const auto& [name, value] : read_exr(file).attributes) h[name] = value;
  ASSERT_FALSE(h["pmrender/error_bias_floor"].empty());
  ASSERT_FALSE(h["pmrender/error_estimate"].empty());
  EXPECT_GE(std::stod(h["pmrender/error_bias_floor"]), 0.0);
  EXPECT_LE(std::stod(h["pmrender/error_bias_floor"]), std::stod(h["pmrender/error_estimate"]));
}

TEST_F(ProgressiveCli, KilledCheckpointedFrameResumesToTheSameImage) {
  const std::string common = "render --backend opencl --resolution 32x32 --photons 4000 --passes 40 "
                             "--progressive shrink --float --checkpoint-every 4 -o ";
  const std::string full = (dir_ / "full.exr").string(), killed = (dir_ / "killed.exr").string();
  ASSERT_EQ(pmrender(common + full).exit_code, 0);
  // The same command as its own process, killed once its first checkpoint is on disk.
  std::vector<std::string> words;
  std::istringstream split(common + killed);
  for (std::string w; split >> w;) words.push_back(w);
  const std::string binary = test::pmrender_binary();
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    std::vector<char*> argv{const_cast<char*>(binary.c_str())};
    for (std::string& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    freopen("/dev/null", "w", stdout);
    freopen("/dev/null", "w", stderr);
    execv(binary.c_str(), argv.data());
    _exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(killed + ".pmstate") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(fs::exists(killed + ".pmstate")) << "no checkpoint was written";
  ASSERT_FALSE(exr_is_complete(killed)) << "the frame finished before it could be killed";
  const test::ProcessResult resumed = pmrender(common + killed + " --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.out.find("continued from its checkpoint"), std::string::npos) << resumed.out;
  EXPECT_FALSE(fs::exists(killed + ".pmstate")) << "a finished frame leaves no checkpoint";
  const FrameImage a = read_exr(full), b = read_exr(killed);
  for (const ImageLayer& layer : a.layers) EXPECT_EQ(layer.rgb, b.find(layer.name)->rgb) << "layer " << layer.name;
}

}  // namespace
}  // namespace pm

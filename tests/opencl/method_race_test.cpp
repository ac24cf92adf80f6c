// --method auto's race (render/method_race.h) on PoCL, on the closed diffuse sphere (test::LitSphere) whose
// indirect light is known in closed form: the frame the winner finishes meets the target error in
// truth, not only by its own estimate; a candidate whose bias keeps it above the target is passed
// over however cheap it is; and the winner goes on from its race passes to the very image it
// would have rendered alone. In the spot-lit box (test::spot_box), final gathering over a coarse
// radiosity solution leads the race's first rounds and then stops falling at its solution's
// bias: the frame goes to the path tracer.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "render/path/path_settings.h"
#include "render/method_race.h"
#include "render/progressive.h"
#include "render/radiosity/radiosity_settings.h"
#include "render/renderer.h"
#include "support/analytic_scenes.h"
#include "support/lit_boxes.h"
#include "support/device_checks.h"
#include "support/render_settings.h"

namespace pm {
namespace {

Device& device() { return test::shared_opencl_device(); }
const test::LitSphere& sphere() { return test::lit_sphere(); }

RenderSettings frame_settings() {
  RenderSettings s;
  s.width = s.height = 32;
  return s;
}

std::shared_ptr<const MethodSettings> photons(int progressive, bool coverage = true, uint32_t final_gather = 0) {
  auto p = std::make_shared<PhotonSettings>();
  p->photons = 20000;
  p->progressive = progressive;
  p->footprint_coverage = coverage;
  p->final_gather = final_gather;
  p->validate();
  return p;
}

std::shared_ptr<const MethodSettings> path() {
  auto p = std::make_shared<PathSettings>();
  p->validate();
  return p;
}

std::shared_ptr<const MethodSettings> radiosity() {
  auto r = std::make_shared<RadiositySettings>();
  r->validate();
  return r;
}

// The race, then the winner's frame to the end of the budget, as `pmrender render` runs them.
struct AutoFrame {
  MethodChoice choice;
  ProgressiveResult result;
  double true_error = 0;  // relative mean absolute error of the indirect light against the closed form
};

AutoFrame render_auto(const std::vector<RaceCandidate>& candidates, const PassBudget& budget) {
  AutoFrame f;
  f.choice = race_methods(device(), sphere().scene, frame_settings(), candidates, 0, budget);
  std::printf("winner %s: %s\n", candidates[f.choice.winner].label.c_str(), f.choice.summary().c_str());
  f.result = render_progressive(*f.choice.renderer, 0, budget, &f.choice.sums, f.choice.race_seconds);
  const std::vector<float> indirect = f.choice.renderer->read_image().find("indirect")->rgb;
  for (float v : indirect) f.true_error += std::fabs(v - sphere().expected);
  f.true_error /= double(indirect.size()) * sphere().expected;
  std::printf("  %u passes, stopped by %s, estimate %.4f, true %.4f\n", f.result.passes, f.result.stopped_by.c_str(),
              f.result.error, f.true_error);
  return f;
}

TEST(MethodRace, TheFrameMeetsItsTargetErrorInTruth) {
  PassBudget budget;
  budget.max_passes = 100000;
  budget.target_error = 0.05;
  const AutoFrame f = render_auto({{"photon", photons(kProgressiveShrink)},
                                   {"photon --final-gather 16", photons(kProgressiveShrink, true, 16)},
                                   {"path", path()},
                                   {"radiosity", radiosity()}},
                                  budget);
  // Radiosity's one pass ends its frame ("passes"); the others stop on the estimate.
  EXPECT_TRUE(f.result.stopped_by == "error" || f.result.stopped_by == "passes") << f.result.stopped_by;
  EXPECT_LE(f.result.error, budget.target_error);
  EXPECT_LE(f.true_error, 1.5 * budget.target_error) << "the issue's bound: at most 1.5x the target, in truth";
  EXPECT_GE(f.result.seconds, f.choice.race_seconds) << "the frame's time counts the race";
  ASSERT_EQ(f.choice.entries.size(), 4u);
  for (const RaceEntry& e : f.choice.entries) EXPECT_FALSE(e.fate.empty()) << e.label;
}

TEST(MethodRace, ABiasedCandidateIsPassedOverHoweverCheap) {
  // pd averaging passes with its flux spread over whole flat ellipses, which the curved sphere
  // leaves before their rims (footprint coverage off): about 5 % too dark whatever the passes
  // (progressive_test.cpp), at a fraction of the path tracer's time per pass here.
  PassBudget budget;
  budget.max_passes = 100000;
  budget.target_error = 0.03;
  const AutoFrame f = render_auto({{"biased photon", photons(kProgressiveAverage, false)}, {"path", path()}}, budget);
  EXPECT_EQ(f.choice.entries[f.choice.winner].label, "path");
  EXPECT_LE(f.true_error, 1.5 * budget.target_error);
}

TEST(MethodRace, TheWinnerGoesOnAsIfItHadRenderedAlone) {
  PassBudget race_budget;
  race_budget.max_passes = 100000;
  race_budget.seconds = 0.5;
  MethodChoice choice = race_methods(device(), sphere().scene, frame_settings(),
                                     {{"photon", photons(kProgressiveShrink)}, {"path", path()}}, 0, race_budget);
  const uint32_t raced = choice.sums.passes;
  ASSERT_GT(raced, 0u);
  PassBudget rest;
  rest.max_passes = raced + 3;
  render_progressive(*choice.renderer, 0, rest, &choice.sums, choice.race_seconds);
  const std::vector<float> continued = choice.renderer->read_image().find("indirect")->rgb;

  RenderSettings alone = frame_settings();
  alone.method = choice.renderer->method() ? (choice.winner == 0 ? photons(kProgressiveShrink) : path()) : nullptr;
  Renderer renderer(device(), sphere().scene, alone);
  render_progressive(renderer, 0, rest, nullptr, 0);
  const std::vector<float> plain = renderer.read_image().find("indirect")->rgb;
  ASSERT_EQ(continued.size(), plain.size());
  size_t differing = 0;
  for (size_t i = 0; i < plain.size(); ++i) differing += continued[i] != plain[i] ? 1 : 0;
  EXPECT_EQ(differing, 0u) << raced << " race passes and 3 more against " << rest.max_passes << " alone";
}

TEST(MethodRace, TheFrameGoesToTheCandidateThatReachesTheTargetNotToTheFirstLeader) {
  // Elements of 0.1 (the box is 1 across), light and link rays from the vertices only: gathered
  // with 4 rays a pass, its error falls fastest at first and stops at about 3.7 % (measured
  // 3.66 %). Asked for 1.5 %, the race chose it on its first readings (a power law through them)
  // and the frame ran 2946 passes, 50 s, until its estimate levelled off at 3.19 %. Now its
  // forecast has the floor its bias measured along the control's paths gives
  // (render/error_forecast.h, bias_probe_test.cpp: about 3.1 % here), and where a floor is not yet
  // clear the duel (render/race_referee.h) keeps the path tracer rendering beside it.
  const auto coarse = test::coarse_spot_box_radiosity(4);
  auto traced = std::make_shared<PathSettings>();
  traced->bounces = 2;
  traced->validate();
  RenderSettings settings;
  settings.width = settings.height = 48;
  PassBudget budget;
  budget.max_passes = 100000;
  budget.target_error = 0.015;
  const Scene box = test::spot_box();
  MethodChoice choice =
      race_methods(device(), box, settings, {{"radiosity --final-gather 4", coarse}, {"path", traced}}, 0, budget);
  std::printf("%s\n", choice.summary().c_str());
  for (const std::string& line : choice.rounds) std::printf("  %s\n", line.c_str());
  EXPECT_EQ(choice.entries[choice.winner].label, "path");
  const ProgressiveResult result = render_progressive(*choice.renderer, 0, budget, &choice.sums, choice.race_seconds);
  std::printf("  %u passes in %.2f s, stopped by %s at %.2f %%\n", result.passes, result.seconds,
              result.stopped_by.c_str(), 100.0 * result.error);
  EXPECT_EQ(result.stopped_by, "error");
  EXPECT_LE(result.error, budget.target_error);
}

TEST(MethodRace, ABiasProbeNearTheTargetResolvesAheadOfTheControl) {
  // The probe's first readings read high, and near the target the forecast turns on them: final
  // gathering over the coarse solution (its bias about 3.1 %) asked for 1.5 % doubles its probe to
  // the control's most paths in the race's first round (when a probe stops short of them:
  // MethodRaceForecast.AProbeReadingUnderHalfTheTargetAsksForNoMorePaths).
  RenderSettings settings;
  settings.width = settings.height = 48;
  settings.control_paths = 256;
  PassBudget budget;
  budget.max_passes = 100000;
  budget.target_error = 0.015;
  const MethodChoice choice =
      race_methods(device(), test::spot_box(), settings,
                   {RaceCandidate{"radiosity --final-gather 4", test::coarse_spot_box_radiosity(4)}}, 0, budget);
  ASSERT_FALSE(choice.rounds.empty());
  std::printf("  %s\n", choice.rounds.front().c_str());
  const std::string most = " over " + std::to_string(settings.control_paths * kControlPathsGrowth) + " paths";
  EXPECT_NE(choice.rounds.front().find(most), std::string::npos) << choice.rounds.front();
}

}  // namespace
}  // namespace pm

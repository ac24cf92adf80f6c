// --method auto: the methods race on the frame itself and the one forecast to reach the budget's
// error soonest (--target-error) or to be the most accurate when the time is up (--time) goes on
// (docs/method-auto.md). Every candidate renders the frame's first passes on a renderer of its own,
// in rounds of doubling time, and after each round its own error estimate (render/bias_control.h:
// noise and bias together) is read and forecast forwards; a candidate clearly behind the best is
// dropped, its time spent; under a target error the race ends in a duel of the two best
// (race_referee.h). The winner's renderer keeps its film, so the frame continues from the passes
// it already has: the race costs the losers' time only.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "render/error_forecast.h"
#include "render/progressive.h"
#include "render/race_referee.h"
#include "render/renderer.h"

namespace pm {

struct RaceCandidate {
  std::string label;  // how the log and the EXR header name it, e.g. "photon", "path"
  std::shared_ptr<const MethodSettings> method;
};

// What a candidate did in the race.
struct RaceEntry {
  std::string label;
  std::vector<ErrorReading> readings;
  ErrorForecast forecast;
  double forecast_value = 0;  // seconds to the target error, or the error when the time is up
  std::string fate;           // "chosen", "dropped after N s", "reached the target"...
};

struct MethodChoice {
  size_t winner = 0;  // index into the candidates
  std::vector<RaceEntry> entries;
  double race_seconds = 0;           // wall time of the race (every candidate's passes): the frame's time so far
  double setup_seconds = 0;          // the candidates' renderers built (scene upload, buffers): start-up
  std::unique_ptr<Renderer> renderer;  // the winner's, its film holding `sums`
  FilmSums sums;                     // the winner's passes so far
  std::vector<std::string> rounds;   // a line per round: the candidates' readings and forecasts (--verbose)
  // One line for logs and the EXR header: each candidate's passes, time, error and forecast.
  std::string summary() const;
};

// The first round's time per candidate without a time budget (then it doubles each round).
constexpr double kFirstRoundSeconds = 0.05;
// Under a target error, a bias probe (final gathering over radiosity's, render/bias_control.h)
// that reads a bias over this share of the target doubles its paths ahead of the control's, up to
// the control's most: its first readings read high (a mean absolute error read through the
// differences' own noise: 0.93 % at 1024 paths per control pixel on Conference, 0.67 % at 16384),
// and near the target the forecast turns on it (at 0.85 % under a target of 1 % it forecast 8.2 s
// where the method alone took 3.9 s; docs/method-auto.md, "The probe resolved near the target").
// Below the share a bias lengthens the time to the target by at most a third.
constexpr double kProbeResolveShare = 0.5;
// Whether a probe's reading (paired_bias) calls for more paths under `target`: the bias it reads,
// less a standard error (the forecast's floor), is kProbeResolveShare of the target or more.
bool probe_reads_near_target(const BiasEstimate& probe, double target);

// Races candidates on `frame` under budget (seconds or target_error must be set) and returns the
// winner's renderer, mid-frame. settings: the frame's settings but for the method (the
// candidates'). Throws SettingError when no budget is set or there is no candidate.
MethodChoice race_methods(Device& device, const Scene& scene, const RenderSettings& settings,
                          const std::vector<RaceCandidate>& candidates, int frame, const PassBudget& budget);

}  // namespace pm

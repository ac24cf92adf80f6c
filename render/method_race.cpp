// The race of --method auto (method_race.h): rounds, forecasts, drops and the winner.
#include "render/method_race.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "render/errors.h"
#include "render/interruption.h"
#include "render/scene_upload.h"

namespace pm {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::string percent(double e) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f %%", 100.0 * e);
  return text;
}

std::string seconds_text(double s) {
  char text[32];
  if (!std::isfinite(s)) return "never";
  std::snprintf(text, sizeof(text), "%.3g s", s);
  return text;
}

// A candidate on the track. Its film at the control pixels is kept at every reading, so that all
// its readings (and every candidate's) are measured against the same control, the latest: the
// control's own noise inflates an early reading, and a rate fitted across controls of different
// sizes would mistake the control sharpening for the film converging.
struct Runner {
  std::unique_ptr<Renderer> renderer;
  double own_seconds = 0;
  double start_seconds = 0;  // of own_seconds, beginning the frame (before any pass)
  RaceEntry entry;
  std::vector<std::vector<float4>> films;  // per reading
  std::vector<ControlFilmPasses> film_passes;  // per reading: the passes behind it
  double last_upper = -1;  // the last reading's error plus two standard errors
  bool out = false;
  int duel_rounds = 0;  // rounds run in the duel (race_referee.h)
  uint32_t cap = 0;  // its passes at most: the method's (radiosity: one) or --passes, the lower
  // Its bias measured along the control's paths, where its method can (grow_bias_probe): as
  // many paths per control pixel as the control has, grown beside it.
  SharedControl probe;
  bool probes = true;  // false once its renderer says it has no probe

  // Passes done: where it stands is where it stays (radiosity after its pass, or --passes reached).
  ErrorDecay decay() const {
    if (renderer->passes_done() >= cap) return ErrorDecay::fixed;
    if (!renderer->method()->may_be_biased()) return ErrorDecay::monte_carlo;
    return renderer->method()->passes_are_samples() ? ErrorDecay::sampled : ErrorDecay::measured;
  }
  // Whether its forecast rests on a measured rate (or on a final error): a reading far enough
  // before its last one, as forecast_error looks for (in the duel the runner-up's readings come
  // closer together than kRateSpan).
  bool measured() const {
    if (decay() == ErrorDecay::fixed) return !entry.readings.empty();
    if (entry.readings.size() < 2) return false;
    const double first = entry.readings.front().seconds - start_seconds;
    return first > 0 && entry.readings.back().seconds - start_seconds >= kRateSpan * first;
  }
};

// The candidate's passes for one round: at least one, then while the next is forecast to end
// within the round's time (another_pass_fits).
void run_round(Runner& r, double slice) {
  const Clock::time_point begun = Clock::now();
  const uint32_t first = r.renderer->passes_done();
  while (r.renderer->passes_done() < r.cap &&
         another_pass_fits(seconds_since(begun), r.renderer->passes_done() - first, slice)) {
    throw_if_interrupted();
    r.renderer->run_pass();
    r.renderer->wait();
  }
  r.own_seconds += seconds_since(begun);
}

// One line of --verbose's account of the race: each candidate still in, its own time, its
// error against the latest control, its rate and what it is forecast to need.
std::string round_text(int round, RacePhase phase, double elapsed, const std::vector<Runner>& runners,
                       const std::vector<RaceStanding>& standings, bool by_error) {
  std::string text = (phase == RacePhase::duel ? "duel round " : "race round ") + std::to_string(round + 1) + " at " +
                     seconds_text(elapsed) + ":";
  for (size_t i = 0; i < runners.size(); ++i) {
    const Runner& r = runners[i];
    if (r.out) continue;
    const ErrorForecast& f = r.entry.forecast;
    const ErrorReading& last = r.entry.readings.back();
    std::string own_floor = last.floor >= 0 ? ", bias at least " + percent(last.floor) : "";
    if (last.measured_floor >= 0)
      own_floor += ", bias measured " + percent(last.measured_floor) + " over " + std::to_string(r.probe.paths) + " paths";
    char part[448];
    std::snprintf(part, sizeof(part), " %s %s, error %s (+-%.2f%s), rate %.2f%s%s%s, %s %s;", r.entry.label.c_str(),
                  seconds_text(r.own_seconds).c_str(), percent(last.error).c_str(), 100.0 * last.error_stderr,
                  own_floor.c_str(), f.rate,
                  standings[i].measured ? "" : " (assumed)", f.floor > 0 ? " over a floor of " : "",
                  f.floor > 0 ? percent(f.floor).c_str() : "", by_error ? "needs" : "forecast",
                  by_error ? seconds_text(standings[i].value).c_str() : percent(standings[i].value).c_str());
    text += part;
  }
  text.pop_back();
  return text;
}

// The leader's round in the duel: its time in passes doubles, as in the race, but no further than
// it is forecast to need to reach the target (where the duel's round would otherwise run on past
// the target by up to the round's length), and not less than a quarter of it, so that its next
// reading is far enough from this one to be told from it.
double duel_lead_slice(const Runner& leader, double remaining) {
  const double passes = std::max(kFirstRoundSeconds, leader.own_seconds - leader.start_seconds);
  return std::clamp(remaining, kDuelShare * passes, passes);
}

// Every reading of r measured again against control.
void measure(Runner& r, const SharedControl& control) {
  const ControlGrid& grid = r.renderer->error_control_grid();
  // Its measured bias is the solution's, the same under every reading.
  const BiasEstimate probed =
      r.probe.paths > 0 && r.probe.bounces == control.bounces ? paired_bias(r.probe, grid, control_level(control)) : BiasEstimate{};
  // The control's paths follow its bounces: a film of other bounces cannot be read against them
  // (every method takes --bounces, so this holds for the command line's candidates).
  const bool comparable = r.renderer->control_bounces() == control.bounces;
  for (size_t i = 0; i < r.films.size(); ++i) {
    const BiasEstimate e = comparable ? compare_with_control(control.sums, r.films[i], grid, control.paths,
                                                             kControlRegionSide, r.film_passes[i])
                                      : BiasEstimate{};
    r.entry.readings[i].error = e.known ? e.mean_abs_error : -1;
    r.entry.readings[i].error_stderr = e.known ? e.mean_abs_error_stderr : 0;
    r.entry.readings[i].floor = e.known ? e.bias_floor : -1;
    r.entry.readings[i].floor_upper = e.known ? e.bias_ceiling : -1;
    r.entry.readings[i].mean_square = e.known ? e.mean_square : -1;
    if (probed.known) {
      ErrorReading& reading = r.entry.readings[i];
      reading.measured_floor = probed.mean_abs_error - probed.mean_abs_error_stderr;
      reading.measured_floor_stderr = probed.mean_abs_error_stderr;
      // The part of its error that is bias, at most: the measured bias with two standard errors.
      reading.floor_upper = probed.mean_abs_error + probed.mean_abs_error_stderr;
    }
    if (i + 1 == r.films.size()) r.last_upper = e.known ? e.mean_abs_error_upper : -1;
  }
}

// Doubles r's bias probe, ahead of the control, while the bias it reads (less a standard error,
// as the forecast's floor) is kProbeResolveShare of the target or more, up to `most` paths per
// control pixel.
void resolve_probe(Runner& r, const SharedControl& control, double target, uint64_t most) {
  const ControlGrid& grid = r.renderer->error_control_grid();
  while (r.probes && r.probe.paths > 0 && r.probe.paths < most &&
         probe_reads_near_target(paired_bias(r.probe, grid, control_level(control)), target))
    r.probes = r.renderer->grow_bias_probe(r.probe, uint32_t(std::min(r.probe.paths, most - r.probe.paths)));
}

}  // namespace

bool probe_reads_near_target(const BiasEstimate& probe, double target) {
  return probe.known && probe.mean_abs_error - probe.mean_abs_error_stderr >= kProbeResolveShare * target;
}

std::string MethodChoice::summary() const {
  std::string text;
  for (size_t i = 0; i < entries.size(); ++i) {
    const RaceEntry& e = entries[i];
    if (!text.empty()) text += "; ";
    text += e.label + ": ";
    if (e.readings.empty()) {
      text += e.fate;
      continue;
    }
    const ErrorReading& r = e.readings.back();
    char head[96];
    std::snprintf(head, sizeof(head), "%u pass%s in %s, error %s", r.passes, r.passes == 1 ? "" : "es",
                  seconds_text(r.seconds).c_str(), percent(r.error).c_str());
    text += head;
    text += ", " + e.fate;
  }
  return text;
}

MethodChoice race_methods(Device& device, const Scene& scene, const RenderSettings& settings,
                          const std::vector<RaceCandidate>& candidates, int frame, const PassBudget& budget) {
  if (!budget.open_ended())
    throw SettingError("method", "auto chooses the method that meets a budget: give --time or --target-error");
  if (candidates.empty()) throw SettingError("method", "auto: no method to choose from");
  if (settings.control_paths == 0)
    throw SettingError("control-paths", "0 leaves --method auto nothing to measure the methods with; give it paths");
  const bool by_error = budget.target_error > 0;
  const double target = budget.target_error;

  MethodChoice choice;
  std::vector<Runner> runners(candidates.size());
  const Clock::time_point setup_begun = Clock::now();
  // The candidates' host work that depends on the scene alone (radiosity's mesh) first, on
  // threads of its own, once for the candidates one run serves: it runs beside the BVH build and
  // the renderers' set-up, and on into the race's first round.
  const SceneMeasures measures = measure_scene(scene);
  std::vector<std::shared_ptr<const HostWorkAhead>> host_work(candidates.size());
  for (size_t i = 0; i < candidates.size(); ++i) {
    for (size_t j = 0; j < i && !host_work[i]; ++j)
      if (host_work[j] && host_work[j]->serves(*candidates[i].method, measures)) host_work[i] = host_work[j];
    if (!host_work[i]) host_work[i] = candidates[i].method->begin_host_work(scene, measures);
  }
  // One BVH, one set of packed textures for all the candidates' renderers.
  StepClock clock;
  std::vector<StartupStep> steps;
  const std::shared_ptr<const SceneUpload> upload = prepare_scene_upload(scene, clock, &steps);
  for (size_t i = 0; i < candidates.size(); ++i) {
    RenderSettings s = settings;
    s.method = candidates[i].method;
    runners[i].entry.label = candidates[i].label;
    runners[i].renderer = std::make_unique<Renderer>(device, scene, s, upload, host_work[i]);
    const uint32_t method_cap = runners[i].renderer->method()->max_passes();
    runners[i].cap = method_cap > 0 ? std::min(budget.max_passes, method_cap) : budget.max_passes;
  }
  device.synchronize();
  choice.setup_seconds = seconds_since(setup_begun);
  const Clock::time_point race_begun = Clock::now();
  // The frame begins on each just before its first round, timed as its own: a method may do much
  // of its work there (radiosity solves its links for the frame's lights before its one pass).
  // What an earlier candidate built and this one would build the same (radiosity's mesh and
  // links) is copied rather than rebuilt.
  const auto begin_frame = [&](size_t i) {
    Runner& r = runners[i];
    const Clock::time_point begun = Clock::now();
    for (size_t j = 0; j < i; ++j)
      if (r.renderer->method() && runners[j].renderer && runners[j].renderer->method() &&
          r.renderer->method()->adopt_setup(*runners[j].renderer->method()))
        break;
    r.renderer->begin_frame(frame);
    r.renderer->wait();
    r.own_seconds = r.start_seconds = seconds_since(begun);
  };

  // With a time budget the race takes up to kRaceShareOfTime of it; without, it starts short.
  // The rounds double.
  double slice = budget.seconds > 0 ? 0.01 * budget.seconds : kFirstRoundSeconds;
  // Every candidate is measured against one control (render/bias_control.h): the same paths at
  // the same pixels, so that their errors compare and an unbiased method is measured as the
  // others are. It doubles every round, so that the readings sharpen as the forecasts narrow.
  SharedControl control;
  uint64_t control_step = settings.control_paths;
  double control_seconds = 0;
  const uint64_t control_cap = uint64_t(settings.control_paths) * kControlPathsGrowth;
  int reached = -1;  // a candidate that met the target error during the race
  int best = 0;
  RacePhase phase = RacePhase::race;
  double best_remaining = 0;  // the leader's own seconds still needed to the target, as last forecast
  for (int round = 0; phase != RacePhase::over; ++round, slice *= 2) {
    const bool duelling = phase == RacePhase::duel;
    const double lead_slice = duelling ? duel_lead_slice(runners[best], best_remaining) : slice;
    for (size_t i = 0; i < runners.size(); ++i) {
      Runner& r = runners[i];
      if (round == 0) begin_frame(i);
      if (r.out || r.decay() == ErrorDecay::fixed) continue;
      // In the duel the runner-up renders a share of the leader's time (race_referee.h).
      run_round(r, duelling && int(i) != best ? kDuelShare * lead_slice : lead_slice);
      r.duel_rounds += duelling ? 1 : 0;
      r.entry.readings.push_back({r.own_seconds, -1, r.renderer->passes_done()});
      r.films.push_back(r.renderer->film_at_control());
      r.film_passes.push_back(r.renderer->film_passes_at_control());
    }
    if (round == 0) host_work.clear();  // every candidate has begun its frame: the host meshes go with their methods
    // The control grows on any renderer still racing, while it has taken less time than the
    // candidates (its first paths always: without them nothing is measured).
    double racing_seconds = 0;
    for (const Runner& r : runners) racing_seconds += r.own_seconds;
    for (Runner& r : runners)
      if (!r.out && control.paths < control_cap && (control.paths == 0 || control_seconds < racing_seconds)) {
        const Clock::time_point begun = Clock::now();
        r.renderer->grow_shared_control(control, uint32_t(std::min(control_step, control_cap - control.paths)));
        control_seconds += seconds_since(begun);
        control_step = control.paths;  // doubles it
        break;
      }
    // The probes of the candidates that measure their own bias follow the control's paths.
    for (Runner& r : runners) {
      if (r.out || !r.probes || r.decay() != ErrorDecay::sampled) continue;
      if (r.probe.paths < control.paths) r.probes = r.renderer->grow_bias_probe(r.probe, uint32_t(control.paths - r.probe.paths));
      if (by_error) resolve_probe(r, control, target, control_cap);
    }
    for (size_t i = 0; i < runners.size(); ++i) {
      Runner& r = runners[i];
      if (r.out) continue;
      measure(r, control);
      const ErrorReading& last = r.entry.readings.back();
      if (by_error && reached < 0 && last.error >= 0 && r.last_upper <= target &&
          (last.passes >= kMinPassesForError || r.decay() == ErrorDecay::fixed))
        reached = int(i);
    }
    if (reached >= 0) break;

    // Forecasts: the own seconds still needed to the target error, or the error when the time is up.
    const double elapsed = seconds_since(race_begun);
    const double remaining = std::max(0.0, budget.seconds - elapsed);
    std::vector<RaceStanding> standings(runners.size());
    for (size_t i = 0; i < runners.size(); ++i) {
      Runner& r = runners[i];
      RaceStanding& st = standings[i];
      st.out = r.out;
      if (r.out) continue;
      r.entry.forecast =
          forecast_error(r.entry.readings, r.decay(), r.start_seconds, r.renderer->method()->noise_rate());
      const bool known = !r.entry.readings.empty() && r.entry.readings.back().error >= 0;
      if (!known) r.entry.forecast_value = std::numeric_limits<double>::infinity();
      else if (by_error) r.entry.forecast_value = r.entry.forecast.seconds_to_proof(target);
      else r.entry.forecast_value = r.entry.forecast.error_at(r.own_seconds + remaining);
      st.forecast_total = r.entry.forecast_value;
      st.value = by_error ? std::max(0.0, r.entry.forecast_value - r.own_seconds) : r.entry.forecast_value;
      if (by_error && known) st.error_at_ten_times = r.entry.forecast.error_at(10 * r.own_seconds);
      st.measured = r.measured();
      if (known) {
        const ErrorForecast fastest =
            best_case_forecast(r.entry.readings, r.decay(), r.start_seconds, r.renderer->method()->noise_rate());
        st.best_case = by_error ? std::max(0.0, fastest.seconds_to_proof(target) - r.own_seconds)
                                : fastest.error_at(r.own_seconds + remaining);
      }
      st.biased = r.renderer->method() && r.renderer->method()->may_be_biased();
      st.error = known ? r.entry.readings.back().error : -1;
      st.bias_at_most = known ? r.entry.readings.back().floor_upper : -1;
      st.bias_in_forecast =
          known && (r.decay() == ErrorDecay::measured || r.entry.readings.back().measured_floor >= 0);
      st.duel_rounds = r.duel_rounds;
    }
    const RoundCall call = call_round(standings, phase, {by_error, target, budget.seconds, elapsed, round});
    if (call.best < 0) throw DeviceError("--method auto: no candidate's error could be measured");
    best = call.best;
    best_remaining = standings[best].value;
    choice.rounds.push_back(round_text(round, phase, elapsed, runners, standings, by_error));
    for (size_t i : call.dropped) {
      Runner& r = runners[i];
      r.out = true;
      const std::string forecast = by_error ? seconds_text(r.entry.forecast_value) + " to " + percent(target)
                                            : percent(r.entry.forecast_value) + " at the time";
      if (phase == RacePhase::duel)
        r.entry.fate = "behind in the duel after " + std::to_string(r.duel_rounds) + " rounds (forecast " + forecast + ")";
      else if (call.phase == RacePhase::duel && standings[i].value <= kDropTimeRatio * standings[best].value)
        r.entry.fate = "out when the duel began after round " + std::to_string(round + 1) + " (forecast " + forecast + ")";
      else
        r.entry.fate = "dropped after round " + std::to_string(round + 1) + " (forecast " + forecast + ")";
      r.renderer.reset();  // its memory back before the winner goes on
    }
    phase = call.phase;
  }
  choice.winner = size_t(reached >= 0 ? reached : best);
  choice.race_seconds = seconds_since(race_begun);

  for (size_t i = 0; i < runners.size(); ++i) {
    Runner& r = runners[i];
    if (i == choice.winner) {
      r.entry.fate = reached >= 0 ? "reached the target" : "chosen";
      if (reached < 0)
        r.entry.fate += by_error ? " (forecast " + seconds_text(r.entry.forecast_value) + " to " + percent(target) + ")"
                                 : " (forecast " + percent(r.entry.forecast_value) + " at the time)";
      if (r.duel_rounds > 0) r.entry.fate += ", after a duel of " + std::to_string(r.duel_rounds) + " rounds";
    } else if (!r.out && reached >= 0) {
      r.entry.fate = "still racing when " + runners[choice.winner].entry.label + " reached the target";
    } else if (!r.out) {
      r.entry.fate = by_error ? "behind (forecast " + seconds_text(r.entry.forecast_value) + " to " + percent(target) + ")"
                              : "behind (forecast " + percent(r.entry.forecast_value) + " at the time)";
    }
    choice.entries.push_back(r.entry);
  }
  Runner& winner = runners[choice.winner];
  choice.sums = winner.renderer->film_sums();
  choice.sums.control = control;
  choice.renderer = std::move(winner.renderer);
  return choice;
}

}  // namespace pm

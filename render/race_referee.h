// --method auto's decisions after each round of the race (method_race.h), from the candidates'
// forecasts alone: which candidate leads, which are dropped, and when the race narrows to a duel
// or ends; and within a round, whether a candidate begins another pass. Kept apart from the
// rendering so that the rules are tested on their own (tests/unit/race_referee_test.cpp).
//
// Under a target error the race's forecasts rest on well under a second of readings, and two
// kinds of candidate fool them (docs/method-auto.md, "The duel"): final gathering over a radiosity
// solution falls as 1/sqrt(t) at first and then slows towards the solution's own error one bounce
// away, which its first readings cannot show; final gathering over photons falls faster than
// 1/sqrt(t) while its map's bias shrinks, so its early forecast is too slow. So the race does not
// end on its forecasts: once they have settled who leads, the leader renders on and the runner-up
// goes on beside it at a quarter of its time, both read against the same control after every
// round, until one reaches the target, or the runner-up, forecast on readings of its own far
// enough apart, is clearly behind while the leader's forecast has proved itself. The lead
// changes whenever the forecasts say so; the runner-up's part costs at most a fifth of the duel's
// time.
#pragma once

#include <cstddef>
#include <limits>
#include <vector>

namespace pm {

// A candidate as the referee sees it after a round.
struct RaceStanding {
  // Under a target error: the candidate's own seconds still needed to reach it (its forecast less
  // the time it has spent: what is spent is spent). Under a time budget: the error it is forecast
  // to reach when the time is up.
  double value = std::numeric_limits<double>::infinity();
  double forecast_total = std::numeric_limits<double>::infinity();  // by error: its whole own time to the target
  // by error: the error forecast at ten times its own time, which ranks the candidates when none
  // is forecast to reach the target
  double error_at_ten_times = std::numeric_limits<double>::infinity();
  bool measured = false;  // its forecast rests on a measured rate (or on its final error)
  // value as the fastest fall its method allows would make it (best_case_forecast): before its
  // rate is measured, a biased candidate even this puts more than the drop ratio behind the best
  // is dropped (its assumed rate is not what keeps it in). 0: not known (never drops it).
  double best_case = 0;
  bool biased = false;    // its passes may converge to a bias (Renderer::method()->may_be_biased())
  double error = -1;      // its last reading
  double bias_at_most = -1;  // of that reading, the part that is bias at most; -1: not known
  // Its forecast carries its bias: measured along the control's paths (final gathering over
  // radiosity, ErrorReading::measured_floor), or shrinking with its passes and so part of the fall
  // its rate measures (photon passes, with or without final gathering).
  bool bias_in_forecast = false;
  bool out = false;       // dropped earlier
  int duel_rounds = 0;    // rounds it has run in the duel
};

enum class RacePhase { race, duel, over };

struct RaceRules {
  bool by_error = false;         // a target error (else a time budget)
  double target = 0;             // that target error
  double budget_seconds = 0;     // > 0: the time budget
  double elapsed = 0;            // the race's wall time so far
  int round = 0;                 // of the race phase, from 0
};

struct RoundCall {
  int best = -1;                     // the leader; -1: no candidate's error is known
  std::vector<size_t> dropped;       // dropped this round
  RacePhase phase = RacePhase::race; // what the next round is
};

// A candidate is dropped in the race when its forecast is this many times the best's: its
// remaining time under a target error, its error under a time budget.
constexpr double kDropTimeRatio = 2.0;
constexpr double kDropErrorRatio = 1.25;
// Share of a --time budget the race may take before the best candidate goes on alone.
constexpr double kRaceShareOfTime = 0.25;
// Under a target error the race phase ends once it has taken this share of the best's forecast time.
constexpr double kRaceShareOfForecast = 0.2;
// Most rounds of the race phase, and of the duel after it.
constexpr int kMaxRaceRounds = 10;
constexpr int kMaxDuelRounds = 12;
// The duel: a runner-up within kDuelTimeRatio of the best's remaining time is kept for it, within
// kTrustedDuelTimeRatio where the best's forecast is trusted (below: it hides no floor, so what
// the duel could find is only the forecasts' own error). Behind a trusted best, a runner-up 1.6 to
// 1.9 times behind lost all the eight duels logged on the H200 since the trusted best (builds
// a281eb5 to 2f92b4f: Sponza and Sibenik at 2 %, Sibenik at 1 %, once with a million photons a
// pass), each after two rounds of its own (0.13-0.15 s of a 1.1-1.7 s frame at 2 %); the two won
// by a runner-up, it stood 1.39 and 1.41 times behind (Sibenik at 1 %; docs/method-auto.md, "The
// duel only within 1.5x of a trusted best"). Behind a trusted best by kTrustedDuelTimeRatio to
// kDropTimeRatio, a runner-up stays in the race and is not carried on when it ends. In the duel it
// renders kDuelShare of the leader's time a round. Once it has run kDuelRoundsToJudge rounds of
// its own there, the duel ends with the leader as soon as the leader's forecast can be
// trusted: an unbiased leader's at once, and a biased one's whose forecast carries its bias
// (RaceStanding::bias_in_forecast); any other biased one's once its error is within
// kDuelProofRatio of the target, or once its reading bounds its bias (plus two standard errors)
// within kTrustedBiasShare of the target; an untrusted leader's lead ends it only at
// kDuelTimeRatio. What the duel guards against is a floor the leader's forecast does not see
// (final gathering over radiosity's, read from how its error fell, until its bias was measured
// along the control's paths); behind a leader that can show none, a runner-up forecast 1.8 to 3.4
// times slower rendered beside it until it reached the target (Sponza at 1 %, 1.7 s of the
// runner-up's own; docs/method-auto.md, "Final gathering's bias measured along the control's
// paths"). Photon passes shrink their bias as they go: final gathering over photons read
// +0.24 / +0.15 / +0.05 % on Sponza / Sibenik / Conference at 1 %.
// A trusted lead ends it however close the two are: the forecasts of two final gatherings within
// 1.5x of each other swap the lead from round to round (Sibenik at 1 %: 3.66 against 5.1 s, then
// 7.21 against 3.63 s), and each round costs the runner-up's quarter for a gain of at most the
// difference, which forecasts a third apart cannot tell (docs/method-auto.md, "The race's start
// and the duel's end"). A bias b under a target E slows a
// method long before it stops it (at b = 0.7 E it needs twice the time, at 0.87 E four times),
// and its readings show it only near the target: final gathering over radiosity on Sponza, its
// floor about 0.8 % under a target of 1 %, fell from 2.07 to 1.50 % as its time doubled, as noise
// alone would, and from 1.21 to 1.15 % over the next half again (docs/method-auto.md, "The
// duel"). A bias of at most half the target lengthens the time to it by at most a third (1 / (1 -
// 0.5^2)), even were the forecast to leave it out.
constexpr double kDuelTimeRatio = 4.0;
constexpr double kTrustedDuelTimeRatio = 1.5;
constexpr double kDuelShare = 0.25;
constexpr int kDuelRoundsToJudge = 2;
constexpr double kDuelProofRatio = 1.2;
constexpr double kTrustedBiasShare = 0.5;

// Within a round a candidate renders at least one pass, then begins another only while it is
// forecast, at the mean of the round's passes so far, to end within the round's time: a round's
// time is what the candidate may spend, not a point past which its last pass runs on. Passing the
// time by up to a pass cost every candidate half a pass a round on average: at 960 x 540 the path
// tracer's passes take 31 ms, so its first round of 0.05 s was two passes (0.061 s) where one
// tells the race as much (docs/method-auto.md, "A round's passes within its time").
bool another_pass_fits(double round_seconds, unsigned passes_this_round, double slice);

// The call after a round in `phase` (race or duel).
RoundCall call_round(const std::vector<RaceStanding>& standings, RacePhase phase, const RaceRules& rules);

}  // namespace pm

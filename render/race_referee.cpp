// The race's calls after each round (race_referee.h).
#include "render/race_referee.h"

#include <algorithm>
#include <cmath>

namespace pm {

namespace {

// The candidate with the lowest value among those still in, but `skip`; -1 if none.
int lowest(const std::vector<RaceStanding>& s, int skip = -1) {
  int best = -1;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i].out || int(i) == skip) continue;
    if (best < 0 || s[i].value < s[best].value) best = int(i);
  }
  return best;
}

// The leader: the lowest value; under a target error none of them may be forecast to reach it,
// and then the lowest error at ten times their time.
int leader(const std::vector<RaceStanding>& s, bool by_error) {
  int best = lowest(s);
  if (best < 0 || !by_error || std::isfinite(s[best].value)) return best;
  for (size_t i = 0; i < s.size(); ++i)
    if (!s[i].out && s[i].error_at_ten_times < s[best].error_at_ten_times) best = int(i);
  return best;
}

// Whether a leader's forecast can hide no floor under a target error (race_referee.h): unbiased,
// or its bias carried in its forecast, or its reading near the target or bounding its bias well
// under it.
bool trusted(const RaceStanding& leader, double target) {
  return !leader.biased || leader.bias_in_forecast || (leader.error >= 0 && leader.error <= kDuelProofRatio * target) ||
         (leader.bias_at_most >= 0 && leader.bias_at_most <= kTrustedBiasShare * target);
}

RoundCall call_duel(const std::vector<RaceStanding>& s, double target) {
  RoundCall call;
  call.best = leader(s, true);
  const int challenger = lowest(s, call.best);
  call.phase = RacePhase::duel;
  if (challenger < 0) {
    call.phase = RacePhase::over;
    return call;
  }
  const RaceStanding &leader = s[call.best], &other = s[challenger];
  const bool judged = other.measured && other.duel_rounds >= kDuelRoundsToJudge;
  if (std::isfinite(leader.value) && judged && (trusted(leader, target) || other.value > kDuelTimeRatio * leader.value)) {
    call.dropped.push_back(size_t(challenger));
    call.phase = RacePhase::over;
  } else if (leader.duel_rounds >= kMaxDuelRounds) {
    call.phase = RacePhase::over;
  }
  return call;
}

}  // namespace

RoundCall call_round(const std::vector<RaceStanding>& s, RacePhase phase, const RaceRules& rules) {
  // Under a target error and --time both, the time is the frame's cap: the race and the duel
  // take no more of it than a race under the time alone would.
  const bool out_of_time = rules.budget_seconds > 0 && rules.elapsed >= kRaceShareOfTime * rules.budget_seconds;
  if (phase == RacePhase::duel) {
    RoundCall call = call_duel(s, rules.target);
    if (out_of_time) call.phase = RacePhase::over;
    return call;
  }
  RoundCall call;
  call.best = leader(s, rules.by_error);
  if (call.best < 0) {
    call.phase = RacePhase::over;
    return call;
  }
  const RaceStanding& best = s[call.best];
  const bool known = std::isfinite(best.value);
  const bool best_trusted = rules.by_error && trusted(best, rules.target);
  // Under a target error the runner-up is kept for the duel while it is within kDuelTimeRatio of
  // a best whose forecast may hide a floor (the race's readings are too short to tell such
  // candidates apart), and within kTrustedDuelTimeRatio of a trusted one.
  const int runner_up = rules.by_error ? lowest(s, call.best) : -1;
  const double duel_ratio = best_trusted ? kTrustedDuelTimeRatio : kDuelTimeRatio;
  const bool duel_worthy = runner_up >= 0 && known && s[runner_up].value <= duel_ratio * best.value;
  const double ratio = rules.by_error ? kDropTimeRatio : kDropErrorRatio;
  size_t left = 0;
  bool only_the_kept_one_left = true;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i].out || int(i) == call.best) continue;
    // Behind on its forecast once its rate is measured; before that, only if behind even at the
    // fastest rate its method allows (photon passes at 1/2: their next round would only measure
    // what cannot bring them back). An unbiased one (the path tracer) reaches any target, and
    // waits for its measured rate behind a best whose forecast may still be hiding a floor (a
    // coarse radiosity solution under final gathering, forecast 0.37 s to 1.5 % on its first
    // reading, levels at 3.2-3.7 %; MethodRace.TheFrameGoesToTheCandidateThatReachesTheTarget...);
    // behind a trusted best its fastest fall (1/sqrt(t): an unbiased estimate's mean absolute
    // error falls no faster) is its forecast, and a second round would only confirm it (the
    // path tracer, 12-54 s behind final gathering's 0.5-13 s on the benchmark scenes, docs/method-auto.md).
    const double judged =
        s[i].measured ? s[i].value : (s[i].biased || best_trusted ? s[i].best_case : 0.0);
    const bool behind = known && judged > ratio * best.value;
    if (behind && !(duel_worthy && int(i) == runner_up)) {
      call.dropped.push_back(i);
      continue;
    }
    ++left;
    if (!behind) only_the_kept_one_left = false;
  }
  if (left == 0) {
    call.phase = RacePhase::over;
    return call;
  }
  // Racing on costs more than it could save: the race has taken its share of the time, or of the
  // time the best is forecast to need; or it has run its rounds.
  const bool last_round = rules.round + 1 >= kMaxRaceRounds;
  if (!rules.by_error || out_of_time) {
    if (out_of_time || last_round) call.phase = RacePhase::over;
    return call;
  }
  const bool settled = (known && best.measured && rules.elapsed >= kRaceShareOfForecast * best.forecast_total) ||
                       last_round || only_the_kept_one_left;
  if (!settled) return call;
  if (!duel_worthy) {
    call.phase = RacePhase::over;
    return call;
  }
  // The duel: the best and the runner-up; the others are done.
  for (size_t i = 0; i < s.size(); ++i)
    if (!s[i].out && int(i) != call.best && int(i) != runner_up &&
        std::find(call.dropped.begin(), call.dropped.end(), i) == call.dropped.end())
      call.dropped.push_back(i);
  call.phase = RacePhase::duel;
  return call;
}

bool another_pass_fits(double round_seconds, unsigned passes_this_round, double slice) {
  if (passes_this_round == 0) return true;
  return round_seconds + round_seconds / passes_this_round <= slice;
}

}  // namespace pm

// --method auto's calls after each round (render/race_referee.h): who leads, who is dropped, when
// the race narrows to a duel of the two best under a target error, how the duel changes its lead
// and judges its runner-up, and that a time budget keeps the race as it was.
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "render/race_referee.h"

namespace pm {
namespace {

constexpr double kNever = std::numeric_limits<double>::infinity();

// value: own seconds still needed (by error) or forecast error (by time); total: whole own time.
RaceStanding standing(double value, bool measured = true, double total = -1, int duel_rounds = 0) {
  RaceStanding s;
  s.value = value;
  s.forecast_total = total < 0 ? value : total;
  s.measured = measured;
  s.duel_rounds = duel_rounds;
  return s;
}

constexpr double kTarget = 0.01;
RaceRules by_error(double elapsed, int round = 2) { return {true, kTarget, 0, elapsed, round}; }

// A biased leader whose forecast may hide a floor: its error far from the target, its bias unbounded.
RaceStanding untrusted_leader(double value, double total = -1) {
  RaceStanding s = standing(value, true, total);
  s.biased = true;
  s.error = 3 * kTarget;
  return s;
}

TEST(RaceReferee, ARunnerUpWithinFourTimesAnUntrustedBestIsKeptForADuel) {
  // The leader needs 10 s more; the runner-up's 28 s would have dropped it (2x), the third's 50 s does.
  const RoundCall call =
      call_round({untrusted_leader(10), standing(28), standing(50)}, RacePhase::race, by_error(0.5));
  EXPECT_EQ(call.best, 0);
  EXPECT_EQ(call.dropped, std::vector<size_t>{2});
  EXPECT_EQ(call.phase, RacePhase::duel) << "only the kept runner-up is left: the duel begins";
}

TEST(RaceReferee, BehindATrustedBestARunnerUpIsKeptForADuelOnlyWithinOneAndAHalfTimes) {
  // Sibenik at 2 %, after the race's second round: final gathering over radiosity, its bias measured,
  // 0.54 s more; over photons 1.59 s (2.9 times): no duel, the race is over.
  RaceStanding leader = standing(0.536, true, 0.71), photons = standing(1.59, true, 1.77);
  leader.biased = photons.biased = true;
  leader.error = 0.0452;
  leader.bias_in_forecast = true;
  const RaceRules two_percent{true, 0.02, 0, 0.84, 1};
  RoundCall call = call_round({leader, photons}, RacePhase::race, two_percent);
  EXPECT_EQ(call.dropped, std::vector<size_t>{1});
  EXPECT_EQ(call.phase, RacePhase::over);
  // Sibenik at 2 % (H200, 2f92b4f): over photons 1.13 s against 0.62 s (1.8 times). Not dropped
  // (within twice), but no duel either: the race is over and the leader goes on alone.
  leader.value = 0.622;
  photons.value = 1.13;
  call = call_round({leader, photons}, RacePhase::race, two_percent);
  EXPECT_TRUE(call.dropped.empty());
  EXPECT_EQ(call.phase, RacePhase::over);
  EXPECT_EQ(call.best, 0);
  // Within one and a half times (Sibenik at 1 %: 1.30 times) the runner-up duels.
  photons.value = 1.3 * leader.value;
  call = call_round({leader, photons}, RacePhase::race, two_percent);
  EXPECT_TRUE(call.dropped.empty());
  EXPECT_EQ(call.phase, RacePhase::duel);
  // Behind a leader whose forecast is not trusted it duels within four times.
  leader.value = 0.536;
  photons.value = 1.59;
  leader.bias_in_forecast = false;
  call = call_round({leader, photons}, RacePhase::race, two_percent);
  EXPECT_TRUE(call.dropped.empty());
  EXPECT_EQ(call.phase, RacePhase::duel);
}

TEST(RaceReferee, ABiasedCandidateBehindEvenAtItsFastestRateGoesBeforeItsRateIsMeasured) {
  // Sponza asked for 2 %, after the first round (H200): final gathering over radiosity forecast
  // 0.73 s more on its assumed rate; photon passes 3.2 s even at 1/2: out without a second round.
  // Final gathering over photons, 7.2 s on its assumed rate but 0.63 s at a net's fastest, stays.
  RaceStanding best = standing(0.73, false), gather = standing(7.2, false), path = standing(12.4, false),
               photon = standing(1380, false);
  best.biased = gather.biased = photon.biased = true;
  gather.best_case = 0.63;
  path.best_case = 12.4;
  photon.best_case = 3.2;
  RoundCall call = call_round({best, gather, path, photon}, RacePhase::race, by_error(0.7, 0));
  EXPECT_EQ(call.best, 0);
  EXPECT_EQ(call.dropped, std::vector<size_t>{3});
  EXPECT_EQ(call.phase, RacePhase::race);
  // The path tracer, 12.4 s even at its fastest, stays until its rate is measured: it reaches any
  // target, and the leader's forecast may still hide a floor. Measured, it goes.
  path.measured = true;
  call = call_round({best, gather, path, photon}, RacePhase::race, by_error(0.7, 0));
  EXPECT_EQ(call.dropped, (std::vector<size_t>{2, 3}));
  // Behind a best whose forecast carries its bias (final gathering over radiosity's measured along
  // the control's paths) the path tracer's fastest fall is its forecast: it goes at once.
  path.measured = false;
  best.bias_in_forecast = true;
  call = call_round({best, gather, path, photon}, RacePhase::race, by_error(0.7, 0));
  EXPECT_EQ(call.dropped, (std::vector<size_t>{2, 3}));
  path.best_case = 1.2;
  EXPECT_EQ(call_round({best, gather, path, photon}, RacePhase::race, by_error(0.7, 0)).dropped,
            std::vector<size_t>{3})
      << "within the drop ratio at its fastest it stays";
  // Within the drop ratio at its fastest a biased candidate stays; without a best case (not known)
  // only a measured forecast drops it.
  photon.best_case = 1.4;
  EXPECT_TRUE(call_round({best, photon}, RacePhase::race, by_error(0.7, 0)).dropped.empty());
  photon.best_case = 0;
  EXPECT_TRUE(call_round({best, photon}, RacePhase::race, by_error(0.7, 0)).dropped.empty());
}

TEST(RaceReferee, TheRaceGoesOnWhileItsForecastsAreUnsettled) {
  // 0.5 s into a race whose best is forecast 10 s, a candidate not yet measured: another round.
  const RoundCall call = call_round({standing(10), standing(12, false), standing(15)}, RacePhase::race, by_error(0.5));
  EXPECT_EQ(call.best, 0);
  EXPECT_TRUE(call.dropped.empty());
  EXPECT_EQ(call.phase, RacePhase::race);
  // Once the race has taken a fifth of the best's forecast time, the two best duel; the others go.
  const RoundCall settled =
      call_round({standing(10, true, 11), standing(12, false), standing(15)}, RacePhase::race, by_error(2.3));
  EXPECT_EQ(settled.phase, RacePhase::duel);
  EXPECT_EQ(settled.dropped, std::vector<size_t>{2});
}

TEST(RaceReferee, ARunnerUpFarBehindEndsTheRaceWithoutADuel) {
  const RoundCall call = call_round({standing(10), standing(45)}, RacePhase::race, by_error(0.5));
  EXPECT_EQ(call.dropped, std::vector<size_t>{1});
  EXPECT_EQ(call.phase, RacePhase::over);
  // Not measured yet, it is not dropped; once the race is settled, it is too far behind to duel.
  const RoundCall settled = call_round({standing(10, true, 11), standing(45, false)}, RacePhase::race, by_error(2.3));
  EXPECT_EQ(settled.phase, RacePhase::over);
}

TEST(RaceReferee, TheDuelsLeadFollowsTheForecasts) {
  // The runner-up of the race now forecasts less time left than the leader: it leads.
  const RoundCall call =
      call_round({standing(14, true, 24, 1), standing(11, true, 13, 1)}, RacePhase::duel, by_error(10));
  EXPECT_EQ(call.best, 1);
  EXPECT_TRUE(call.dropped.empty());
  EXPECT_EQ(call.phase, RacePhase::duel);
}

TEST(RaceReferee, TheRunnerUpIsJudgedOnReadingsOfItsOwnInTheDuel) {
  // Three times behind after one round of its own in the duel: kept.
  RoundCall call = call_round({standing(10, true, 20, 1), standing(30, true, 31, 1)}, RacePhase::duel, by_error(10));
  EXPECT_TRUE(call.dropped.empty());
  EXPECT_EQ(call.phase, RacePhase::duel);
  // After kDuelRoundsToJudge rounds behind a trusted (here unbiased) leader, however close: dropped,
  // and the leader goes on alone.
  for (double behind : {16.0, 10.5}) {
    call = call_round({standing(10, true, 20, kDuelRoundsToJudge), standing(behind, true, 20, kDuelRoundsToJudge)},
                      RacePhase::duel, by_error(12));
    EXPECT_EQ(call.dropped, std::vector<size_t>{1}) << behind;
    EXPECT_EQ(call.phase, RacePhase::over) << behind;
  }
  // Behind a leader whose forecast is not yet trusted (biased, its error far from the target),
  // within kDuelTimeRatio, the duel goes on...
  RaceStanding untrusted = standing(10, true, 20, 4);
  untrusted.biased = true;
  untrusted.error = 3 * kTarget;
  call = call_round({untrusted, standing(14, true, 20, 4)}, RacePhase::duel, by_error(20));
  EXPECT_EQ(call.phase, RacePhase::duel);
  // ... until its last round.
  untrusted.duel_rounds = kMaxDuelRounds;
  call = call_round({untrusted, standing(14, true, 20, kMaxDuelRounds)}, RacePhase::duel, by_error(20));
  EXPECT_EQ(call.best, 0);
  EXPECT_EQ(call.phase, RacePhase::over);
}

TEST(RaceReferee, ABiasedLeadersForecastIsTrustedOnlyNearTheTarget) {
  // Final gathering over radiosity on Sponza, asked for 1 %: at 2.65 % after 1.6 s its error still
  // fell as 1/sqrt(t) and it was forecast 10 s more; it took 45 s, its solution's bias slowing it.
  // Final gathering over photons, forecast 17 s more, is kept beside it while it is that far out.
  RaceStanding leader = standing(10, true, 11.6, kDuelRoundsToJudge), other = standing(17, true, 17.8, kDuelRoundsToJudge);
  leader.biased = other.biased = true;
  leader.error = 0.0265;
  RoundCall call = call_round({leader, other}, RacePhase::duel, by_error(3.5));
  EXPECT_TRUE(call.dropped.empty());
  EXPECT_EQ(call.phase, RacePhase::duel);
  // Within kDuelProofRatio of the target the leader's rate would show its bias: its forecast stands.
  leader.error = kDuelProofRatio * kTarget;
  call = call_round({leader, other}, RacePhase::duel, by_error(9));
  EXPECT_EQ(call.dropped, std::vector<size_t>{1});
  // An unbiased leader is trusted at once; a runner-up kDuelTimeRatio behind goes whatever the leader.
  leader.error = 0.0265;
  leader.biased = false;
  EXPECT_EQ(call_round({leader, other}, RacePhase::duel, by_error(3.5)).dropped, std::vector<size_t>{1});
  leader.biased = true;
  other.value = 41;
  EXPECT_EQ(call_round({leader, other}, RacePhase::duel, by_error(3.5)).dropped, std::vector<size_t>{1});
}

TEST(RaceReferee, ABiasedLeaderWhoseBiasIsBoundedWellUnderTheTargetIsTrusted) {
  // Final gathering over radiosity on Conference, asked for 2 %: at 3.45 % its reading bounds
  // its bias under 0.9 %; final gathering over photons, 1.9 times behind, goes.
  RaceStanding leader = standing(1.35, true, 2.0, kDuelRoundsToJudge), other = standing(2.61, true, 2.9, kDuelRoundsToJudge);
  leader.biased = other.biased = true;
  leader.error = 0.0345;
  const RaceRules two_percent{true, 0.02, 0, 2.5, 2};
  leader.bias_at_most = 0.009;
  RoundCall call = call_round({leader, other}, RacePhase::duel, two_percent);
  EXPECT_EQ(call.dropped, std::vector<size_t>{1});
  EXPECT_EQ(call.phase, RacePhase::over);
  // A bound over half the target, or none, proves nothing: the duel goes on.
  for (double bound : {0.011, -1.0}) {
    leader.bias_at_most = bound;
    call = call_round({leader, other}, RacePhase::duel, two_percent);
    EXPECT_TRUE(call.dropped.empty()) << "bound " << bound;
    EXPECT_EQ(call.phase, RacePhase::duel) << "bound " << bound;
  }
}

TEST(RaceReferee, ABiasedLeaderWhoseForecastCarriesItsBiasIsTrusted) {
  // Sponza at 1 %: final gathering over photons leads at 3.12 %, its passes shrinking what bias
  // it has; final gathering over radiosity, its bias measured along the control's paths, is
  // forecast 1.8 times slower. After its rounds in the duel it goes.
  RaceStanding leader = standing(4.19, true, 5.0, kDuelRoundsToJudge), other = standing(7.73, true, 8.2, kDuelRoundsToJudge);
  leader.biased = other.biased = true;
  leader.error = 0.0312;
  RoundCall call = call_round({leader, other}, RacePhase::duel, by_error(2.0));
  EXPECT_TRUE(call.dropped.empty()) << "a bias the forecast may not see: the duel goes on";
  leader.bias_in_forecast = true;
  call = call_round({leader, other}, RacePhase::duel, by_error(2.0));
  EXPECT_EQ(call.dropped, std::vector<size_t>{1});
  EXPECT_EQ(call.phase, RacePhase::over);
  // Not before the runner-up has had its rounds.
  other.duel_rounds = kDuelRoundsToJudge - 1;
  EXPECT_TRUE(call_round({leader, other}, RacePhase::duel, by_error(2.0)).dropped.empty());
}

TEST(RaceReferee, NoneForecastToReachTheTargetRanksByTheErrorItWouldReach) {
  RaceStanding a = standing(kNever), b = standing(kNever);
  a.error_at_ten_times = 0.04;
  b.error_at_ten_times = 0.02;
  const RoundCall call = call_round({a, b}, RacePhase::race, by_error(0.5));
  EXPECT_EQ(call.best, 1);
  EXPECT_TRUE(call.dropped.empty()) << "nothing is measured against a best that never arrives";
  EXPECT_EQ(call.phase, RacePhase::race);
}

TEST(RaceReferee, UnderATargetErrorAndATimeTheRaceKeepsToItsShareOfTheTime) {
  // --target-error 0.01 --time 2: 0.6 s into the race (over a quarter of 2 s), the forecasts
  // unsettled, the race ends; so does a duel. Under the target alone both go on.
  const std::vector<RaceStanding> unsettled = {standing(10), standing(12, false), standing(15)};
  RaceRules both = by_error(0.6);
  both.budget_seconds = 2;
  EXPECT_EQ(call_round(unsettled, RacePhase::race, both).phase, RacePhase::over);
  EXPECT_EQ(call_round(unsettled, RacePhase::race, by_error(0.6)).phase, RacePhase::race);
  const std::vector<RaceStanding> duel = {standing(10, true, -1, 1), standing(12, true, -1, 1)};
  EXPECT_EQ(call_round(duel, RacePhase::duel, both).phase, RacePhase::over);
  EXPECT_EQ(call_round(duel, RacePhase::duel, by_error(0.6)).phase, RacePhase::duel);
  both.elapsed = 0.4;
  EXPECT_EQ(call_round(unsettled, RacePhase::race, both).phase, RacePhase::race) << "within its share";
}

TEST(RaceReferee, UnderATimeBudgetTheRaceIsAsBeforeWithoutADuel) {
  // Forecast errors at the time: 2 %, 2.4 % (kept: within 1.25x) and 3 % (dropped).
  const RaceRules by_time{false, 0, 10.0, 1.0, 2};
  RoundCall call = call_round({standing(0.02), standing(0.024), standing(0.03)}, RacePhase::race, by_time);
  EXPECT_EQ(call.best, 0);
  EXPECT_EQ(call.dropped, std::vector<size_t>{2});
  EXPECT_EQ(call.phase, RacePhase::race);
  // At its share of the budget the race ends with the best; no duel.
  call = call_round({standing(0.02), standing(0.024)}, RacePhase::race, {false, 0, 10.0, 2.5, 3});
  EXPECT_EQ(call.phase, RacePhase::over);
  // Its rounds run out.
  call = call_round({standing(0.02), standing(0.024)}, RacePhase::race, {false, 0, 100.0, 2.5, kMaxRaceRounds - 1});
  EXPECT_EQ(call.phase, RacePhase::over);
}

// Passes of the round's mean length, begun while another fits: how many a round holds.
unsigned passes_in_round(double pass_seconds, double slice) {
  unsigned passes = 0;
  while (another_pass_fits(passes * pass_seconds, passes, slice)) ++passes;
  return passes;
}

TEST(RaceReferee, ARoundBeginsAPassOnlyWhereItIsForecastToEndWithinTheRound) {
  // The path tracer at 960 x 540 (31 ms a pass) in a first round of 0.05 s: one pass, not two.
  EXPECT_EQ(passes_in_round(0.031, 0.05), 1u);
  // Photon passes of 8.8 ms: five (44 ms), where the sixth would end at 52.8 ms.
  EXPECT_EQ(passes_in_round(0.0088, 0.05), 5u);
  // A pass longer than the round still runs once: without it nothing is read.
  EXPECT_EQ(passes_in_round(0.2, 0.05), 1u);
  EXPECT_TRUE(another_pass_fits(0.3, 0, 0.05));
  // Exactly filling the round is within it.
  EXPECT_EQ(passes_in_round(0.25, 1.0), 4u);
  // The forecast is the mean of the round's passes: a slow first pass holds the rest back.
  EXPECT_FALSE(another_pass_fits(0.04 + 0.01, 2, 0.07));  // mean 25 ms: 75 ms would pass 70
  EXPECT_TRUE(another_pass_fits(0.02 + 0.01, 2, 0.05));   // mean 15 ms: 45 ms
}

}  // namespace
}  // namespace pm

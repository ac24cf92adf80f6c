// Keyframe tracks (animations/keyframe_track.h): exact values at keys, holds outside the keys,
// continuity between keys, C1 continuity and no overshoot for smooth tracks, and a derivative
// that is the derivative of what evaluate() returns.
#include <gtest/gtest.h>

#include <cmath>

#include "animations/keyframe_track.h"

namespace pm {
namespace {

Vec3Track uneven_track(Interpolation interpolation) {
  Vec3Track track;
  track.interpolation = interpolation;
  // Uneven spacing, a turning point in x (up then down), a flat stretch in y, monotone z.
  track.keys = {{0.0, {0.0f, 1.0f, -2.0f}},
                {0.4, {1.5f, 1.0f, -1.0f}},
                {1.5, {0.5f, 1.0f, 3.0f}},
                {1.6, {0.7f, 2.0f, 3.5f}},
                {3.0, {4.0f, 2.0f, 10.0f}}};
  return track;
}

const Interpolation kAll[] = {Interpolation::step, Interpolation::linear, Interpolation::smooth};

TEST(AnimationTrack, ExactAtKeysAndHoldsOutside) {
  for (Interpolation mode : kAll) {
    SCOPED_TRACE(interpolation_name(mode));
    const Vec3Track track = uneven_track(mode);
    for (const auto& key : track.keys) EXPECT_EQ(track.evaluate(key.time), key.value);
    EXPECT_EQ(track.evaluate(-5.0), track.keys.front().value);
    EXPECT_EQ(track.evaluate(-1e-9), track.keys.front().value);
    EXPECT_EQ(track.evaluate(3.0 + 1e-9), track.keys.back().value);
    EXPECT_EQ(track.evaluate(1e6), track.keys.back().value);
  }
}

TEST(AnimationTrack, SingleKeyIsConstant) {
  ScalarTrack track;
  track.interpolation = Interpolation::smooth;
  track.keys = {{2.0, {40.0f}}};
  for (double t : {-1.0, 0.0, 2.0, 7.5}) EXPECT_EQ(track.evaluate(t)[0], 40.0f);
  EXPECT_EQ(track.derivative(2.0)[0], 0.0);
}

TEST(AnimationTrack, LinearIsTheStraightLine) {
  const Vec3Track track = uneven_track(Interpolation::linear);
  const auto v = track.evaluate(0.1);  // a quarter of the way from key 0 to key 1
  EXPECT_FLOAT_EQ(v[0], 0.375f);
  EXPECT_FLOAT_EQ(v[1], 1.0f);
  EXPECT_FLOAT_EQ(v[2], -1.75f);
}

TEST(AnimationTrack, StepHoldsTheEarlierKey) {
  const Vec3Track track = uneven_track(Interpolation::step);
  EXPECT_EQ(track.evaluate(0.39), track.keys[0].value);
  EXPECT_EQ(track.evaluate(1.59), track.keys[2].value);
}

TEST(AnimationTrack, ContinuousBetweenAndAcrossKeys) {
  for (Interpolation mode : {Interpolation::linear, Interpolation::smooth}) {
    SCOPED_TRACE(interpolation_name(mode));
    const Vec3Track track = uneven_track(mode);
    // Values just before and after every key converge to the key's value.
    for (const auto& key : track.keys)
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(track.evaluate(key.time - 1e-7)[c], key.value[c], 1e-5);
        EXPECT_NEAR(track.evaluate(key.time + 1e-7)[c], key.value[c], 1e-5);
      }
    // No jumps anywhere: steps of 1e-4 s change the value by at most |slope| * 1e-4.
    auto previous = track.evaluate(-0.1);
    for (double t = -0.1; t < 3.1; t += 1e-4) {
      const auto v = track.evaluate(t);
      for (int c = 0; c < 3; ++c) EXPECT_LT(std::fabs(v[c] - previous[c]), 2e-3) << "t = " << t;
      previous = v;
    }
  }
}

TEST(AnimationTrack, SmoothIsC1AndLinearIsNot) {
  const Vec3Track smooth = uneven_track(Interpolation::smooth);
  const Vec3Track linear = uneven_track(Interpolation::linear);
  bool linear_has_a_kink = false;
  for (const auto& key : smooth.keys) {
    for (int c = 0; c < 3; ++c) {
      const double left = smooth.derivative(key.time - 1e-9)[c];
      const double right = smooth.derivative(key.time)[c];
      EXPECT_NEAR(left, right, 1e-6) << "key at " << key.time << ", component " << c;
      linear_has_a_kink |= std::fabs(linear.derivative(key.time - 1e-9)[c] - linear.derivative(key.time)[c]) > 0.1;
    }
  }
  EXPECT_TRUE(linear_has_a_kink) << "the check above would not notice a kink";
  // The first and last keys meet the holds with zero slope.
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(smooth.derivative(0.0)[c], 0.0);
    EXPECT_NEAR(smooth.derivative(3.0 - 1e-12)[c], 0.0, 1e-6);
  }
}

TEST(AnimationTrack, DerivativeIsTheSlopeOfEvaluate) {
  for (Interpolation mode : {Interpolation::linear, Interpolation::smooth}) {
    SCOPED_TRACE(interpolation_name(mode));
    const Vec3Track track = uneven_track(mode);
    for (double t : {0.05, 0.3, 0.8, 1.2, 1.55, 2.0, 2.9}) {
      const double h = 1e-3;
      for (int c = 0; c < 3; ++c) {
        const double numeric = (double(track.evaluate(t + h)[c]) - double(track.evaluate(t - h)[c])) / (2 * h);
        EXPECT_NEAR(track.derivative(t)[c], numeric, 2e-2 + 1e-3 * std::fabs(numeric)) << "t = " << t << " c = " << c;
      }
    }
  }
}

TEST(AnimationTrack, SmoothNeverLeavesTheRangeOfItsKeys) {
  const Vec3Track track = uneven_track(Interpolation::smooth);
  for (size_t k = 0; k + 1 < track.keys.size(); ++k) {
    const auto& a = track.keys[k];
    const auto& b = track.keys[k + 1];
    for (int i = 1; i < 200; ++i) {
      const double t = a.time + (b.time - a.time) * i / 200.0;
      const auto v = track.evaluate(t);
      for (int c = 0; c < 3; ++c) {
        EXPECT_GE(v[c], std::min(a.value[c], b.value[c])) << "t = " << t;
        EXPECT_LE(v[c], std::max(a.value[c], b.value[c])) << "t = " << t;
      }
    }
  }
  // A flat stretch stays exactly flat (y between the first three keys).
  for (double t = 0; t <= 1.5; t += 0.01) EXPECT_EQ(track.evaluate(t)[1], 1.0f);
}

TEST(AnimationTrack, SmoothBendsWhereLinearDoesNot) {
  // Evenly spaced keys on a parabola: the smooth curve differs from the chords in between.
  ScalarTrack smooth, linear;
  smooth.interpolation = Interpolation::smooth;
  for (int k = 0; k <= 4; ++k) smooth.keys.push_back({double(k), {float(k * k)}});
  linear.keys = smooth.keys;
  EXPECT_NE(smooth.evaluate(2.5)[0], linear.evaluate(2.5)[0]);
  // Interior tangents are the centred differences: at t = 2, (9 - 1) / 2 = 4.
  EXPECT_NEAR(smooth.derivative(2.0)[0], 4.0, 1e-12);
}

TEST(AnimationTrack, InterpolationNamesRoundTrip) {
  for (Interpolation mode : kAll) {
    Interpolation parsed = Interpolation::linear;
    EXPECT_TRUE(parse_interpolation(interpolation_name(mode), &parsed));
    EXPECT_EQ(parsed, mode);
  }
  Interpolation parsed;
  EXPECT_FALSE(parse_interpolation("cubic", &parsed));
  EXPECT_FALSE(parse_interpolation("Linear", &parsed));
}

}  // namespace
}  // namespace pm

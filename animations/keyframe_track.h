// Keyframe tracks: a value of N float components given at key times (seconds) and interpolated
// between them. Before the first key and after the last the track holds the end key's value.
// Pure host code with no file or scene knowledge; loaders fill tracks, animations/
// render/scene_frame.h evaluates the scene's tracks at a frame (docs/animation.md).
#pragma once

#include <array>
#include <string>
#include <vector>

namespace pm {

enum class Interpolation {
  step,    // the value of the key at or before t
  linear,  // straight lines between keys: C0
  smooth,  // cubic Hermite with monotonicity-limited Catmull-Rom tangents: C1, no overshoot
};

// "step", "linear", "smooth".
const char* interpolation_name(Interpolation interpolation);
// Parses those names; false for anything else.
bool parse_interpolation(const std::string& name, Interpolation* out);

template <int N>
struct Track {
  using Value = std::array<float, N>;
  struct Key {
    double time = 0;  // seconds
    Value value{};
  };

  std::vector<Key> keys;  // strictly increasing times; empty: the track is absent
  Interpolation interpolation = Interpolation::linear;

  bool empty() const { return keys.empty(); }
  // The interpolated value at time t. Exactly the key's value at a key time and in the holds.
  // Must not be called on an empty track.
  Value evaluate(double t) const;
  // d value / dt at t (per second), from the same curve: zero in the holds and for step tracks.
  // At a key time, the derivative of the segment that starts there (the right derivative).
  std::array<double, N> derivative(double t) const;
};

using ScalarTrack = Track<1>;
using Vec3Track = Track<3>;

extern template struct Track<1>;
extern template struct Track<3>;

}  // namespace pm

// Evaluation of keyframe tracks. Arithmetic is in double and rounded to float once, so a value
// at a key time is the key's value exactly and a segment between equal keys stays exactly
// constant (the renderer relies on that to see that a light did not change between frames).
#include "animations/keyframe_track.h"

#include <algorithm>
#include <cmath>

namespace pm {

namespace {

// Slope of segment k (keys k and k+1) in component c.
template <int N>
double secant(const std::vector<typename Track<N>::Key>& keys, size_t k, int c) {
  return (double(keys[k + 1].value[c]) - double(keys[k].value[c])) / (keys[k + 1].time - keys[k].time);
}

// The tangent (d value / dt) of the smooth curve at key k, component c. The first and last keys
// get zero, which matches the holds outside the keys, so the curve is C1 there too. Inner keys
// get the centred difference (v[k+1] - v[k-1]) / (t[k+1] - t[k-1]) (Catmull-Rom for uneven key
// spacing), set to zero where the curve turns (neighbouring slopes of opposite sign or a flat
// neighbour) and limited to 3 times the smaller neighbouring slope. With both tangents of a
// segment within [0, 3] times its slope, the cubic is monotone between its keys (Fritsch and
// Carlson 1980), so it never leaves the range of its two keys: powers stay >= 0, a field of view
// stays within its keys, a camera does not swing past a key.
template <int N>
double smooth_tangent(const std::vector<typename Track<N>::Key>& keys, size_t k, int c) {
  if (k == 0 || k + 1 >= keys.size()) return 0.0;
  const double before = secant<N>(keys, k - 1, c);
  const double after = secant<N>(keys, k, c);
  if (!(before * after > 0)) return 0.0;
  const double centred =
      (double(keys[k + 1].value[c]) - double(keys[k - 1].value[c])) / (keys[k + 1].time - keys[k - 1].time);
  const double limit = 3.0 * std::min(std::fabs(before), std::fabs(after));
  return std::copysign(std::min(std::fabs(centred), limit), centred);
}

// Index k of the segment [keys[k], keys[k+1]) that contains t; requires t0 <= t < t_last.
template <int N>
size_t segment_of(const std::vector<typename Track<N>::Key>& keys, double t) {
  auto it = std::upper_bound(keys.begin(), keys.end(), t,
                             [](double time, const typename Track<N>::Key& key) { return time < key.time; });
  return size_t(it - keys.begin()) - 1;
}

}  // namespace

const char* interpolation_name(Interpolation interpolation) {
  switch (interpolation) {
    case Interpolation::step: return "step";
    case Interpolation::linear: return "linear";
    case Interpolation::smooth: return "smooth";
  }
  return "?";
}

bool parse_interpolation(const std::string& name, Interpolation* out) {
  for (Interpolation i : {Interpolation::step, Interpolation::linear, Interpolation::smooth}) {
    if (name == interpolation_name(i)) {
      *out = i;
      return true;
    }
  }
  return false;
}

template <int N>
typename Track<N>::Value Track<N>::evaluate(double t) const {
  if (t <= keys.front().time || keys.size() == 1) return keys.front().value;
  if (t >= keys.back().time) return keys.back().value;
  const size_t k = segment_of<N>(keys, t);
  const Key& a = keys[k];
  const Key& b = keys[k + 1];
  if (interpolation == Interpolation::step || t == a.time) return a.value;
  const double h = b.time - a.time;
  const double s = (t - a.time) / h;
  Value out{};
  for (int c = 0; c < N; ++c) {
    const double va = a.value[c], vb = b.value[c];
    double v;
    if (interpolation == Interpolation::linear) {
      v = va + (vb - va) * s;
    } else {
      const double s2 = s * s, s3 = s2 * s;
      const double h01 = -2 * s3 + 3 * s2, h10 = s3 - 2 * s2 + s, h11 = s3 - s2;
      v = va + (vb - va) * h01 + h * (smooth_tangent<N>(keys, k, c) * h10 + smooth_tangent<N>(keys, k + 1, c) * h11);
    }
    out[c] = float(v);
  }
  return out;
}

template <int N>
std::array<double, N> Track<N>::derivative(double t) const {
  std::array<double, N> out{};
  if (interpolation == Interpolation::step || keys.size() < 2 || t < keys.front().time || t >= keys.back().time)
    return out;
  const size_t k = segment_of<N>(keys, t);
  const Key& a = keys[k];
  const Key& b = keys[k + 1];
  const double h = b.time - a.time;
  const double s = (t - a.time) / h;
  for (int c = 0; c < N; ++c) {
    const double slope = (double(b.value[c]) - double(a.value[c])) / h;
    if (interpolation == Interpolation::linear) {
      out[c] = slope;
    } else {
      const double d01 = -6 * s * s + 6 * s, d10 = 3 * s * s - 4 * s + 1, d11 = 3 * s * s - 2 * s;
      out[c] = slope * d01 + smooth_tangent<N>(keys, k, c) * d10 + smooth_tangent<N>(keys, k + 1, c) * d11;
    }
  }
  return out;
}

template struct Track<1>;
template struct Track<3>;

}  // namespace pm

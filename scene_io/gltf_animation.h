// Owns the math of glTF 2.0 node animation: samplers (STEP, LINEAR with quaternion slerp,
// CUBICSPLINE) evaluated at a time, and node transforms (TRS or matrix) as 4x4 matrices, all in
// double precision. No tinygltf types here, so it can be tested on plain numbers.
#pragma once

#include <array>
#include <vector>

namespace pm::gltf {

using Vec3d = std::array<double, 3>;
using Quat = std::array<double, 4>;  // x, y, z, w as glTF stores rotations

// Column-major 4x4 matrix, as glTF's node.matrix: element (row r, column c) is m[4 * c + r].
struct Mat4 {
  std::array<double, 16> m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
};

Mat4 operator*(const Mat4& a, const Mat4& b);
// T * R * S, the glTF node transform of translation, rotation (normalised here) and scale.
Mat4 mat4_from_trs(const Vec3d& translation, const Quat& rotation, const Vec3d& scale);
Vec3d transform_point(const Mat4& m, const Vec3d& p);
Vec3d transform_direction(const Mat4& m, const Vec3d& d);

enum class SamplerInterpolation { step, linear, cubic_spline };

// One animation sampler: key times (seconds, strictly increasing) and output values with
// `components` numbers per element. CUBICSPLINE stores three elements per key (in-tangent,
// value, out-tangent), the others one. Rotations (components 4) are quaternions: LINEAR uses
// spherical linear interpolation along the shorter arc, CUBICSPLINE normalises its result.
struct Sampler {
  std::vector<double> times;
  std::vector<double> values;
  int components = 3;
  SamplerInterpolation interpolation = SamplerInterpolation::linear;

  // The value at t; before the first and after the last key, that key's value (a hold).
  std::vector<double> evaluate(double t) const;
  double last_time() const { return times.empty() ? 0.0 : times.back(); }
};

// Spherical linear interpolation from a to b (unit quaternions) by s in [0, 1], along the
// shorter arc; normalised linear interpolation when they are nearly equal.
Quat slerp(const Quat& a, const Quat& b, double s);

}  // namespace pm::gltf

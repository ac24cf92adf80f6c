// glTF node animation math: samplers and TRS matrices (glTF 2.0 specification, sections 3.5.3
// "Transformations" and 3.11 "Animations", Appendix C "Interpolation").
#include "scene_io/gltf_animation.h"

#include <algorithm>
#include <cmath>

namespace pm::gltf {

Mat4 operator*(const Mat4& a, const Mat4& b) {
  Mat4 out;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      double sum = 0;
      for (int k = 0; k < 4; ++k) sum += a.m[4 * k + r] * b.m[4 * c + k];
      out.m[4 * c + r] = sum;
    }
  return out;
}

Mat4 mat4_from_trs(const Vec3d& t, const Quat& rotation, const Vec3d& s) {
  double len = std::sqrt(rotation[0] * rotation[0] + rotation[1] * rotation[1] + rotation[2] * rotation[2] +
                         rotation[3] * rotation[3]);
  if (!(len > 0)) len = 1;
  const double x = rotation[0] / len, y = rotation[1] / len, z = rotation[2] / len, w = rotation[3] / len;
  // Rotation matrix columns of the unit quaternion, each scaled by its axis' scale.
  const double r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),
                       2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                       2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y)};
  Mat4 m;
  for (int c = 0; c < 3; ++c)
    for (int row = 0; row < 3; ++row) m.m[4 * c + row] = r[3 * c + row] * s[c];
  m.m[12] = t[0];
  m.m[13] = t[1];
  m.m[14] = t[2];
  return m;
}

Vec3d transform_point(const Mat4& m, const Vec3d& p) {
  Vec3d out;
  for (int r = 0; r < 3; ++r) out[r] = m.m[r] * p[0] + m.m[4 + r] * p[1] + m.m[8 + r] * p[2] + m.m[12 + r];
  return out;
}

Vec3d transform_direction(const Mat4& m, const Vec3d& d) {
  Vec3d out;
  for (int r = 0; r < 3; ++r) out[r] = m.m[r] * d[0] + m.m[4 + r] * d[1] + m.m[8 + r] * d[2];
  return out;
}

Quat slerp(const Quat& a, const Quat& b_in, double s) {
  Quat b = b_in;
  double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
  if (d < 0) {  // q and -q are the same rotation: take the shorter way
    for (double& v : b) v = -v;
    d = -d;
  }
  double wa, wb;
  if (d > 0.9995) {
    wa = 1 - s;
    wb = s;
  } else {
    const double angle = std::acos(std::min(d, 1.0));
    const double sin_angle = std::sin(angle);
    wa = std::sin((1 - s) * angle) / sin_angle;
    wb = std::sin(s * angle) / sin_angle;
  }
  Quat out;
  double len = 0;
  for (int i = 0; i < 4; ++i) {
    out[i] = wa * a[i] + wb * b[i];
    len += out[i] * out[i];
  }
  len = std::sqrt(len);
  for (double& v : out) v /= len;
  return out;
}

std::vector<double> Sampler::evaluate(double t) const {
  const size_t n = size_t(components);
  const bool cubic = interpolation == SamplerInterpolation::cubic_spline;
  // Element e of key k: CUBICSPLINE keys hold (in-tangent, value, out-tangent).
  auto element = [&](size_t k, int which) {
    const size_t index = cubic ? 3 * k + size_t(which) : k;
    return std::vector<double>(values.begin() + long(index * n), values.begin() + long((index + 1) * n));
  };
  auto normalised = [&](std::vector<double> v) {
    if (components == 4) {
      double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
      if (len > 0)
        for (double& x : v) x /= len;
    }
    return v;
  };
  if (t <= times.front() || times.size() == 1) return normalised(element(0, 1));
  if (t >= times.back()) return normalised(element(times.size() - 1, 1));
  const size_t k = size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
  const double h = times[k + 1] - times[k];
  const double s = (t - times[k]) / h;
  const std::vector<double> a = element(k, 1), b = element(k + 1, 1);
  switch (interpolation) {
    case SamplerInterpolation::step:
      return normalised(a);
    case SamplerInterpolation::linear: {
      if (components == 4) {
        const Quat q = slerp(Quat{a[0], a[1], a[2], a[3]}, Quat{b[0], b[1], b[2], b[3]}, s);
        return std::vector<double>(q.begin(), q.end());
      }
      std::vector<double> out(n);
      for (size_t c = 0; c < n; ++c) out[c] = a[c] + (b[c] - a[c]) * s;
      return out;
    }
    case SamplerInterpolation::cubic_spline: {
      const std::vector<double> out_tangent = element(k, 2), in_tangent = element(k + 1, 0);
      const double s2 = s * s, s3 = s2 * s;
      std::vector<double> out(n);
      for (size_t c = 0; c < n; ++c)
        out[c] = (2 * s3 - 3 * s2 + 1) * a[c] + (s3 - 2 * s2 + s) * h * out_tangent[c] + (-2 * s3 + 3 * s2) * b[c] +
                 (s3 - s2) * h * in_tangent[c];
      return normalised(out);
    }
  }
  return a;
}

}  // namespace pm::gltf

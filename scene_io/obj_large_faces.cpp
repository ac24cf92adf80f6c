// Large convex OBJ faces: convexity test and fan triangulation (obj_large_faces.h).
#include "scene_io/obj_large_faces.h"

#include <cmath>

namespace pm {

namespace {

using Vec = std::array<double, 3>;

Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double length(const Vec& a) { return std::sqrt(dot(a, a)); }

}  // namespace

bool is_convex_polygon(const std::vector<std::array<double, 3>>& positions, const std::vector<uint32_t>& corners) {
  const size_t n = corners.size();
  // Newell's normal, taken about the first corner to keep the products small.
  const Vec& origin = positions[corners[0]];
  Vec normal = {0, 0, 0};
  for (size_t i = 0; i < n; ++i) {
    const Vec c = cross(sub(positions[corners[i]], origin), sub(positions[corners[(i + 1) % n]], origin));
    for (int k = 0; k < 3; ++k) normal[k] += c[k];
  }
  const double normal_length = length(normal);
  if (!(normal_length > 0)) return true;
  for (double& v : normal) v /= normal_length;

  double turning = 0;  // sum of the signed exterior angles, radians
  for (size_t i = 0; i < n; ++i) {
    const Vec in = sub(positions[corners[i]], positions[corners[(i + n - 1) % n]]);
    const Vec out = sub(positions[corners[(i + 1) % n]], positions[corners[i]]);
    const double in_length = length(in), out_length = length(out);
    if (in_length == 0 || out_length == 0) continue;  // a repeated corner turns nowhere
    const double sine = dot(cross(in, out), normal) / (in_length * out_length);
    const double cosine = dot(in, out) / (in_length * out_length);
    if (sine < -1e-9) return false;  // a reflex corner
    turning += std::atan2(sine, cosine);
  }
  // Once around: 2 pi. Twice (a pentagram) or more: 4 pi and up.
  return std::fabs(turning - 2 * M_PI) < 1e-3;
}

void append_fan(const std::vector<uint32_t>& corners, const std::vector<int32_t>& texcoords, int32_t usemtl,
                std::vector<ObjFanTriangle>* out) {
  for (size_t i = 1; i + 1 < corners.size(); ++i)
    out->push_back({{corners[0], corners[i], corners[i + 1]}, usemtl, {texcoords[0], texcoords[i], texcoords[i + 1]}});
}

}  // namespace pm

// Unit tests of kernels/common/footprint.h (stage S3 and the kernels of the gather): bounds,
// point-in-ellipsoid, kernel normalisation, a uniform photon density reproducing the analytic
// irradiance, the |dp|^(-3/4) compression, the r_max clamp and degenerate differentials.
// Reference values are computed independently in double precision.
#include "kernels/common/compat_host.h"
#include "kernels/common/vec3.h"
#include "kernels/common/photon_differentials.h"
#include "kernels/common/footprint.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace {

const double kPi = 3.14159265358979323846;

float fp_uniform01(std::mt19937& g) { return (float)(g() >> 8) * (1.0f / 16777216.0f); }
float fp_uniform(std::mt19937& g, float lo, float hi) { return lo + (hi - lo) * fp_uniform01(g); }
Vec3 fp_random_vec(std::mt19937& g, float scale) {
  return vec3(fp_uniform(g, -scale, scale), fp_uniform(g, -scale, scale), fp_uniform(g, -scale, scale));
}
double fp_len(Vec3 v) { return std::sqrt((double)v.x * v.x + (double)v.y * v.y + (double)v.z * v.z); }
bool fp_finite(Vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool fp_finite(Footprint f) { return fp_finite(f.axis_u) && fp_finite(f.axis_v) && fp_finite(f.axis_n); }

// A random skewed, well-conditioned footprint.
Footprint fp_random_footprint(std::mt19937& g) {
  for (;;) {
    Footprint f;
    f.axis_u = fp_random_vec(g, 1.0f);
    f.axis_v = fp_random_vec(g, 1.0f);
    f.axis_n = fp_random_vec(g, 0.5f);
    double det = vec3_dot(f.axis_u, vec3_cross(f.axis_v, f.axis_n));
    if (std::fabs(det) > 0.05 * fp_len(f.axis_u) * fp_len(f.axis_v) * fp_len(f.axis_n)) return f;
  }
}

// Solve [a_u a_v a_n] c = r by Gaussian elimination with partial pivoting, in double.
void fp_solve(Footprint f, Vec3 r, double c[3]) {
  double m[3][4] = {{f.axis_u.x, f.axis_v.x, f.axis_n.x, r.x},
                    {f.axis_u.y, f.axis_v.y, f.axis_n.y, r.y},
                    {f.axis_u.z, f.axis_v.z, f.axis_n.z, r.z}};
  for (int col = 0; col < 3; ++col) {
    int piv = col;
    for (int row = col + 1; row < 3; ++row)
      if (std::fabs(m[row][col]) > std::fabs(m[piv][col])) piv = row;
    for (int k = 0; k < 4; ++k) std::swap(m[col][k], m[piv][k]);
    for (int row = col + 1; row < 3; ++row) {
      double factor = m[row][col] / m[col][col];
      for (int k = col; k < 4; ++k) m[row][k] -= factor * m[col][k];
    }
  }
  for (int row = 2; row >= 0; --row) {
    double s = m[row][3];
    for (int k = row + 1; k < 3; ++k) s -= m[row][k] * c[k];
    c[row] = s / m[row][row];
  }
}

}  // namespace

TEST(FootprintEllipsoid, BoundsContainSurfaceSamplesAndAreTight) {
  std::mt19937 g(101);
  for (int rep = 0; rep < 20; ++rep) {
    Footprint f = fp_random_footprint(g);
    Vec3 c = fp_random_vec(g, 10.0f);
    Vec3 lo, hi;
    footprint_bounds(f, c, &lo, &hi);
    double best_lo[3] = {1e30, 1e30, 1e30}, best_hi[3] = {-1e30, -1e30, -1e30};
    for (int i = 0; i < 200000; ++i) {
      // uniform point on the unit sphere, mapped onto the ellipsoid surface
      double z = 1.0 - 2.0 * fp_uniform01(g), phi = 2.0 * kPi * fp_uniform01(g);
      double s = std::sqrt(std::max(0.0, 1.0 - z * z));
      double x = s * std::cos(phi), y = s * std::sin(phi);
      double p[3] = {c.x + x * f.axis_u.x + y * f.axis_v.x + z * f.axis_n.x,
                     c.y + x * f.axis_u.y + y * f.axis_v.y + z * f.axis_n.y,
                     c.z + x * f.axis_u.z + y * f.axis_v.z + z * f.axis_n.z};
      double l[3] = {lo.x, lo.y, lo.z}, h[3] = {hi.x, hi.y, hi.z};
      for (int k = 0; k < 3; ++k) {
        ASSERT_GE(p[k], l[k] - 1e-5) << k;
        ASSERT_LE(p[k], h[k] + 1e-5) << k;
        best_lo[k] = std::min(best_lo[k], p[k]);
        best_hi[k] = std::max(best_hi[k], p[k]);
      }
    }
    double l[3] = {lo.x, lo.y, lo.z}, h[3] = {hi.x, hi.y, hi.z};
    for (int k = 0; k < 3; ++k) {
      EXPECT_LT(best_lo[k] - l[k], 1e-3) << "face -" << k;
      EXPECT_LT(h[k] - best_hi[k], 1e-3) << "face +" << k;
    }
  }
}

TEST(FootprintEllipsoid, ContainsAgreesWithExplicitSolve) {
  std::mt19937 g(103);
  int inside = 0, outside = 0;
  for (int rep = 0; rep < 200; ++rep) {
    Footprint f = fp_random_footprint(g);
    Vec3 c = fp_random_vec(g, 5.0f);
    for (int i = 0; i < 200; ++i) {
      Vec3 x = vec3_add(c, fp_random_vec(g, 1.5f));
      double coord[3];
      fp_solve(f, vec3_sub(x, c), coord);
      double r2 = coord[0] * coord[0] + coord[1] * coord[1] + coord[2] * coord[2];
      float got = -1.0f;
      int in = footprint_contains(f, c, x, &got);
      EXPECT_NEAR(got, r2, 1e-3 * (1.0 + r2));
      if (std::fabs(r2 - 1.0) > 1e-3) {
        EXPECT_EQ(in, r2 <= 1.0 ? 1 : 0) << r2;
        (r2 <= 1.0 ? inside : outside)++;
      }
    }
  }
  EXPECT_GT(inside, 1000);  // both outcomes exercised
  EXPECT_GT(outside, 1000);
  // A singular basis contains nothing and reports a finite r2.
  Footprint flat;
  flat.axis_u = vec3(1, 0, 0);
  flat.axis_v = vec3(2, 0, 0);
  flat.axis_n = vec3(0, 0, 1);
  float r2 = 0.0f;
  EXPECT_EQ(footprint_contains(flat, vec3(0, 0, 0), vec3(0, 0, 0), &r2), 0);
  EXPECT_TRUE(std::isfinite(r2));
  EXPECT_EQ(footprint_contains(flat, vec3(0, 0, 0), vec3(0, 0, 0), nullptr), 0);
}

// Both kernels have mean 1 over the unit disc: their integral over it is pi (midpoint rule in
// polar coordinates), and they vanish outside.
TEST(FootprintEllipsoid, KernelsIntegrateToPiOverUnitDisc) {
  const int steps = 4000;
  double sum_const = 0.0, sum_epan = 0.0;
  for (int i = 0; i < steps; ++i) {
    double r = (i + 0.5) / steps, w = 2.0 * kPi * r / steps;
    sum_const += kernel_constant((float)(r * r)) * w;
    sum_epan += kernel_epanechnikov((float)(r * r)) * w;
  }
  EXPECT_NEAR(sum_const, kPi, 1e-4);
  EXPECT_NEAR(sum_epan, kPi, 1e-4);
  EXPECT_EQ(kernel_constant(1.0001f), 0.0f);
  EXPECT_EQ(kernel_epanechnikov(1.0001f), 0.0f);
  EXPECT_EQ(kernel_epanechnikov(0.0f), 2.0f);
}

// Uniform photon density: photons with flux phi on a jittered unit grid of the plane z = 0, each
// with a fixed-radius (and, second case, skewed) footprint; at points away from the border,
// sum kernel(r2) * phi / area must equal the irradiance phi / (cell area) = phi.
TEST(FootprintEllipsoid, UniformDensityReproducesIrradiance) {
  const float delta = photon_spacing(1000u), radius = 3.0f, phi = 0.25f;
  struct Case {
    Vec3 dir_u, dir_v;
    int is_caustic;
  } cases[] = {{vec3(1, 0, 0), vec3(0, 1, 0), 1},
               {vec3(1, 0, 0), vec3(0.6f, 0.8f, 0), 1},   // skewed
               {vec3(0.8f, -0.6f, 0), vec3(0, 1, 0), 0}}; // diffuse path (compressed lengths)
  for (const Case& cs : cases) {
    std::mt19937 g(107);
    const int side = 64;
    std::vector<Vec3> pos;
    std::vector<Footprint> fps;
    for (int j = 0; j < side; ++j)
      for (int i = 0; i < side; ++i) {
        // Drawn in sequence (y first, as gcc evaluated the arguments when the tolerances were set):
        // the order of function arguments is unspecified and clang's differs.
        const float dy = fp_uniform01(g), dx = fp_uniform01(g);
        pos.push_back(vec3(i + dx, j + dy, 0.0f));
        // dp lengths chosen so the semiaxis length is `radius` in either mode
        float len = cs.is_caustic ? radius / (PM_CAUSTIC_SMOOTHING * delta)
                                  : std::pow(radius / (2.0f * delta), 4.0f);
        fps.push_back(footprint_from_differentials(vec3_scale(cs.dir_u, len), vec3_scale(cs.dir_v, len),
                                                   vec3(0, 0, 1), delta, 2.0f, 100.0f, cs.is_caustic));
      }
    EXPECT_NEAR(fp_len(fps[0].axis_u), radius, 1e-4 * radius);
    const int queries = 400;
    double mean_c = 0.0, mean_e = 0.0;
    for (int q = 0; q < queries; ++q) {
      const float qy = fp_uniform(g, 8.0f, side - 8.0f), qx = fp_uniform(g, 8.0f, side - 8.0f);  // as above
      Vec3 x = vec3(qx, qy, 0.0f);
      double est_c = 0.0, est_e = 0.0;
      for (size_t k = 0; k < pos.size(); ++k) {
        float r2;
        if (!footprint_contains(fps[k], pos[k], x, &r2)) continue;
        double area = footprint_area(fps[k]);
        est_c += kernel_constant(r2) * phi / area;
        est_e += kernel_epanechnikov(r2) * phi / area;
      }
      EXPECT_NEAR(est_c, phi, 0.3 * phi);
      EXPECT_NEAR(est_e, phi, 0.2 * phi);
      mean_c += est_c / queries;
      mean_e += est_e / queries;
    }
    EXPECT_NEAR(mean_c, phi, 0.02 * phi) << cs.is_caustic;
    EXPECT_NEAR(mean_e, phi, 0.02 * phi) << cs.is_caustic;
  }
}

// Diffuse photons: a = s Delta dp |dp|^(-3/4) (exponent on the differential, scene units), so
// |a| = s Delta |dp|^(1/4): a range of 1e4 in |dp| becomes 10 in radius, anisotropy ratios are
// compressed the same way, and scaling the scene by k scales radii by k^(1/4) (not invariant).
TEST(FootprintEllipsoid, DiffuseCompressionIsQuarterPower) {
  const float delta = 0.01f, s = 20.0f, rmax = 1e6f;
  const Vec3 n = vec3(0, 0, 1);
  double rmin_seen = 1e30, rmax_seen = 0.0;
  for (int e = -2; e <= 2; ++e) {
    double L = std::pow(10.0, e);
    Vec3 du = vec3((float)L, 0, 0), dv = vec3(0, (float)L, 0);
    Footprint f = footprint_from_differentials(du, dv, n, delta, s, rmax, 0);
    double expected = s * delta * L * std::pow(L, -0.75);
    EXPECT_NEAR(fp_len(f.axis_u), expected, 1e-5 * expected) << L;
    EXPECT_NEAR(f.axis_u.x / fp_len(f.axis_u), 1.0, 1e-6);  // direction kept
    rmin_seen = std::min(rmin_seen, fp_len(f.axis_u));
    rmax_seen = std::max(rmax_seen, fp_len(f.axis_u));
  }
  EXPECT_NEAR(rmax_seen / rmin_seen, 10.0, 1e-4);  // (1e4)^(1/4)
  // anisotropy 16:1 in dp becomes 2:1; skew (angle between the axes) is kept
  Footprint f = footprint_from_differentials(vec3(16, 0, 0), vec3(0.6f, 0.8f, 0), n, delta, s, rmax, 0);
  EXPECT_NEAR(fp_len(f.axis_u) / fp_len(f.axis_v), 2.0, 1e-5);
  EXPECT_NEAR(vec3_dot(f.axis_u, f.axis_v) / (fp_len(f.axis_u) * fp_len(f.axis_v)), 0.6, 1e-6);
  // not scale-invariant: k = 1e4 scales the radius by 10
  Footprint small = footprint_from_differentials(vec3(0.5f, 0, 0), vec3(0, 0.5f, 0), n, delta, s, rmax, 0);
  Footprint big = footprint_from_differentials(vec3(5000, 0, 0), vec3(0, 5000, 0), n, delta, s, rmax, 0);
  EXPECT_NEAR(fp_len(big.axis_u) / fp_len(small.axis_u), 10.0, 1e-4);
  // caustic photons: linear in dp, s = 5 whatever the smoothing argument
  Footprint c1 = footprint_from_differentials(vec3(3, 0, 0), vec3(0, 1, 0), n, delta, s, rmax, 1);
  Footprint c2 = footprint_from_differentials(vec3(3, 0, 0), vec3(0, 1, 0), n, delta, 77.0f, rmax, 1);
  EXPECT_NEAR(fp_len(c1.axis_u), 5.0 * delta * 3.0, 1e-6);
  EXPECT_NEAR(fp_len(c1.axis_v), 5.0 * delta * 1.0, 1e-6);
  EXPECT_EQ(fp_len(c1.axis_u), fp_len(c2.axis_u));
  // caustic footprint area = s^2 * eq. 10 area
  EXPECT_NEAR(footprint_area(c1), 25.0 * photon_footprint_area(vec3(3, 0, 0), vec3(0, 1, 0), delta),
              1e-5 * footprint_area(c1));
}

TEST(FootprintEllipsoid, SemiaxesClampedToRmaxAndNormalAxis) {
  const float delta = 0.01f, rmax = 0.7f;
  // caustic: lengths 5 * 0.01 * {40, 4} = {2.0, 0.2}: the first is clamped, the second is not
  Vec3 du = vec3(24, 32, 0), dv = vec3(0, 0, 4);
  Vec3 normal = vec3(1, -0.75f, 0);  // unnormalised on purpose, perpendicular to du and dv
  Footprint f = footprint_from_differentials(du, dv, normal, delta, 1.0f, rmax, 1);
  EXPECT_NEAR(fp_len(f.axis_u), rmax, 1e-6);
  EXPECT_NEAR(f.axis_u.x / fp_len(f.axis_u), 0.6, 1e-6);
  EXPECT_NEAR(fp_len(f.axis_v), 0.2, 1e-6);
  double h = PM_FOOTPRINT_NORMAL_RATIO * 0.2;
  EXPECT_NEAR(fp_len(f.axis_n), h, 1e-6);
  EXPECT_NEAR(f.axis_n.x / fp_len(f.axis_n), 0.8, 1e-6);  // along the unit normal
  // points off the plane along the normal are inside iff |offset| <= h
  Vec3 c = vec3(1, 2, 3), nu = vec3(0.8f, -0.6f, 0);
  EXPECT_TRUE(footprint_contains(f, c, vec3_madd(c, nu, (float)(0.99 * h)), nullptr));
  EXPECT_FALSE(footprint_contains(f, c, vec3_madd(c, nu, (float)(1.01 * h)), nullptr));
  // diffuse: s Delta |dp|^(1/4) = 10 * 0.01 * 10^(4/4) = 1.0 > rmax
  Footprint d = footprint_from_differentials(vec3(1e4f, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1), delta, 10.0f, rmax, 0);
  EXPECT_NEAR(fp_len(d.axis_u), rmax, 1e-6);
  EXPECT_NEAR(fp_len(d.axis_v), 0.1, 1e-6);
}

TEST(FootprintEllipsoid, DegenerateDifferentialsGiveFiniteFootprints) {
  const float delta = 0.01f, rmax = 0.7f;
  const float inf = INFINITY, nan = NAN;
  const Vec3 n = vec3(0, 1, 0);
  struct Case {
    Vec3 du, dv, normal;
  } cases[] = {
      {vec3(0, 0, 0), vec3(0, 0, 0), n},       // zero
      {vec3(1, 0, 0), vec3(0, 0, 0), n},       // one zero
      {vec3(1, 0, 0), vec3(2, 0, 0), n},       // parallel
      {vec3(1, 0, 0), vec3(-3, 0, 1e-7f), n},  // nearly antiparallel
      {vec3(inf, 0, 0), vec3(0, 0, 1), n},     // infinite
      {vec3(nan, 0, 0), vec3(nan, 0, 1), n},   // NaN
      {vec3(1e-30f, 0, 0), vec3(0, 0, 1e-30f), n},
      {vec3(1e30f, 0, 0), vec3(0, 0, 1e30f), n},
      {vec3(1, 0, 0), vec3(0, 0, 1), vec3(0, 0, 0)},  // no normal
      {vec3(0, 0, 0), vec3(0, 0, 0), vec3(nan, 0, 0)},
  };
  for (int caustic = 0; caustic < 2; ++caustic) {
    int index = 0;
    for (const Case& cs : cases) {
      Footprint f = footprint_from_differentials(cs.du, cs.dv, cs.normal, delta, 10.0f, rmax, caustic);
      ASSERT_TRUE(fp_finite(f)) << index;
      double area = footprint_area(f);
      EXPECT_TRUE(std::isfinite(area)) << index;
      EXPECT_GT(area, 0.0) << index;
      EXPECT_LE(fp_len(f.axis_u), rmax * (1 + 1e-6)) << index;
      EXPECT_LE(fp_len(f.axis_v), rmax * (1 + 1e-6)) << index;
      Vec3 lo, hi;
      footprint_bounds(f, vec3(1, 1, 1), &lo, &hi);
      EXPECT_TRUE(fp_finite(lo) && fp_finite(hi)) << index;
      float r2 = -1.0f;
      EXPECT_TRUE(footprint_contains(f, vec3(1, 1, 1), vec3(1, 1, 1), &r2)) << index;
      EXPECT_TRUE(std::isfinite(r2)) << index;
      ++index;
    }
  }
  // both zero: circle of radius rmax * PM_FOOTPRINT_FALLBACK_FRACTION in the plane of the normal
  Footprint z = footprint_from_differentials(vec3(0, 0, 0), vec3(0, 0, 0), n, delta, 10.0f, rmax, 0);
  double r = rmax * PM_FOOTPRINT_FALLBACK_FRACTION;
  EXPECT_NEAR(footprint_area(z), kPi * r * r, 1e-5);
  EXPECT_NEAR(vec3_dot(z.axis_u, n), 0.0, 1e-6);
  EXPECT_NEAR(vec3_dot(z.axis_v, n), 0.0, 1e-6);
  EXPECT_NEAR(vec3_dot(z.axis_u, z.axis_v), 0.0, 1e-6);
  // parallel: circle with the longer usable semiaxis (caustic: 5 * 0.01 * 2 = 0.1)
  Footprint p = footprint_from_differentials(vec3(1, 0, 0), vec3(2, 0, 0), n, delta, 10.0f, rmax, 1);
  EXPECT_NEAR(fp_len(p.axis_u), 0.1, 1e-6);
  EXPECT_NEAR(fp_len(p.axis_v), 0.1, 1e-6);
}

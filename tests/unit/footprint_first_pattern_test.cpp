// Unit tests of the coverage probes' first pattern (kernels/common/footprint_coverage.h): 16 of the
// whole pattern's 64 probes, written as a table and a mask that must agree, and chosen to tell an
// edge, which is all a footprint's first pattern decides (a footprint it finds partly covered is
// measured with all 64). Telling an edge is measured as the kernel mass left uncovered in the
// footprints whose 16 probes are all covered (their flux is then spread over the whole disc, and
// the light over that mass is lost), over random rims, corners and holes about a covered centre
// (the photon's own hit lies on the surface); the pattern must lose no more than a 16-point
// Vogel spiral of its own, the first pattern before it was nested in the whole.
#include "kernels/common/compat_host.h"
#include "kernels/common/footprint_coverage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <set>
#include <vector>

namespace pm {
namespace {

TEST(FootprintFirstPattern, TheTableAndTheMaskNameTheSameSixteenProbes) {
  std::set<uint> table;
  for (uint j = 0; j < PM_FOOTPRINT_PROBES; ++j) {
    const uint q = footprint_first_probe(j);
    ASSERT_LT(q, PM_FOOTPRINT_EDGE_PROBES);
    table.insert(q);
  }
  EXPECT_EQ(table.size(), size_t(PM_FOOTPRINT_PROBES));
  for (uint q = 0; q < PM_FOOTPRINT_EDGE_PROBES; ++q)
    EXPECT_EQ(footprint_probe_in_first(q), table.count(q) ? 1u : 0u) << "probe " << q;
  // The second pattern's walk by angle begins at probe 0 (footprint_second_probe_next).
  EXPECT_EQ(footprint_probe_in_first(0u), 0u);
}

struct Point {
  double x, y;
};

// A footprint's covered region: true where a surface lies under disc point p.
using Region = std::function<bool(Point)>;

// Random regions of one kind about a covered centre.
struct RegionKind {
  const char* name;
  std::function<Region(std::mt19937&)> draw;
};

double uniform(std::mt19937& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

std::vector<RegionKind> region_kinds() {
  auto side = [](double angle, double d) {  // covered where p . (cos, sin) <= d
    const double c = std::cos(angle), s = std::sin(angle);
    return [=](Point p) { return p.x * c + p.y * s <= d; };
  };
  return {
      {"straight rim",
       [=](std::mt19937& rng) { return Region(side(uniform(rng, 0, 2 * M_PI), uniform(rng, 0, 1))); }},
      {"convex corner",
       [=](std::mt19937& rng) {
         const double a = uniform(rng, 0, 2 * M_PI), b = a + uniform(rng, 0.3 * M_PI, M_PI);
         auto first = side(a, uniform(rng, 0, 1)), second = side(b, uniform(rng, 0, 1));
         return Region([=](Point p) { return first(p) && second(p); });
       }},
      {"concave corner",
       [=](std::mt19937& rng) {
         const double a = uniform(rng, 0, 2 * M_PI), b = a + uniform(rng, 0.3 * M_PI, M_PI);
         auto first = side(a, uniform(rng, 0, 1)), second = side(b, uniform(rng, 0, 1));
         return Region([=](Point p) { return first(p) || second(p); });
       }},
      {"hole",
       [=](std::mt19937& rng) {
         const double radius = uniform(rng, 0.05, 0.5), at = radius + uniform(rng, 0, 1);
         const double angle = uniform(rng, 0, 2 * M_PI), cx = at * std::cos(angle), cy = at * std::sin(angle);
         return Region([=](Point p) { return (p.x - cx) * (p.x - cx) + (p.y - cy) * (p.y - cy) > radius * radius; });
       }},
  };
}

// Points of a `count`-probe Vogel spiral, unturned.
std::vector<Point> spiral(uint count) {
  std::vector<Point> points;
  for (uint j = 0; j < count; ++j) {
    float x, y;
    footprint_probe_point(j, count, 0.0f, &x, &y);
    points.push_back({x, y});
  }
  return points;
}

std::vector<Point> first_pattern() {
  std::vector<Point> points;
  for (uint j = 0; j < PM_FOOTPRINT_PROBES; ++j) {
    float x, y;
    footprint_probe_point(footprint_first_probe(j), PM_FOOTPRINT_EDGE_PROBES, 0.0f, &x, &y);
    points.push_back({x, y});
  }
  return points;
}

// The mean kernel mass (of 1) left uncovered in the regions whose probes at `pattern` are all
// covered, over `draws` regions of `kind` (the same regions for every pattern).
double mass_missed(const RegionKind& kind, const std::vector<Point>& pattern, uint shape, int draws) {
  const std::vector<Point> fine = spiral(2000);  // the kernel's mass, point by point
  std::vector<double> weight;
  double total = 0;
  for (const Point& p : fine) {
    weight.push_back(shape == PM_KERNEL_EPANECHNIKOV ? kernel_epanechnikov(float(p.x * p.x + p.y * p.y)) : 1.0);
    total += weight.back();
  }
  std::mt19937 rng(20261202u);
  double missed = 0;
  for (int i = 0; i < draws; ++i) {
    const Region covered = kind.draw(rng);
    if (!covered({0, 0})) continue;  // the photon's own hit is on the surface
    bool all_covered = true;
    for (const Point& p : pattern) all_covered = all_covered && covered(p);
    if (!all_covered) continue;
    double open = 0;
    for (size_t k = 0; k < fine.size(); ++k)
      if (!covered(fine[k])) open += weight[k];
    missed += open / total;
  }
  return missed / draws;
}

TEST(FootprintFirstPattern, TellsAnEdgeAtLeastAsWellAsASpiralOfSixteen) {
  const std::vector<Point> nested = first_pattern(), own = spiral(PM_FOOTPRINT_PROBES);
  for (uint shape : {uint(PM_KERNEL_CONSTANT), uint(PM_KERNEL_EPANECHNIKOV)})
    for (const RegionKind& kind : region_kinds()) {
      const double missed_nested = mass_missed(kind, nested, shape, 20000);
      const double missed_own = mass_missed(kind, own, shape, 20000);
      EXPECT_GT(missed_own, 0.0) << kind.name;  // the measure sees what 16 probes miss
      EXPECT_LE(missed_nested, missed_own) << kind.name << ", kernel " << shape;
      std::printf("%-14s kernel %u: uncovered mass missed, first pattern %.3e, spiral of 16 %.3e (%.2f)\n", kind.name,
                  shape, missed_nested, missed_own, missed_nested / missed_own);
    }
}

}  // namespace
}  // namespace pm

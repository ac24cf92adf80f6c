// The analysis half of `pmrender tradeoff` on known points: the Pareto front (dominated points
// off, ties and duplicates on, non-finite points never), the budget and target picks, and the SVG
// plot's escaping and structure.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "render/tradeoff/pareto.h"
#include "render/tradeoff/svg_plot.h"

namespace pm {
namespace {

TEST(ParetoFront, KnownPoints) {
  // time, error: the front is the staircase 1/0.5, 2/0.3, 5/0.1, 9/0.05.
  const std::vector<TradeoffPoint> points = {
      {1, 0.5},   // front: fastest
      {2, 0.3},   // front
      {3, 0.3},   // off: as accurate as #1 but slower
      {4, 0.4},   // off: beaten by #1 in both
      {5, 0.1},   // front
      {9, 0.05},  // front: most accurate
      {10, 0.2},  // off
      {2, 0.6},   // off: as fast as #1, less accurate
  };
  const std::vector<bool> expected = {true, true, false, false, true, true, false, false};
  EXPECT_EQ(pareto_front(points), expected);
}

TEST(ParetoFront, EqualPointsAreAllOnTheFrontAndNonFiniteNever) {
  const std::vector<TradeoffPoint> points = {{1, 1}, {1, 1}, {NAN, 0.0}, {0.5, INFINITY}, {2, 0.5}};
  const std::vector<bool> expected = {true, true, false, false, true};
  EXPECT_EQ(pareto_front(points), expected);
  EXPECT_TRUE(pareto_front({}).empty());
  EXPECT_EQ(pareto_front({{3, 0.2}}), std::vector<bool>{true});
}

TEST(ParetoFront, EveryPointOffTheFrontIsDominatedByOneOnIt) {
  // A grid of points on two crossing curves, checked against the definition directly.
  std::vector<TradeoffPoint> points;
  for (int i = 1; i <= 20; ++i) {
    points.push_back({double(i), 1.0 / i});
    points.push_back({double(i) * 1.5, 0.8 / i + 0.01 * i});
  }
  const std::vector<bool> front = pareto_front(points);
  for (size_t i = 0; i < points.size(); ++i) {
    bool dominated = false;
    for (size_t j = 0; j < points.size(); ++j)
      dominated |= points[j].time_ms <= points[i].time_ms && points[j].error <= points[i].error &&
                   (points[j].time_ms < points[i].time_ms || points[j].error < points[i].error);
    EXPECT_EQ(front[i], !dominated) << i;
  }
}

TEST(TradeoffPicks, BudgetAndTarget) {
  const std::vector<TradeoffPoint> points = {{1, 0.5}, {2, 0.3}, {5, 0.1}, {9, 0.05}, {5, 0.1}};
  EXPECT_EQ(best_within_time(points, 0.5), -1);
  EXPECT_EQ(best_within_time(points, 1), 0);
  EXPECT_EQ(best_within_time(points, 4.9), 1);
  EXPECT_EQ(best_within_time(points, 6), 2) << "ties: the first";
  EXPECT_EQ(best_within_time(points, 100), 3);
  EXPECT_EQ(fastest_within_error(points, 0.01), -1);
  EXPECT_EQ(fastest_within_error(points, 0.05), 3);
  EXPECT_EQ(fastest_within_error(points, 0.2), 2);
  EXPECT_EQ(fastest_within_error(points, 1), 0);
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(SvgPlot, EscapesLabelsAndMarksTheFront) {
  EXPECT_EQ(xml_escape("a<b & \"c\" 'd'>"), "a&lt;b &amp; &quot;c&quot; &apos;d&apos;&gt;");
  const std::vector<PlotPoint> points = {{10, 0.1, "pd <fast>", "photon pd", true},
                                         {100, 0.01, "path & slow", "path tracer", true},
                                         {200, 0.05, "knn", "photon knn", false},
                                         {0, 0.05, "zero time", "photon knn", false}};
  const std::string svg = svg_scatter_plot(points, {"title & more", "time", "error"});
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("<svg xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos);
  EXPECT_NE(svg.find("pd &lt;fast&gt;"), std::string::npos);
  EXPECT_NE(svg.find("path &amp; slow"), std::string::npos);
  EXPECT_NE(svg.find("title &amp; more"), std::string::npos);
  EXPECT_EQ(svg.find("<fast>"), std::string::npos);
  EXPECT_EQ(count(svg, "stroke-dasharray"), 1) << "one front line";
  EXPECT_EQ(count(svg, "r=\"7\""), 3) << "two ringed front points and the legend's ring";
  EXPECT_NE(svg.find("1 point(s) off the log axes"), std::string::npos);
  EXPECT_EQ(count(svg, "<svg"), 1);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
}

}  // namespace
}  // namespace pm

// A small, plain SVG writer for `pmrender tradeoff`: error against time on log-log axes, one
// colour per series (method or estimator), every point labelled, the Pareto front drawn as the
// staircase of the best error reachable by each time and its points ringed. A standalone
// document any browser opens; no scripts, no external references.
#pragma once

#include <string>
#include <vector>

namespace pm {

struct PlotPoint {
  double x = 0, y = 0;  // both > 0 and finite, or the point is left out (log axes)
  std::string label;    // short text beside the point
  std::string series;   // colour and legend entry
  bool on_front = false;
};

struct PlotText {
  std::string title, x_label, y_label;
};

std::string svg_scatter_plot(const std::vector<PlotPoint>& points, const PlotText& text);

// Text with &, <, >, " and ' replaced by XML entities.
std::string xml_escape(const std::string& text);

}  // namespace pm

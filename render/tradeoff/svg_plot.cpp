// Log-log scatter plot as SVG text (svg_plot.h).
#include "render/tradeoff/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace pm {

namespace {

constexpr double kWidth = 960, kHeight = 620;
constexpr double kLeft = 90, kRight = 230, kTop = 50, kBottom = 70;
const char* const kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};

bool plottable(const PlotPoint& p) { return std::isfinite(p.x) && std::isfinite(p.y) && p.x > 0 && p.y > 0; }

// Whole decades around [lo, hi], at least one.
void decade_range(double lo, double hi, double* first, double* last) {
  *first = std::floor(std::log10(lo));
  *last = std::ceil(std::log10(hi));
  if (*last <= *first) *last = *first + 1;
}

std::string num(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f", v);
  return text;
}

std::string tick_text(double decade) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", std::pow(10.0, decade));
  return text;
}

}  // namespace

std::string xml_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string svg_scatter_plot(const std::vector<PlotPoint>& points, const PlotText& text) {
  std::vector<const PlotPoint*> shown;
  for (const PlotPoint& p : points)
    if (plottable(p)) shown.push_back(&p);
  double x_lo = 1, x_hi = 10, y_lo = 0.01, y_hi = 0.1;
  if (!shown.empty()) {
    x_lo = x_hi = shown[0]->x;
    y_lo = y_hi = shown[0]->y;
    for (const PlotPoint* p : shown) {
      x_lo = std::min(x_lo, p->x), x_hi = std::max(x_hi, p->x);
      y_lo = std::min(y_lo, p->y), y_hi = std::max(y_hi, p->y);
    }
  }
  double x0, x1, y0, y1;
  decade_range(x_lo, x_hi, &x0, &x1);
  decade_range(y_lo, y_hi, &y0, &y1);
  const double plot_w = kWidth - kLeft - kRight, plot_h = kHeight - kTop - kBottom;
  auto sx = [&](double x) { return kLeft + (std::log10(x) - x0) / (x1 - x0) * plot_w; };
  auto sy = [&](double y) { return kTop + (y1 - std::log10(y)) / (y1 - y0) * plot_h; };

  std::vector<std::string> series;
  for (const PlotPoint* p : shown)
    if (std::find(series.begin(), series.end(), p->series) == series.end()) series.push_back(p->series);
  auto colour = [&](const std::string& name) {
    const size_t i = size_t(std::find(series.begin(), series.end(), name) - series.begin());
    return kPalette[i % (sizeof(kPalette) / sizeof(kPalette[0]))];
  };

  std::ostringstream s;
  s << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << kHeight
    << "\" viewBox=\"0 0 " << kWidth << " " << kHeight << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<text x=\"" << kLeft << "\" y=\"28\" font-size=\"16\">" << xml_escape(text.title) << "</text>\n";
  // Decade grid, ticks and their labels.
  for (double d = x0; d <= x1; ++d) {
    const std::string x = num(sx(std::pow(10.0, d)));
    s << "<line x1=\"" << x << "\" y1=\"" << kTop << "\" x2=\"" << x << "\" y2=\"" << kTop + plot_h
      << "\" stroke=\"#ddd\"/>\n<text x=\"" << x << "\" y=\"" << kTop + plot_h + 18 << "\" text-anchor=\"middle\">"
      << tick_text(d) << "</text>\n";
  }
  for (double d = y0; d <= y1; ++d) {
    const std::string y = num(sy(std::pow(10.0, d)));
    s << "<line x1=\"" << kLeft << "\" y1=\"" << y << "\" x2=\"" << kLeft + plot_w << "\" y2=\"" << y
      << "\" stroke=\"#ddd\"/>\n<text x=\"" << kLeft - 6 << "\" y=\"" << y << "\" text-anchor=\"end\" dy=\"4\">"
      << tick_text(d) << "</text>\n";
  }
  s << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << plot_w << "\" height=\"" << plot_h
    << "\" fill=\"none\" stroke=\"black\"/>\n"
    << "<text x=\"" << kLeft + plot_w / 2 << "\" y=\"" << kHeight - 24 << "\" text-anchor=\"middle\">"
    << xml_escape(text.x_label) << " (log)</text>\n"
    << "<text transform=\"translate(22," << kTop + plot_h / 2 << ") rotate(-90)\" text-anchor=\"middle\">"
    << xml_escape(text.y_label) << " (log)</text>\n";

  // The front: the best error reachable by each time, a staircase through the front's points.
  std::vector<const PlotPoint*> front;
  for (const PlotPoint* p : shown)
    if (p->on_front) front.push_back(p);
  std::sort(front.begin(), front.end(), [](const PlotPoint* a, const PlotPoint* b) { return a->x < b->x; });
  if (!front.empty()) {
    s << "<path d=\"M" << num(sx(front[0]->x)) << " " << num(sy(front[0]->y));
    for (size_t i = 1; i < front.size(); ++i) s << " H" << num(sx(front[i]->x)) << " V" << num(sy(front[i]->y));
    s << " H" << num(kLeft + plot_w) << "\" fill=\"none\" stroke=\"black\" stroke-width=\"1.5\" "
      << "stroke-dasharray=\"6 3\"/>\n";
  }
  for (const PlotPoint* p : shown) {
    const std::string cx = num(sx(p->x)), cy = num(sy(p->y));
    if (p->on_front)
      s << "<circle cx=\"" << cx << "\" cy=\"" << cy << "\" r=\"7\" fill=\"none\" stroke=\"black\" stroke-width=\"1.5\"/>\n";
    s << "<circle cx=\"" << cx << "\" cy=\"" << cy << "\" r=\"4\" fill=\"" << colour(p->series) << "\"><title>"
      << xml_escape(p->label) << "</title></circle>\n"
      << "<text x=\"" << num(sx(p->x) + 8) << "\" y=\"" << num(sy(p->y) - 6) << "\" font-size=\"9\" fill=\"#333\">"
      << xml_escape(p->label) << "</text>\n";
  }
  // Legend.
  double ly = kTop + 10;
  for (const std::string& name : series) {
    s << "<circle cx=\"" << kWidth - kRight + 24 << "\" cy=\"" << ly << "\" r=\"5\" fill=\"" << colour(name)
      << "\"/>\n<text x=\"" << kWidth - kRight + 36 << "\" y=\"" << ly + 4 << "\">" << xml_escape(name) << "</text>\n";
    ly += 20;
  }
  s << "<circle cx=\"" << kWidth - kRight + 24 << "\" cy=\"" << ly << "\" r=\"7\" fill=\"none\" stroke=\"black\" "
    << "stroke-width=\"1.5\"/>\n<text x=\"" << kWidth - kRight + 36 << "\" y=\"" << ly + 4
    << "\">Pareto front</text>\n";
  if (shown.size() < points.size())
    s << "<text x=\"" << kWidth - kRight + 16 << "\" y=\"" << ly + 28 << "\" font-size=\"10\">"
      << points.size() - shown.size() << " point(s) off the log axes</text>\n";
  s << "</svg>\n";
  return s.str();
}

}  // namespace pm

// Errors, Pareto marking and the table / JSON / SVG of `pmrender tradeoff` (tradeoff_report.h).
#include "cli/tradeoff_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "render/errors.h"
#include "render/image_metrics.h"
#include "render/tradeoff/pareto.h"
#include "render/tradeoff/svg_plot.h"

namespace pm::cli {

namespace {

std::string number_percent(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g%%", 100 * v);
  return text;
}

}  // namespace

TradeoffErrors tradeoff_errors(const FrameImage& reference, const FrameImage& test) {
  if (reference.width != test.width || reference.height != test.height)
    throw InputError("reference is " + std::to_string(reference.width) + "x" + std::to_string(reference.height) +
                     " but the render is " + std::to_string(test.width) + "x" + std::to_string(test.height));
  const std::vector<float>& ref = reference.find("")->rgb;
  const std::vector<float>& img = test.find("")->rgb;
  const ImageComparison c = compare_images(ref, img, test.width, test.height);
  TradeoffErrors e;
  e.relmae = c.relmae;
  e.relmse = c.relmse;
  e.flip = c.flip;
  const LightBias bias = light_bias(reference, test);
  e.mean = bias.mean;
  e.indirect = bias.indirect;
  return e;
}

bool is_tradeoff_metric(const std::string& metric) { return metric == "relmae" || metric == "relmse" || metric == "flip"; }

std::string tradeoff_metric_title(const std::string& metric) {
  if (metric == "relmse") return "relative mean squared error";
  if (metric == "flip") return "mean HDR-FLIP";
  return "relative mean absolute error";
}

double TradeoffRow::error(const std::string& metric) const {
  if (metric == "relmse") return errors.relmse;
  if (metric == "flip") return errors.flip;
  return errors.relmae;
}

void mark_pareto_front(std::vector<TradeoffRow>& rows, const std::string& metric) {
  std::vector<TradeoffPoint> points;
  for (const TradeoffRow& r : rows) points.push_back({r.device_ms.median, r.error(metric)});
  const std::vector<bool> front = pareto_front(points);
  for (size_t i = 0; i < rows.size(); ++i) rows[i].front = front[i];
}

std::string tradeoff_table(const std::vector<TradeoffRow>& rows, const std::string& metric) {
  std::ostringstream s;
  char line[256];
  const std::string front = "front (" + metric + ")";
  std::snprintf(line, sizeof(line), "%3s  %-28s %11s %11s %8s %9s %7s %7s %9s  %s\n", "#", "setting", "device ms",
                "wall ms", "relMAE", "relMSE", "FLIP", "mean", "indirect", front.c_str());
  s << line;
  for (size_t i = 0; i < rows.size(); ++i) {
    const TradeoffRow& r = rows[i];
    std::snprintf(line, sizeof(line), "%3zu  %-28s %11.3f %11.3f %7.3f%% %9.3g %7.4f %+6.2f%% %+8.2f%%  %s\n", i + 1,
                  r.setting.label().c_str(), r.device_ms.median, r.wall_ms.median, 100 * r.errors.relmae,
                  r.errors.relmse, r.errors.flip, 100 * r.errors.mean, 100 * r.errors.indirect, r.front ? "*" : "");
    s << line;
  }
  return s.str();
}

namespace {

// Series in order of first appearance: estimator, then one pass or several.
std::vector<std::string> mode_series(const std::vector<TradeoffRow>& rows, std::vector<std::string>* of_row) {
  std::vector<std::string> names;
  for (const TradeoffRow& r : rows) {
    // Radiosity is deterministic: one pass, nothing to tell apart.
    const std::string name = r.setting.estimator == "radiosity"
                                 ? r.setting.estimator
                                 : r.setting.estimator + (r.setting.passes > 1 ? " (passes > 1)" : " (1 pass)");
    of_row->push_back(name);
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  }
  return names;
}

// Index of the fastest row of series reaching level, or -1; the row with the smallest error.
int fastest_reaching(const std::vector<TradeoffRow>& rows, const std::vector<std::string>& of_row,
                     const std::string& series, const std::string& metric, double level) {
  std::vector<TradeoffPoint> points;
  for (size_t i = 0; i < rows.size(); ++i)
    points.push_back({rows[i].device_ms.median, of_row[i] == series ? rows[i].error(metric) : INFINITY});
  return fastest_within_error(points, level);
}

// Index of the fastest row of any series reaching level, or -1: the method to pick for it.
int fastest_overall(const std::vector<TradeoffRow>& rows, const std::string& metric, double level) {
  std::vector<TradeoffPoint> points;
  for (const TradeoffRow& r : rows) points.push_back({r.device_ms.median, r.error(metric)});
  return fastest_within_error(points, level);
}

int most_accurate(const std::vector<TradeoffRow>& rows, const std::vector<std::string>& of_row,
                  const std::string& series, const std::string& metric) {
  std::vector<TradeoffPoint> points;
  for (size_t i = 0; i < rows.size(); ++i)
    points.push_back({of_row[i] == series ? rows[i].device_ms.median : INFINITY, rows[i].error(metric)});
  return best_within_time(points, INFINITY);
}

}  // namespace

std::string time_to_error_table(const std::vector<TradeoffRow>& rows, const std::string& metric,
                                const std::vector<double>& levels, double floor) {
  std::vector<std::string> of_row;
  const std::vector<std::string> series = mode_series(rows, &of_row);
  std::ostringstream s;
  char cell[96];
  std::snprintf(cell, sizeof(cell), "%-22s", ("device ms to reach " + metric).c_str());
  s << cell;
  for (double level : levels) {
    std::snprintf(cell, sizeof(cell), " %12s", (number_percent(level) + (level <= floor ? " (noise)" : "")).c_str());
    s << cell;
  }
  s << "   smallest error (at ms)\n";
  for (const std::string& name : series) {
    std::snprintf(cell, sizeof(cell), "%-22s", name.c_str());
    s << cell;
    for (double level : levels) {
      const int i = fastest_reaching(rows, of_row, name, metric, level);
      if (i < 0) std::snprintf(cell, sizeof(cell), " %12s", "-");
      else std::snprintf(cell, sizeof(cell), " %12.3f", rows[size_t(i)].device_ms.median);
      s << cell;
    }
    const int best = most_accurate(rows, of_row, name, metric);
    if (best >= 0) {
      std::snprintf(cell, sizeof(cell), "   %s (%.3f)", number_percent(rows[size_t(best)].error(metric)).c_str(),
                    rows[size_t(best)].device_ms.median);
      s << cell;
    }
    s << "\n";
  }
  s << "fastest to each level:";
  for (size_t l = 0; l < levels.size(); ++l) {
    const int i = fastest_overall(rows, metric, levels[l]);
    s << (l ? "; " : " ") << number_percent(levels[l]) << " ";
    if (i < 0) {
      s << "none";
      continue;
    }
    std::snprintf(cell, sizeof(cell), "%s, %s (%.3f ms)", of_row[size_t(i)].c_str(), rows[size_t(i)].setting.label().c_str(),
                  rows[size_t(i)].device_ms.median);
    s << cell;
  }
  s << "\n";
  if (floor > 0) s << "(noise): at or under twice the reference's own noise, " << number_percent(floor / 2) << "\n";
  return s.str();
}

nlohmann::ordered_json time_to_error_json(const std::vector<TradeoffRow>& rows, const std::string& metric,
                                          const std::vector<double>& levels, double floor) {
  std::vector<std::string> of_row;
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const std::string& name : mode_series(rows, &of_row)) {
    nlohmann::ordered_json reach = nlohmann::ordered_json::array();
    for (double level : levels) {
      const int i = fastest_reaching(rows, of_row, name, metric, level);
      reach.push_back({{"error", level},
                       {"below_reference_noise", level <= floor},
                       {"device_ms", i < 0 ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(rows[size_t(i)].device_ms.median)},
                       {"setting", i < 0 ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(rows[size_t(i)].setting.label())}});
    }
    const int best = most_accurate(rows, of_row, name, metric);
    out.push_back({{"series", name},
                   {"reach", reach},
                   {"smallest_error", best < 0 ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(rows[size_t(best)].error(metric))},
                   {"smallest_error_setting", best < 0 ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(rows[size_t(best)].setting.label())}});
  }
  return out;
}

nlohmann::ordered_json fastest_per_level_json(const std::vector<TradeoffRow>& rows, const std::string& metric,
                                              const std::vector<double>& levels) {
  std::vector<std::string> of_row;
  mode_series(rows, &of_row);
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (double level : levels) {
    const int i = fastest_overall(rows, metric, level);
    if (i < 0) {
      out.push_back({{"error", level}, {"series", nullptr}, {"setting", nullptr}, {"device_ms", nullptr}});
      continue;
    }
    const TradeoffRow& r = rows[size_t(i)];
    out.push_back({{"error", level}, {"series", of_row[size_t(i)]}, {"setting", r.setting.label()},
                   {"device_ms", r.device_ms.median}});
  }
  return out;
}

nlohmann::ordered_json tradeoff_json_rows(const std::vector<TradeoffRow>& rows) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const TradeoffRow& r : rows) {
    nlohmann::ordered_json j;
    j["label"] = r.setting.label();
    j["estimator"] = r.setting.estimator;
    const bool radiosity = r.setting.estimator == "radiosity" || r.setting.estimator == "radiosity-fg";
    const bool photon_mapping = r.setting.estimator != "path" && !radiosity;
    if (r.setting.estimator == "path") j["spp"] = r.setting.parameter;
    if (radiosity) {
      j["max_edge"] = r.setting.parameter;
      j["directions"] = r.setting.directions;
    }
    if (r.setting.estimator == "radiosity-fg") j["final_gather"] = r.setting.rays;
    if (photon_mapping) j["photons"] = r.setting.photons;
    if (r.setting.estimator == "pd") j["smoothing"] = r.setting.parameter;
    if (r.setting.estimator == "knn") j["k"] = r.setting.parameter;
    if (r.setting.estimator == "radius") j["radius"] = r.setting.parameter;
    if (r.setting.estimator == "fg") j["final_gather"] = r.setting.parameter;
    j["passes"] = r.setting.passes;
    if (photon_mapping) j["progressive"] = r.setting.progressive;
    if (r.setting.progressive == "shrink") j["alpha"] = r.setting.alpha;
    j["device_ms"] = {{"median", r.device_ms.median}, {"min", r.device_ms.min}, {"max", r.device_ms.max}};
    j["wall_ms"] = {{"median", r.wall_ms.median}, {"min", r.wall_ms.min}, {"max", r.wall_ms.max}};
    j["relmae"] = r.errors.relmae;
    j["relmse"] = r.errors.relmse;
    j["flip"] = r.errors.flip;
    j["mean_bias"] = r.errors.mean;
    j["indirect_bias"] = r.errors.indirect;
    j["pareto"] = r.front;
    list.push_back(j);
  }
  return list;
}

std::string tradeoff_svg(const std::vector<TradeoffRow>& rows, const std::string& metric, const std::string& title) {
  std::vector<PlotPoint> points;
  for (const TradeoffRow& r : rows)
    points.push_back({r.device_ms.median, r.error(metric), r.setting.label(), r.setting.series(), r.front});
  return svg_scatter_plot(points, {title, "device time per frame, ms", tradeoff_metric_title(metric)});
}

}  // namespace pm::cli

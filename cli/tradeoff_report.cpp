// Errors, Pareto marking and the table / JSON / SVG of `pmrender tradeoff` (tradeoff_report.h).
#include "cli/tradeoff_report.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "render/errors.h"
#include "render/image_metrics.h"
#include "render/tradeoff/pareto.h"
#include "render/tradeoff/svg_plot.h"

namespace pm::cli {

namespace {

double sum(const std::vector<float>& v) {
  double s = 0;
  for (float x : v) s += x;
  return s;
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
  double relmae = 0;
  for (float v : c.mean_map) relmae += v;
  e.relmae = c.mean_map.empty() ? 0 : relmae / double(c.mean_map.size());
  e.relmse = c.relmse;
  e.flip = c.flip;
  const double ref_sum = sum(ref), test_sum = sum(img);
  e.mean = ref_sum > 0 ? test_sum / ref_sum - 1.0 : 0.0;
  const double test_direct = sum(test.find("direct")->rgb);
  const ImageLayer* ref_direct_layer = reference.find("direct");
  const double ref_direct = ref_direct_layer ? sum(ref_direct_layer->rgb) : test_direct;
  const double test_ratio = test_direct > 0 ? (test_sum - test_direct) / test_direct : 0.0;
  const double ref_ratio = ref_direct > 0 ? (ref_sum - ref_direct) / ref_direct : 0.0;
  e.indirect = ref_ratio > 0 ? test_ratio / ref_ratio - 1.0 : 0.0;
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

nlohmann::ordered_json tradeoff_json_rows(const std::vector<TradeoffRow>& rows) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const TradeoffRow& r : rows) {
    nlohmann::ordered_json j;
    j["label"] = r.setting.label();
    j["estimator"] = r.setting.estimator;
    if (r.setting.estimator == "path") j["spp"] = r.setting.parameter;
    else j["photons"] = r.setting.photons;
    if (r.setting.estimator == "pd") j["smoothing"] = r.setting.parameter;
    if (r.setting.estimator == "knn") j["k"] = r.setting.parameter;
    if (r.setting.estimator == "radius") j["radius"] = r.setting.parameter;
    j["passes"] = r.setting.passes;
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

// What `pmrender tradeoff` measured and how it reports it: one row per setting (device and wall
// time medians, every error against the reference), the Pareto front on the chosen error, and the
// table, JSON and SVG plot written from them.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/bench_measure.h"
#include "cli/tradeoff_grid.h"
#include "render/image.h"

namespace pm::cli {

// Errors of a render against the reference, combined layers.
struct TradeoffErrors {
  double relmae = 0;  // sum |test - ref| / sum ref, all pixels and channels
  double relmse = 0;  // mean (test - ref)^2 / (ref^2 + 0.01)
  double flip = 0;    // mean HDR-FLIP
  double mean = 0;      // mean(test) / mean(ref) - 1 (render/image_metrics.h, light_bias)
  double indirect = 0;  // the indirect light's bias with the direct light matched (light_bias)
};

// Errors of test against reference (same size; InputError otherwise).
TradeoffErrors tradeoff_errors(const FrameImage& reference, const FrameImage& test);

struct TradeoffRow {
  TradeoffSetting setting;
  Spread device_ms, wall_ms;
  TradeoffErrors errors;
  bool front = false;
  double error(const std::string& metric) const;  // relmae, relmse or flip
};

// Marks each row's front flag on (device median, metric).
void mark_pareto_front(std::vector<TradeoffRow>& rows, const std::string& metric);

std::string tradeoff_table(const std::vector<TradeoffRow>& rows, const std::string& metric);

// Per series (estimator, one pass or several): the fastest setting reaching each error level and
// the smallest error reached (where its bias, or the grid, stops it). Levels at or below
// `floor` (twice the reference's own noise; 0: unknown) cannot be told from that noise and are
// reported as such. A last line names, per level, the series of the fastest setting of all.
std::string time_to_error_table(const std::vector<TradeoffRow>& rows, const std::string& metric,
                                const std::vector<double>& levels, double floor);
nlohmann::ordered_json time_to_error_json(const std::vector<TradeoffRow>& rows, const std::string& metric,
                                          const std::vector<double>& levels, double floor);
// Per error level, the fastest setting of any method that reaches it (null where none does).
nlohmann::ordered_json fastest_per_level_json(const std::vector<TradeoffRow>& rows, const std::string& metric,
                                              const std::vector<double>& levels);
nlohmann::ordered_json tradeoff_json_rows(const std::vector<TradeoffRow>& rows);
std::string tradeoff_svg(const std::vector<TradeoffRow>& rows, const std::string& metric, const std::string& title);

// Metric names as the option takes them, and their long names for plots.
bool is_tradeoff_metric(const std::string& metric);
std::string tradeoff_metric_title(const std::string& metric);

}  // namespace pm::cli

// Pareto front and budget/target picks over (time, error) points.
#include "render/tradeoff/pareto.h"

#include <cmath>

namespace pm {

namespace {

bool finite(const TradeoffPoint& p) { return std::isfinite(p.time_ms) && std::isfinite(p.error); }

// a dominates b: no worse in both, better in one.
bool dominates(const TradeoffPoint& a, const TradeoffPoint& b) {
  return a.time_ms <= b.time_ms && a.error <= b.error && (a.time_ms < b.time_ms || a.error < b.error);
}

}  // namespace

std::vector<bool> pareto_front(const std::vector<TradeoffPoint>& points) {
  std::vector<bool> front(points.size(), false);
  for (size_t i = 0; i < points.size(); ++i) {
    if (!finite(points[i])) continue;
    bool beaten = false;
    for (size_t j = 0; j < points.size() && !beaten; ++j) beaten = j != i && finite(points[j]) && dominates(points[j], points[i]);
    front[i] = !beaten;
  }
  return front;
}

int best_within_time(const std::vector<TradeoffPoint>& points, double budget_ms) {
  int best = -1;
  for (size_t i = 0; i < points.size(); ++i) {
    const TradeoffPoint& p = points[i];
    if (!finite(p) || p.time_ms > budget_ms) continue;
    if (best < 0 || p.error < points[best].error ||
        (p.error == points[best].error && p.time_ms < points[best].time_ms))
      best = int(i);
  }
  return best;
}

int fastest_within_error(const std::vector<TradeoffPoint>& points, double target) {
  int best = -1;
  for (size_t i = 0; i < points.size(); ++i) {
    const TradeoffPoint& p = points[i];
    if (!finite(p) || p.error > target) continue;
    if (best < 0 || p.time_ms < points[best].time_ms ||
        (p.time_ms == points[best].time_ms && p.error < points[best].error))
      best = int(i);
  }
  return best;
}

}  // namespace pm

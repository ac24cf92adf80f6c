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

// The index of the best finite point that accept() admits, better(a, b) saying a beats b; -1 if none.
template <typename Accept, typename Better>
int best_index(const std::vector<TradeoffPoint>& points, Accept accept, Better better) {
  int best = -1;
  for (size_t i = 0; i < points.size(); ++i)
    if (finite(points[i]) && accept(points[i]) && (best < 0 || better(points[i], points[size_t(best)]))) best = int(i);
  return best;
}

int best_within_time(const std::vector<TradeoffPoint>& points, double budget_ms) {
  return best_index(
      points, [&](const TradeoffPoint& p) { return p.time_ms <= budget_ms; },
      [](const TradeoffPoint& a, const TradeoffPoint& b) {
        return a.error < b.error || (a.error == b.error && a.time_ms < b.time_ms);
      });
}

int fastest_within_error(const std::vector<TradeoffPoint>& points, double target) {
  return best_index(
      points, [&](const TradeoffPoint& p) { return p.error <= target; },
      [](const TradeoffPoint& a, const TradeoffPoint& b) {
        return a.time_ms < b.time_ms || (a.time_ms == b.time_ms && a.error < b.error);
      });
}

}  // namespace pm

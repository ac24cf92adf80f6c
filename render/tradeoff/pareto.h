// The speed/accuracy trade of a set of measured settings (`pmrender tradeoff`): which settings no
// other beats (the Pareto front of time against error), and the best setting for a time budget
// or an error target. Pure functions of the measured numbers.
#pragma once

#include <vector>

namespace pm {

struct TradeoffPoint {
  double time_ms = 0;  // cost: lower is better
  double error = 0;    // lower is better
};

// front[i]: no other point is at least as fast and at least as accurate while strictly better
// in one of the two. Equal points are all on the front; non-finite points never are.
std::vector<bool> pareto_front(const std::vector<TradeoffPoint>& points);

// The most accurate point within time_ms <= budget (ties: the faster, then the first), or -1.
int best_within_time(const std::vector<TradeoffPoint>& points, double budget_ms);
// The fastest point with error <= target (ties: the more accurate, then the first), or -1.
int fastest_within_error(const std::vector<TradeoffPoint>& points, double target);

}  // namespace pm

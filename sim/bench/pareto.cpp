#include "sim/bench/pareto.h"

#include <algorithm>
#include <cmath>

namespace ffsim::bench {

std::vector<std::size_t> pareto_front(const std::vector<std::pair<double, double>>& p) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (!std::isnan(p[i].first) && !std::isnan(p[i].second)) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return p[a] != p[b] ? p[a] < p[b] : a < b;
  });
  // Sweep by increasing x (then y): a point is on the front when its y is below
  // every y seen at a strictly smaller x, or it ties the best point exactly.
  std::vector<std::size_t> front;
  bool have = false;
  std::pair<double, double> best{};  // the last front point
  for (std::size_t i : order) {
    if (!have || p[i].second < best.second || p[i] == best) {
      front.push_back(i);
      best = p[i];
      have = true;
    }
  }
  return front;
}

}  // namespace ffsim::bench

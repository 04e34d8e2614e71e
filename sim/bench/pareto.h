// The Pareto front of points where both coordinates are costs (smaller is better):
// run time against error in `ffsim bench`, throughput against bandwidth elsewhere.
#pragma once
#include <cstddef>
#include <utility>
#include <vector>

namespace ffsim::bench {

// Indices of the points no other point dominates (another point is <= in both
// coordinates and < in at least one), sorted by x, then y. Exact duplicates are
// all kept. Points with a NaN coordinate are never on the front.
std::vector<std::size_t> pareto_front(const std::vector<std::pair<double, double>>& points);

}  // namespace ffsim::bench

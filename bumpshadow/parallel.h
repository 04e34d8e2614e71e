// Row-parallel loops with std::thread. Each row's result depends only on the
// inputs, never on which thread ran it or in what order, so every output is
// identical for any thread count (tested).
#pragma once
#include <functional>

namespace ffsim::bumpshadow {

// Progress callback: (rows done, rows total); called from worker threads under a
// lock, in increasing order of `done`.
using Progress = std::function<void(int done, int total)>;

// threads <= 0: std::thread::hardware_concurrency() (at least 1). Runs
// body(row) for row in [0, rows); the first exception thrown is rethrown.
void parallel_rows(int rows, int threads, const std::function<void(int row)>& body, const Progress& progress = {});

}  // namespace ffsim::bumpshadow

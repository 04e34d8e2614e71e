// `ffsim bench --perf` (issue 10): per-stage throughput in million fragments per
// second on one core, whole-trace frames per second over sizes and threads, each
// beside the memory-bandwidth floor of the pass; a table, CSV and a plot under
// docs/results/.
#pragma once
#include <iosfwd>
#include <string>
#include <vector>

namespace ffsim::bench {

// args: the arguments after `ffsim bench --perf`. Returns the exit code.
int run_perf(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

std::string perf_usage();

// Amdahl's bound on the speed-up of `threads` threads: a frame that takes
// `one_thread_s` on one thread, of which `serial_s` (measured on `threads`
// threads: the calling thread's time outside the pool's runs) cannot be split,
// and the rest splits perfectly: one_thread_s / (serial_s + (one_thread_s -
// serial_s) / threads). A serial part longer than the one-thread frame gives
// one_thread_s / serial_s. 0 for a non-positive time or thread count.
double amdahl_bound(double one_thread_s, double serial_s, int threads);

}  // namespace ffsim::bench

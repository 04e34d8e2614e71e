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

}  // namespace ffsim::bench

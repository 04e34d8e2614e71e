// `ffsim bench` (issue 9): run time against error over the paper's variants,
// precision profiles, texture filters, frame sizes and a sweep of light
// directions; a table on stdout, CSV under docs/results/, and a Pareto plot.
#pragma once
#include <iosfwd>
#include <string>
#include <vector>

namespace ffsim::bench {

// args: the arguments after `ffsim bench` (without --perf). Returns the exit code
// (0 success, 1 a run failed, 2 usage error). Never fails on a measured number.
int run_accuracy(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

// The text of `ffsim bench --help` for this mode.
std::string accuracy_usage();

}  // namespace ffsim::bench

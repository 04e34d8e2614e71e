// `ffsim bench`: run time against error (issue 9, sim/bench/accuracy.cpp) and,
// with --perf, throughput (issue 10, sim/bench/perf.cpp).
#include <algorithm>
#include <ostream>

#include "sim/bench/accuracy.h"
#include "sim/bench/perf.h"
#include "sim/cli/cli.h"

namespace ffsim::cli {

Subcommand bench_command() {
  Subcommand s;
  s.name = "bench";
  s.summary = "run time against error (default) or per-stage throughput (--perf)";
  s.usage = bench::accuracy_usage() + "\n" + bench::perf_usage();
  s.run = [](const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    const bool perf = std::find(args.begin(), args.end(), "--perf") != args.end();
    if (wants_help(args)) {
      out << (perf ? bench::perf_usage() : bench::accuracy_usage() + "\n" + bench::perf_usage());
      return 0;
    }
    if (perf) {
      std::vector<std::string> rest;
      for (const auto& a : args)
        if (a != "--perf") rest.push_back(a);
      return bench::run_perf(rest, out, err);
    }
    return bench::run_accuracy(args, out, err);
  };
  return s;
}

}  // namespace ffsim::cli

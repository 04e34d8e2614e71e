#include "sim/bench/perf.h"

#include <ostream>

namespace ffsim::bench {

std::string perf_usage() { return "usage: ffsim bench --perf ...  (throughput; not built yet)\n"; }

int run_perf(const std::vector<std::string>&, std::ostream&, std::ostream& err) {
  err << "ffsim bench --perf: not built yet (issue #10)\n";
  return 2;
}

}  // namespace ffsim::bench

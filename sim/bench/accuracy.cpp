#include "sim/bench/accuracy.h"

#include <ostream>

namespace ffsim::bench {

std::string accuracy_usage() { return "usage: ffsim bench [--quick] ...  (run time against error; not built yet)\n"; }

int run_accuracy(const std::vector<std::string>&, std::ostream&, std::ostream& err) {
  err << "ffsim bench: run time against error is not built yet (issue #9)\n";
  return 2;
}

}  // namespace ffsim::bench

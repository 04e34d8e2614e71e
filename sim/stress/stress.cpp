#include "sim/stress/stress.h"

#include <ostream>

namespace ffsim::stress {

std::string usage() { return "usage: ffsim stress [--seconds S] [--seed N]  (not built yet)\n"; }

int run(const std::vector<std::string>&, std::ostream&, std::ostream& err) {
  err << "ffsim stress: not built yet (issue #9)\n";
  return 2;
}

}  // namespace ffsim::stress

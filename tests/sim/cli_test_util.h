// Runs the ffsim command line in-process, as main() does (tests of the subcommands).
#pragma once
#include <sstream>
#include <string>
#include <vector>

#include "sim/cli/cli.h"

namespace ffsim::test {

struct Run {
  int code;
  std::string out, err;
};

inline Run run(std::vector<std::string> args) {
  std::ostringstream out, err;
  const int code = cli::run(args, out, err);
  return {code, out.str(), err.str()};
}

}  // namespace ffsim::test

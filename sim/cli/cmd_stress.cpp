// `ffsim stress`: seeded randomised stress cases (issue 9, sim/stress/stress.cpp).
#include <ostream>

#include "sim/cli/cli.h"
#include "sim/stress/stress.h"

namespace ffsim::cli {

Subcommand stress_command() {
  Subcommand s;
  s.name = "stress";
  s.summary = "seeded randomised stress cases; reports the worst cases and their seeds";
  s.usage = stress::usage();
  s.run = [](const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    if (wants_help(args)) {
      out << stress::usage();
      return 0;
    }
    return stress::run(args, out, err);
  };
  return s;
}

}  // namespace ffsim::cli

// `ffsim stress` (issue 9): seeded randomised cases at and beyond the paper's
// assumptions, run for a given time; reports the worst cases found and the seeds
// that reproduce them.
#pragma once
#include <iosfwd>
#include <string>
#include <vector>

namespace ffsim::stress {

// args: the arguments after `ffsim stress`. Returns the exit code (0: no invariant
// violated, 1: a violation was found, 2: usage error).
int run(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

std::string usage();

}  // namespace ffsim::stress

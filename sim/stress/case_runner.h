// One randomised stress case: its inputs are a pure function of (kind, seed), so
// `ffsim stress --case KIND --repro SEED` replays it exactly.
#pragma once
#include <cstdint>
#include <iosfwd>
#include <string>

#include "sim/stress/report.h"

namespace ffsim::stress {

struct CaseOptions {
  std::string traces_dir = "traces";  // for trace cases
};

// verbose: when non-null, every input and every statistic is printed there.
CaseOutcome run_case(CaseKind kind, std::uint64_t seed, const CaseOptions& o, std::ostream* verbose);

}  // namespace ffsim::stress

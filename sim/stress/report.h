// What one stress case found, and the worst cases of a whole run per metric
// (docs/stress.md shows the format).
#pragma once
#include <cstdint>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "sim/stress/invariants.h"

namespace ffsim::stress {

enum class CaseKind { Ellipse, Light, Field, Trace, Count };
const char* case_kind_name(CaseKind k);
bool parse_case_kind(const std::string& s, CaseKind& k);

struct Metric {
  std::string name;   // e.g. "combiner geforce256 err/bound"
  double value = 0;   // larger is worse
  std::string what;   // the input that produced it
};

struct CaseOutcome {
  CaseKind kind = CaseKind::Ellipse;
  std::uint64_t seed = 0;
  std::string summary;                  // the inputs, one line
  std::vector<std::string> violations;  // hard invariant violations
  std::vector<Metric> metrics;
  RangeCounts ranges;
};

// Worst value per metric over a run, with the seed that produced it.
class Report {
 public:
  void add(const CaseOutcome& c);
  bool failed() const { return !violations_.empty(); }
  // The report (no timing: identical for identical seeds and case counts).
  void print(std::ostream& out) const;

 private:
  struct Worst {
    double value = 0;
    CaseKind kind = CaseKind::Ellipse;
    std::uint64_t seed = 0;
    std::string what;
  };
  std::map<std::string, Worst> worst_;
  std::map<CaseKind, long long> counts_;
  RangeCounts ranges_;
  struct Violation {
    CaseKind kind;
    std::uint64_t seed;
    std::string text;
  };
  std::vector<Violation> violations_;
};

std::string repro_command(CaseKind k, std::uint64_t seed);
std::string hex_seed(std::uint64_t seed);

}  // namespace ffsim::stress

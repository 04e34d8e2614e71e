#include "sim/stress/report.h"

#include <cstdio>
#include <ostream>

namespace ffsim::stress {

const char* case_kind_name(CaseKind k) {
  switch (k) {
    case CaseKind::Ellipse: return "ellipse";
    case CaseKind::Light: return "light";
    case CaseKind::Field: return "field";
    case CaseKind::Trace: return "trace";
    case CaseKind::Count: break;
  }
  return "?";
}

bool parse_case_kind(const std::string& s, CaseKind& k) {
  for (int i = 0; i < static_cast<int>(CaseKind::Count); ++i)
    if (s == case_kind_name(static_cast<CaseKind>(i))) {
      k = static_cast<CaseKind>(i);
      return true;
    }
  return false;
}

std::string hex_seed(std::uint64_t seed) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "0x%016llx", static_cast<unsigned long long>(seed));
  return buf;
}

std::string repro_command(CaseKind k, std::uint64_t seed) {
  return std::string("ffsim stress --case ") + case_kind_name(k) + " --repro " + hex_seed(seed);
}

void Report::add(const CaseOutcome& c) {
  ++counts_[c.kind];
  ranges_.add(c.ranges);
  for (const std::string& v : c.violations) violations_.push_back({c.kind, c.seed, v});
  for (const Metric& m : c.metrics) {
    auto it = worst_.find(m.name);
    if (it == worst_.end() || m.value > it->second.value) worst_[m.name] = {m.value, c.kind, c.seed, m.what};
  }
}

void Report::print(std::ostream& out) const {
  long long total = 0;
  for (const auto& [k, n] : counts_) total += n;
  out << "cases: " << total;
  for (const auto& [k, n] : counts_) out << "  " << case_kind_name(k) << " " << n;
  out << "\n\nrange violations (the paper's assumptions, counted before each clamp; docs/numerics.md §12.4):\n"
      << "  per texel: " << ranges_.texels << " texels, |C| > 1: " << ranges_.center
      << ", T^r component outside [-1,1]: " << ranges_.tr_component << ", T^n component outside [-1,1]: "
      << ranges_.tn_component << ",\n             rx > sqrt 2 (T3^r alpha > 1): " << ranges_.t3r_alpha
      << ", rx > 1 (T1^n alpha > 1): " << ranges_.t1n_alpha << "\n"
      << "  per (texel, light): " << ranges_.cases << " cases, dot product outside [-1,1]: " << ranges_.dot
      << ", sum outside [0,1]: " << ranges_.sum << ", A' outside [0,1] (index clamp): " << ranges_.lookup_index
      << ", lookup > 1 (entry clamp): " << ranges_.lookup_entry << "\n\n";
  out << "worst case per metric (larger is worse; err/bound <= 1 is required where a bound applies):\n";
  for (const auto& [name, w] : worst_) {
    char v[64];
    std::snprintf(v, sizeof v, "%.6g", w.value);
    out << "  " << name << ": " << v << "  seed " << hex_seed(w.seed) << "  (" << repro_command(w.kind, w.seed) << ")\n";
    if (!w.what.empty()) out << "      " << w.what << "\n";
  }
  out << "\nhard invariant violations: " << violations_.size() << "\n";
  for (const Violation& v : violations_)
    out << "  " << case_kind_name(v.kind) << " seed " << hex_seed(v.seed) << ": " << v.text << "\n      "
        << repro_command(v.kind, v.seed) << "\n";
}

}  // namespace ffsim::stress

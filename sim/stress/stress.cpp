#include "sim/stress/stress.h"

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ostream>

#include "sim/stress/case_runner.h"
#include "sim/stress/cases.h"
#include "sim/stress/report.h"

namespace ffsim::stress {

std::string usage() {
  return "usage: ffsim stress [--seconds S | --cases N] [--seed N] [--case ellipse|light|field|trace]\n"
         "                    [--repro SEED] [--traces DIR] [--verbose]\n"
         "\n"
         "Runs seeded randomised cases at and beyond the paper's assumptions (docs/stress.md):\n"
         "  ellipse  ellipses with |C| -> 1 and > 1, rx -> 0, rx > sqrt 2, rx = ry, huge eccentricity,\n"
         "           through the encodings, the combiner path and the lookup-table path\n"
         "  light    lights over the upper hemisphere, grazing (elevation 0..1 degree, exactly 0),\n"
         "           lx^2 + ly^2 -> 1 (lz = sqrt of a tiny negative: NaN)\n"
         "  field    flat, spike, cliff and noise height fields, scales 1e-6..1e6, sizes 1..17\n"
         "  trace    the paper's traces at 8^2 or 16^2 under a random profile and light, threads 1/2/3\n"
         "Checks: no NaN/Inf, every register and value in range, hardware within the bound of\n"
         "docs/numerics.md §12 of `ideal` where no clamp acts, identical results across threads.\n"
         "Reports the worst case per metric with the command that replays it.\n"
         "\n"
         "  --seconds S     time budget (default 10); cases are started until it is spent\n"
         "  --cases N       run exactly N cases instead (reproducible output)\n"
         "  --seed N        master seed (default 1; decimal or 0x hex); case i has its own seed\n"
         "  --case KIND     only this kind of case (default: the four in turn)\n"
         "  --repro SEED    replay the one case with this seed verbosely (with --case; without it,\n"
         "                  the seed is replayed as every kind)\n"
         "  --traces DIR    the traces directory (default traces)\n"
         "  --verbose       one line per case\n"
         "Exit code: 0 no hard invariant violated, 1 a violation, 2 usage error.\n";
}

namespace {

constexpr const char* kShortUsage =
    "usage: ffsim stress [--seconds S | --cases N] [--seed N] [--case KIND] [--repro SEED] [--traces DIR] [--verbose]";

bool parse_u64(const std::string& s, std::uint64_t& v) {
  if (s.empty() || s[0] == '-') return false;
  char* end = nullptr;
  errno = 0;
  v = std::strtoull(s.c_str(), &end, 0);
  return errno == 0 && end && *end == 0;
}

bool parse_seconds(const std::string& s, double& v) {
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return !s.empty() && end && *end == 0 && v >= 0 && v <= 1e7;
}

int usage_error(std::ostream& err, const std::string& what) {
  err << "ffsim stress: " << what << " (" << kShortUsage << ")\n";
  return 2;
}

}  // namespace

int run(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  double seconds = 10;
  std::uint64_t master = 1, repro = 0, cases = 0;
  bool have_cases = false, have_seconds = false, have_repro = false, have_kind = false, verbose = false;
  CaseKind only = CaseKind::Ellipse;
  CaseOptions co;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&](std::string& v) {
      if (i + 1 >= args.size()) return false;
      v = args[++i];
      return true;
    };
    std::string v;
    if (a == "--help" || a == "-h") {
      out << usage();
      return 0;
    } else if (a == "--seconds") {
      if (!value(v) || !parse_seconds(v, seconds)) return usage_error(err, "--seconds needs a number of seconds >= 0");
      have_seconds = true;
    } else if (a == "--cases") {
      if (!value(v) || !parse_u64(v, cases)) return usage_error(err, "--cases needs a count");
      have_cases = true;
    } else if (a == "--seed") {
      if (!value(v) || !parse_u64(v, master)) return usage_error(err, "--seed needs an unsigned integer");
    } else if (a == "--repro") {
      if (!value(v) || !parse_u64(v, repro)) return usage_error(err, "--repro needs a case seed");
      have_repro = true;
    } else if (a == "--case") {
      if (!value(v) || !parse_case_kind(v, only)) return usage_error(err, "--case needs ellipse, light, field or trace");
      have_kind = true;
    } else if (a == "--traces") {
      if (!value(v)) return usage_error(err, "--traces needs a directory");
      co.traces_dir = v;
    } else if (a == "--verbose") {
      verbose = true;
    } else {
      return usage_error(err, std::string("unknown argument '") + a + "'");
    }
  }
  if (have_cases && have_seconds) return usage_error(err, "--seconds and --cases exclude each other");

  if (have_repro) {
    Report report;
    for (int k = 0; k < static_cast<int>(CaseKind::Count); ++k) {
      const auto kind = static_cast<CaseKind>(k);
      if (have_kind && kind != only) continue;
      out << "case " << case_kind_name(kind) << " seed " << hex_seed(repro) << ": ";
      report.add(run_case(kind, repro, co, &out));
    }
    out << "\n";
    report.print(out);
    return report.failed() ? 1 : 0;
  }

  out << "ffsim stress: master seed " << master << ", "
      << (have_cases ? std::to_string(cases) + " cases" : std::string("budget ") + std::to_string(seconds).substr(0, 6) + " s")
      << ", kinds " << (have_kind ? case_kind_name(only) : "ellipse, light, field, trace") << "\n";
  Report report;
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  for (std::uint64_t i = 0;; ++i) {
    if (have_cases ? i >= cases : elapsed() >= seconds) break;
    const CaseKind kind = have_kind ? only : static_cast<CaseKind>(i % static_cast<std::uint64_t>(CaseKind::Count));
    const std::uint64_t seed = case_seed(master, i);
    const CaseOutcome c = run_case(kind, seed, co, nullptr);
    if (verbose)
      out << "case " << i << " " << case_kind_name(kind) << " seed " << hex_seed(seed) << ": " << c.summary
          << (c.violations.empty() ? "" : "  VIOLATED") << "\n";
    report.add(c);
  }
  out << "\n";
  report.print(out);
  char buf[64];
  std::snprintf(buf, sizeof buf, "elapsed: %.1f s\n", elapsed());
  out << buf;
  return report.failed() ? 1 : 0;
}

}  // namespace ffsim::stress

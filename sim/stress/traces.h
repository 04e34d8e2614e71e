// The paper's traces under stress: thread-count and repeat determinism, finite
// and in-range float framebuffers, and the error of a trace under a profile
// against the same trace under `ideal` and against the exact reference.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "sim/trace/executor.h"

namespace ffsim::stress {

using Sets = std::vector<std::pair<std::string, std::string>>;

struct TraceRun {
  bool ok = false;
  std::string error;
  trace::RunResult r;
};

// traces_dir/stem.trace with the sets, profile ("" = the trace's own), threads;
// images kept in memory, nothing written. Trace errors become ok = false.
TraceRun run_paper_trace(const std::string& traces_dir, const std::string& stem, const Sets& sets,
                         const std::string& profile, int threads);

// Every `hash` line and final hash of a run, one string.
std::string all_hashes(const trace::RunResult& r);

// NaN/Inf or values outside [0, 1] in every kept image of a run: the count and
// the first one described in `first`.
long long bad_image_values(const trace::RunResult& r, std::string* first);

// Error of one (trace, profile) run of an antialiased variant, over covered pixels:
// RMSE of alpha.png (the shadow test d, clamped) against the same trace under
// `ideal`, and the lit (alpha > 0) disagreement with the exact reference.
struct SweepPoint {
  std::string trace, profile;
  bool ok = false;
  std::string error;
  double rmse_vs_ideal = 0;          // in [0, 1] units
  double max_abs_vs_ideal = 0;       // worst pixel
  long long pixels = 0;
  long long differ_vs_ideal = 0;     // pixels whose lit verdict differs from ideal's
  long long disagree_vs_reference = 0;
  long long ideal_disagree_vs_reference = 0;  // the same trace under `ideal`
  std::vector<double> alpha;   // alpha.png values, row-major
  std::vector<bool> covered;   // pixels the scene covers
};
// Runs kautz-reference, `stem` under `ideal` and `stem` under each profile.
std::vector<SweepPoint> error_sweep(const std::string& traces_dir, const std::string& stem, const Sets& sets,
                                    const std::vector<std::string>& profiles);

}  // namespace ffsim::stress

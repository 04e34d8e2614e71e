#include "sim/stress/traces.h"

#include <cmath>
#include <filesystem>
#include <sstream>

#include "sim/paper.h"
#include "sim/trace/trace.h"

namespace ffsim::stress {

TraceRun run_paper_trace(const std::string& traces_dir, const std::string& stem, const Sets& sets,
                         const std::string& profile, int threads) {
  TraceRun run;
  try {
    trace::LoadOptions lo;
    lo.sets = sets;
    lo.profile = profile;
    const trace::Program prog =
        trace::load_trace_file((std::filesystem::path(traces_dir) / (stem + ".trace")).string(), lo);
    trace::RunOptions ro;
    ro.keep_images = true;
    ro.threads = threads;
    std::ostringstream sink;
    run.r = trace::run_program(prog, ro, sink);
    run.ok = run.r.ok && run.r.gl_errors.empty() && run.r.expect_failures.empty();
    if (!run.r.ok) run.error = run.r.fatal;
    else if (!run.r.gl_errors.empty()) run.error = run.r.gl_errors.front();
    else if (!run.r.expect_failures.empty()) run.error = run.r.expect_failures.front();
  } catch (const trace::TraceError& e) {
    run.error = e.where().str() + ": " + e.what();
  } catch (const std::exception& e) {
    run.error = e.what();
  }
  return run;
}

std::string all_hashes(const trace::RunResult& r) {
  std::string s;
  for (const auto& h : r.hashes) s.append(h.hex).append(" ");
  for (const auto& [b, h] : r.final_hashes) s.append(b).append("=").append(h).append(" ");
  return s;
}

long long bad_image_values(const trace::RunResult& r, std::string* first) {
  long long bad = 0;
  for (const auto& [name, im] : r.images)
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x)
        for (int c = 0; c < im.channels; ++c) {
          const double v = im.value(x, y, c);
          if (std::isfinite(v) && v >= 0 && v <= 1) continue;
          if (!bad && first) *first = name + " pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") channel " +
                                      std::to_string(c) + " = " + std::to_string(v);
          ++bad;
        }
  return bad;
}

namespace {
const Image* image_of(const trace::RunResult& r, const std::string& name) {
  auto it = r.images.find(name);
  return it == r.images.end() ? nullptr : &it->second;
}
std::vector<bool> above(const std::vector<double>& v, double t) {
  std::vector<bool> b(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) b[i] = v[i] > t;
  return b;
}
}  // namespace

std::vector<SweepPoint> error_sweep(const std::string& traces_dir, const std::string& stem, const Sets& sets,
                                    const std::vector<std::string>& profiles) {
  std::vector<SweepPoint> out;
  const TraceRun ref = run_paper_trace(traces_dir, "kautz-reference", sets, "", 1);
  const TraceRun ideal = run_paper_trace(traces_dir, stem, sets, "ideal", 1);
  for (const std::string& p : profiles) {
    SweepPoint pt;
    pt.trace = stem;
    pt.profile = p;
    const TraceRun run = run_paper_trace(traces_dir, stem, sets, p, 1);
    const Image *cov = ref.ok ? image_of(ref.r, "coverage.png") : nullptr, *rl = ref.ok ? image_of(ref.r, "reference.png") : nullptr;
    const Image *ai = ideal.ok ? image_of(ideal.r, "alpha.png") : nullptr, *ah = run.ok ? image_of(run.r, "alpha.png") : nullptr;
    if (!cov || !rl || !ai || !ah) {
      pt.error = !ref.ok ? ref.error : !ideal.ok ? ideal.error : !run.ok ? run.error : "missing alpha.png/coverage.png";
      out.push_back(pt);
      continue;
    }
    pt.ok = true;
    const std::vector<bool> covered = above(paper::channel_values(*cov), 0.5), ref_lit = above(paper::channel_values(*rl), 0.5);
    const std::vector<double> a = paper::channel_values(*ah), b = paper::channel_values(*ai);
    pt.rmse_vs_ideal = paper::rmse(a, b, covered);
    const std::vector<bool> lit = above(a, 0), ideal_lit = above(b, 0);
    for (std::size_t i = 0; i < covered.size() && i < a.size() && i < b.size(); ++i) {
      if (!covered[i]) continue;
      ++pt.pixels;
      pt.max_abs_vs_ideal = std::max(pt.max_abs_vs_ideal, std::fabs(a[i] - b[i]));
      pt.differ_vs_ideal += lit[i] != ideal_lit[i];
    }
    const paper::ShadowStats st = paper::compare_masks(lit, ref_lit, covered);
    pt.disagree_vs_reference = st.false_lit + st.false_shadow;
    const paper::ShadowStats si = paper::compare_masks(ideal_lit, ref_lit, covered);
    pt.ideal_disagree_vs_reference = si.false_lit + si.false_shadow;
    pt.alpha = a;
    pt.covered = covered;
    out.push_back(pt);
  }
  return out;
}

}  // namespace ffsim::stress

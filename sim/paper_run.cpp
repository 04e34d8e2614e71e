#include "sim/paper_run.h"

#include <chrono>
#include <sstream>

namespace ffsim::paper {

Run replay(const trace::Program& prog, const std::string& out_dir, int threads, bool keep_images) {
  Run run;
  const auto t0 = std::chrono::steady_clock::now();
  trace::RunOptions ro;
  ro.out_dir = out_dir;
  ro.keep_images = keep_images;
  ro.threads = threads;
  std::ostringstream sink;
  run.r = trace::run_program(prog, ro, sink);
  run.run_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  run.ok = run.r.ok && run.r.expect_failures.empty() && run.r.gl_errors.empty();
  if (!run.r.ok) run.error = run.r.fatal;
  else if (!run.r.gl_errors.empty()) run.error = run.r.gl_errors.front();
  else if (!run.r.expect_failures.empty()) run.error = run.r.expect_failures.front();
  return run;
}

Run run_trace(const std::string& path, const std::vector<std::pair<std::string, std::string>>& sets,
              const std::string& out_dir, int threads, const std::string& profile) {
  Run run;
  const auto t0 = std::chrono::steady_clock::now();
  try {
    trace::LoadOptions lo;
    lo.sets = sets;
    lo.profile = profile;
    const trace::Program prog = trace::load_trace_file(path, lo);
    const double load = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    run = replay(prog, out_dir, threads);
    run.load_seconds = load;
  } catch (const trace::TraceError& e) {
    run.error = e.where().str() + ": " + e.what();
  } catch (const std::exception& e) {
    run.error = e.what();
  }
  return run;
}

const Image* image_of(const Run& r, const std::string& name) {
  auto it = r.r.images.find(name);
  return it == r.r.images.end() ? nullptr : &it->second;
}

std::vector<bool> threshold(const std::vector<double>& v, double t) {
  std::vector<bool> b(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) b[i] = v[i] > t;
  return b;
}

}  // namespace ffsim::paper

// Running one trace of the paper and reading its dumps: shared by `ffsim
// paper-report` (sim/paper.cpp) and `ffsim bench` (sim/bench/accuracy.cpp).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "sim/image_io.h"
#include "sim/trace/executor.h"
#include "sim/trace/trace.h"

namespace ffsim::paper {

struct Run {
  bool ok = false;    // ran to the end without a fatal error, GL error or failed expect
  std::string error;  // the first of those, "file:line:column: message"
  double load_seconds = 0, run_seconds = 0;
  trace::RunResult r;
};

// Loads `path` with the --set values (and the profile, when not empty) and replays
// it once, keeping every dump's image; dumps are written under out_dir when it is
// not empty. Never throws: load errors end up in Run::error.
Run run_trace(const std::string& path, const std::vector<std::pair<std::string, std::string>>& sets,
              const std::string& out_dir, int threads, const std::string& profile = "");

// Replays a loaded program once; Run::load_seconds stays 0. keep_images: keep the
// dumps in Run::r.images (the timed replays of `ffsim bench` do not need them).
Run replay(const trace::Program& prog, const std::string& out_dir, int threads, bool keep_images = true);

// The image a run dumped under `name` ("alpha.png"), or nullptr.
const Image* image_of(const Run& r, const std::string& name);

// v[i] > t.
std::vector<bool> threshold(const std::vector<double>& v, double t);

}  // namespace ffsim::paper

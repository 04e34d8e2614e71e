// Running a loaded trace on a Context: every step sets the Context's call site to
// its file:line:column, GL errors are collected with that position (a debug
// context's report), outputs (dump, hash, expect) are evaluated in order.
//
// Files: dumps are written under a temporary name next to their final name and
// renamed only when the whole run succeeded; a fatal error (--strict GL error, an
// I/O failure) removes them, so nothing is left written half-way. Failed
// `expect`s are not fatal: the run finishes, writes its dumps (so the failure can
// be looked at) and reports each failure.
#pragma once
#include <iosfwd>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sim/context.h"
#include "sim/trace/trace.h"

namespace ffsim::trace {

struct RunOptions {
  std::string out_dir;       // empty: dumps are made (see keep_images) but not written
  bool dump_each_pass = false;  // write passes/NNN-<command>-color/alpha/stencil after every pass
  bool explain = false;         // print the explainers' text after every pass
  int threads = 1;
  std::optional<std::pair<int, int>> probe;  // print what each pass did at this pixel
  bool strict = false;          // the first GL error not checked by `expect error` is fatal
  bool keep_images = false;     // keep every dump's image in RunResult::images
  bool outputs = true;          // false: skip dump, hash and expect steps and the final
                                // hashes (`ffsim bench` times the GL work alone)
};

struct HashLine {
  SourceLoc where;
  BufferKind buffer = BufferKind::Color;
  std::string hex;
};

struct RunResult {
  bool ok = true;     // false: a fatal error stopped the run and nothing was written
  std::string fatal;  // that error, "file:line:column: message"
  bool strict_stop = false;  // the fatal error is the last of gl_errors (--strict)
  int passes = 0;
  int steps = 0;      // steps executed
  double seconds = 0;
  std::vector<HashLine> hashes;               // `hash` outputs, in order
  std::vector<std::string> written;           // files written, relative to out_dir
  std::vector<std::string> gl_errors;         // GL errors not checked by `expect error`
  std::vector<std::string> expect_failures;   // "file:line:column: expect ...: got ..., expected ..."
  std::map<std::string, Image> images;        // keep_images: dump file -> image, plus the final
                                              // buffers as "final-color" and "final-alpha"
  std::vector<std::pair<std::string, std::string>> final_hashes;  // (color|alpha|stencil|depth, hash) at the end
  int exit_code() const { return ok && expect_failures.empty() ? 0 : 1; }
};

// `out` receives the --explain and --probe text. Never throws for trace or GL
// problems (they end up in the result).
RunResult run_program(const Program& program, const RunOptions& options, std::ostream& out);
// The same on a Context the caller made (tests inspect its state afterwards); the
// Context should have the program's profile and size.
RunResult run_program_on(Context& ctx, const Program& program, const RunOptions& options, std::ostream& out);

}  // namespace ffsim::trace

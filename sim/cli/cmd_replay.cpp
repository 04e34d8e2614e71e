// `ffsim replay TRACE ...`: load a trace, run it, write its dumps, print a summary.
#include <cstdio>
#include <filesystem>
#include <ostream>

#include "sim/cli/cli.h"
#include "sim/cli/trace_cli.h"
#include "sim/trace/executor.h"
#include "sim/trace/trace.h"

namespace ffsim::cli {

namespace {

const char* kUsage =
    "usage: ffsim replay TRACE [--set NAME=VALUE ...] [--profile NAME|FILE] [--size WxH]\n"
    "                    [--out DIR] [--dump-each-pass] [--explain] [--threads N]\n"
    "                    [--probe X,Y] [--strict] [--json]\n\n"
    "Runs a command trace (docs/trace-format.md) and writes its dumps to DIR\n"
    "(default out/<trace name>). Prints the passes run, the time, the `hash` outputs and\n"
    "the final hash of every buffer.\n\n"
    "  --set NAME=VALUE   override a `param` (VALUE is an expression)\n"
    "  --profile P        precision profile (built-in name or file), overrides the trace\n"
    "  --size WxH         framebuffer size, overrides the trace's `framebuffer`\n"
    "  --out DIR          where dumps are written\n"
    "  --dump-each-pass   also write DIR/passes/NNN-<command>-{color,alpha,stencil} after\n"
    "                     every pass (a draw, a copy or a clear)\n"
    "  --explain          after every pass, print what each area did (stages, equations)\n"
    "  --threads N        worker threads: the polygons of each glBegin/glEnd are drawn\n"
    "                     in bands of rows on N threads (results are identical for every N)\n"
    "  --probe X,Y        print each stage's input and output at pixel (X, Y) per pass\n"
    "  --strict           the first GL error not checked by `expect error` is fatal\n"
    "  --json             print the summary as JSON\n\n"
    "Errors in the trace are reported as file:line:column: message, before anything\n"
    "runs. Exit code 0 success, 1 a trace error, a fatal GL error or a failed\n"
    "`expect`, 2 a usage error. Nothing is written when the run fails half-way.\n";

}  // namespace

Subcommand replay_command() {
  Subcommand s;
  s.name = "replay";
  s.summary = "replay a command trace and write its dumps";
  s.usage = kUsage;
  s.run = [](const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    trace::LoadOptions lo;
    trace::RunOptions ro;
    std::string path, error;
    bool json = false, out_given = false;
    for (std::size_t i = 0; i < args.size(); ++i) {
      const std::string& a = args[i];
      if (parse_load_flag(args, i, lo, error)) {
        if (!error.empty()) return usage_error(err, "replay", error);
        continue;
      }
      auto value = [&](std::string& dst) {
        if (i + 1 >= args.size()) return false;
        dst = args[++i];
        return true;
      };
      std::string v;
      if (a == "--out") {
        if (!value(ro.out_dir) || ro.out_dir.empty()) return usage_error(err, "replay", "--out needs a directory");
        out_given = true;
      } else if (a == "--dump-each-pass") ro.dump_each_pass = true;
      else if (a == "--explain") ro.explain = true;
      else if (a == "--strict") ro.strict = true;
      else if (a == "--json") json = true;
      else if (a == "--threads") {
        int n = 0;
        if (!value(v) || std::sscanf(v.c_str(), "%d", &n) != 1 || n < 1 || n > 256 || std::to_string(n) != v)
          return usage_error(err, "replay", "--threads expects a number from 1 to 256");
        ro.threads = n;
      } else if (a == "--probe") {
        int x = 0, y = 0;
        if (!value(v) || !parse_int_pair(v, ',', x, y)) return usage_error(err, "replay", "--probe expects X,Y");
        ro.probe = std::make_pair(x, y);
      } else if (!a.empty() && a[0] == '-') {
        return usage_error(err, "replay", std::string("unknown argument `") + a + "`");
      } else if (path.empty()) {
        path = a;
      } else {
        return usage_error(err, "replay", std::string("expected one trace, got a second one `") + a + "`");
      }
    }
    if (path.empty()) return usage_error(err, "replay", "expected a trace file");
    if (!out_given) ro.out_dir = std::string("out/") + std::filesystem::path(path).stem().string();

    trace::Program prog;
    try {
      prog = trace::load_trace_file(path, lo);
    } catch (const trace::TraceError& e) {
      print_trace_error(err, "replay", e);
      if (json) out << "{\"trace\": " << json_string(path) << ", \"ok\": false, \"error\": " << json_string(e.what()) << "}\n";
      return 1;
    }
    if (ro.probe && (ro.probe->first < 0 || ro.probe->second < 0 || ro.probe->first >= prog.width ||
                     ro.probe->second >= prog.height))
      return usage_error(err, "replay", std::string("--probe ") + std::to_string(ro.probe->first) + "," +
                                            std::to_string(ro.probe->second) + " is outside the " +
                                            std::to_string(prog.width) + "x" + std::to_string(prog.height) + " framebuffer");

    std::ostream& text = out;
    const trace::RunResult r = trace::run_program(prog, ro, text);
    for (const auto& e : r.gl_errors) err << e << "\n";
    for (const auto& e : r.expect_failures) err << e << "\n";
    if (!r.ok && r.strict_stop) err << "ffsim replay: stopped at the first GL error (--strict); nothing written\n";
    else if (!r.ok) err << r.fatal << "\nffsim replay: stopped; nothing written\n";

    if (json) {
      out << "{\"trace\": " << json_string(path) << ", \"ok\": " << (r.exit_code() == 0 ? "true" : "false")
          << ", \"error\": " << (r.ok ? "null" : json_string(r.fatal)) << ", \"profile\": " << json_string(prog.profile.name)
          << ", \"width\": " << prog.width << ", \"height\": " << prog.height << ", \"threads\": " << ro.threads
          << ", \"passes\": " << r.passes << ", \"steps\": " << r.steps << ", \"seconds\": " << json_number(r.seconds)
          << ", \"hashes\": [";
      for (std::size_t k = 0; k < r.hashes.size(); ++k)
        out << (k ? ", " : "") << "{\"buffer\": " << json_string(trace::buffer_kind_name(r.hashes[k].buffer))
            << ", \"hash\": " << json_string(r.hashes[k].hex) << ", \"where\": " << json_string(r.hashes[k].where.str()) << "}";
      out << "], \"final\": {";
      bool first = true;
      for (const auto& [k, v] : r.final_hashes) {
        out << (first ? "" : ", ") << json_string(k) << ": " << json_string(v);
        first = false;
      }
      std::vector<std::string> written;
      for (const auto& w : r.written) written.push_back((std::filesystem::path(ro.out_dir) / w).string());
      out << "}, \"written\": " << json_string_array(written) << ", \"gl_errors\": " << json_string_array(r.gl_errors)
          << ", \"expect_failures\": " << json_string_array(r.expect_failures) << "}\n";
    } else {
      char secs[32];
      std::snprintf(secs, sizeof secs, "%.3f", r.seconds);
      out << path << ": profile " << prog.profile.name << ", " << prog.width << "x" << prog.height << ", " << r.passes
          << " pass" << (r.passes == 1 ? "" : "es") << ", " << r.steps << " steps, " << secs << " s\n";
      for (const auto& h : r.hashes)
        out << "hash " << trace::buffer_kind_name(h.buffer) << " " << h.hex << "  " << h.where.str() << "\n";
      for (const auto& [k, v] : r.final_hashes) out << "final " << k << " " << v << "\n";
      for (const auto& w : r.written) out << "wrote " << (std::filesystem::path(ro.out_dir) / w).string() << "\n";
      if (!r.expect_failures.empty()) out << r.expect_failures.size() << " expect failed\n";
    }
    return r.exit_code();
  };
  return s;
}

}  // namespace ffsim::cli

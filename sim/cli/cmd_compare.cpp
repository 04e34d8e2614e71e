// `ffsim compare TRACE_A [TRACE_B]`: replay two traces (or one trace under two
// profiles) and diff their dumps and final buffers.
#include <ostream>
#include <sstream>

#include "sim/cli/cli.h"
#include "sim/cli/trace_cli.h"
#include "sim/trace/executor.h"
#include "sim/trace/trace.h"

namespace ffsim::cli {

Subcommand compare_command() {
  Subcommand s;
  s.name = "compare";
  s.summary = "replay two traces (or one under two profiles) and diff them";
  s.usage =
      "usage: ffsim compare TRACE_A [TRACE_B] [--set NAME=VALUE ...] [--profile P]\n"
      "                     [--profile-a P] [--profile-b P] [--size WxH] [--out DIR] [--json]\n\n"
      "Replays both traces (one trace twice when TRACE_B is omitted, then --profile-a\n"
      "and/or --profile-b should differ) without writing their dumps, and diffs every\n"
      "dump the two runs have in common (matched by file name) and the final color and\n"
      "alpha buffers (final-color, final-alpha), as `ffsim diff` does. --set, --profile\n"
      "and --size apply to both runs; --profile-a/--profile-b to one each. --out DIR\n"
      "writes heat maps of the images that differ.\n\n"
      "Exit code 0 identical, 1 different, 2 error (a trace error, a failed run, usage).\n";
  s.run = [](const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    trace::LoadOptions lo;
    std::vector<std::string> paths;
    std::string profile_a, profile_b, out_dir, error;
    bool json = false;
    for (std::size_t i = 0; i < args.size(); ++i) {
      const std::string& a = args[i];
      if (parse_load_flag(args, i, lo, error)) {
        if (!error.empty()) return usage_error(err, "compare", error);
        continue;
      }
      auto value = [&](std::string& dst, const char* what) {
        if (i + 1 >= args.size() || args[i + 1].empty()) {
          error = a + " needs " + what;
          return false;
        }
        dst = args[++i];
        return true;
      };
      if (a == "--profile-a") { if (!value(profile_a, "a profile")) return usage_error(err, "compare", error); }
      else if (a == "--profile-b") { if (!value(profile_b, "a profile")) return usage_error(err, "compare", error); }
      else if (a == "--out") { if (!value(out_dir, "a directory")) return usage_error(err, "compare", error); }
      else if (a == "--json") json = true;
      else if (!a.empty() && a[0] == '-') return usage_error(err, "compare", std::string("unknown argument `") + a + "`");
      else paths.push_back(a);
    }
    if (paths.empty() || paths.size() > 2) return usage_error(err, "compare", "expected one or two traces");
    if (paths.size() == 1) paths.push_back(paths[0]);

    trace::RunResult runs[2];
    std::string profiles[2];
    for (int k = 0; k < 2; ++k) {
      trace::LoadOptions o = lo;
      const std::string& p = k == 0 ? profile_a : profile_b;
      if (!p.empty()) o.profile = p;
      trace::Program prog;
      try {
        prog = trace::load_trace_file(paths[static_cast<std::size_t>(k)], o);
      } catch (const trace::TraceError& e) {
        print_trace_error(err, "compare", e);
        return 2;
      }
      profiles[k] = prog.profile.name;
      trace::RunOptions ro;
      ro.keep_images = true;
      std::ostringstream ignored;
      runs[k] = trace::run_program(prog, ro, ignored);
      for (const auto& e : runs[k].gl_errors) err << e << "\n";
      if (!runs[k].ok) {
        err << runs[k].fatal << "\nffsim compare: run " << (k == 0 ? "A" : "B") << " failed\n";
        return 2;
      }
    }
    std::vector<std::pair<std::string, std::pair<const Image*, const Image*>>> pairs;
    std::vector<std::string> only_a, only_b;
    for (const auto& [name, im] : runs[0].images) {
      auto it = runs[1].images.find(name);
      if (it == runs[1].images.end()) only_a.push_back(name);
      else pairs.push_back({name, {&im, &it->second}});
    }
    for (const auto& [name, im] : runs[1].images)
      if (!runs[0].images.count(name)) only_b.push_back(name);
    if (!json) {
      out << "A: " << paths[0] << " (profile " << profiles[0] << ")\nB: " << paths[1] << " (profile " << profiles[1] << ")\n";
    }
    const std::string header = std::string("\"a\": {\"trace\": ") + json_string(paths[0]) + ", \"profile\": " + json_string(profiles[0]) +
                               std::string("}, \"b\": {\"trace\": ") + json_string(paths[1]) + ", \"profile\": " + json_string(profiles[1]) + "}, ";
    return run_diff(pairs, only_a, only_b, out_dir, json, out, err, header);
  };
  return s;
}

}  // namespace ffsim::cli

// `ffsim paper-report` (the main job: every paper trace for every scene, with the
// report) and `ffsim paper-mesh` (the generated terrain mesh include). sim/paper.h.
#include <fstream>
#include <ostream>

#include "sim/cli/cli.h"
#include "sim/paper.h"
#include "sim/trace/trace.h"

namespace ffsim::cli {

namespace {

const char* kReportUsage =
    "usage: ffsim paper-report [--traces DIR] [--out DIR] [--set NAME=VALUE ...] [--quick] [--threads N]\n\n"
    "Replays the paper's traces (traces/kautz-*.trace, bump-only.trace) for the single\n"
    "polygon, the magnified polygon and the terrain, and writes DIR/<scene>/<variant>/\n"
    "(color.png, alpha.png, stencil.png or factor.png), DIR/report.md and DIR/report.json:\n"
    "per variant the lit/shadow disagreement with the exact ray-cast reference, the RMSE\n"
    "of the shadow factor against the soft reference, the run time and the content hashes.\n\n"
    "  --traces DIR   where the traces are (default traces)\n"
    "  --out DIR      output folder (default out)\n"
    "  --set N=V      a parameter for every run (e.g. --set lx=0.8)\n"
    "  --quick        small resolutions (a smoke run)\n"
    "  --threads N    worker threads per replay (results do not depend on it)\n\n"
    "Exit code 0 when every run succeeded, 1 otherwise (the report lists the failures).\n";

const char* kMeshUsage =
    "usage: ffsim paper-mesh [--lit] [--out FILE]\n\n"
    "Prints the terrain mesh include (traces/include/terrain-mesh.trace; with --lit\n"
    "terrain-mesh-lit.trace, with the per-vertex light colour) or writes it to FILE.\n";

}  // namespace

Subcommand paper_report_command() {
  Subcommand s;
  s.name = "paper-report";
  s.summary = "the main job: replay the paper's traces for both scenes and write the report";
  s.usage = kReportUsage;
  s.run = [](const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    if (wants_help(args)) {
      out << kReportUsage;
      return 0;
    }
    paper::ReportOptions o;
    for (std::size_t i = 0; i < args.size(); ++i) {
      const std::string& a = args[i];
      const bool has_value = i + 1 < args.size();
      if (a == "--quick") {
        o.quick = true;
      } else if (a == "--traces" && has_value) {
        o.traces_dir = args[++i];
      } else if (a == "--out" && has_value) {
        o.out_dir = args[++i];
      } else if (a == "--threads" && has_value) {
        try {
          o.threads = std::stoi(args[++i]);
        } catch (const std::exception&) {
          return usage_error(err, "paper-report", "--threads needs a number");
        }
      } else if (a == "--set" && has_value) {
        try {
          o.sets.push_back(trace::parse_set_argument(args[++i]));
        } catch (const std::exception& e) {
          return usage_error(err, "paper-report", e.what());
        }
      } else {
        return usage_error(err, "paper-report", std::string("unknown or incomplete argument `") + a + "`");
      }
    }
    return paper::run_report(o, out, err);
  };
  return s;
}

Subcommand paper_mesh_command() {
  Subcommand s;
  s.name = "paper-mesh";
  s.summary = "print the terrain mesh include of the paper's traces";
  s.usage = kMeshUsage;
  s.run = [](const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    if (wants_help(args)) {
      out << kMeshUsage;
      return 0;
    }
    bool lit = false;
    std::string file;
    for (std::size_t i = 0; i < args.size(); ++i) {
      if (args[i] == "--lit") lit = true;
      else if (args[i] == "--out" && i + 1 < args.size()) file = args[++i];
      else return usage_error(err, "paper-mesh", std::string("unknown or incomplete argument `") + args[i] + "`");
    }
    const std::string text = paper::terrain_mesh_trace(lit);
    if (file.empty()) {
      out << text;
      return 0;
    }
    std::ofstream f(file, std::ios::binary);
    f << text;
    if (!f) {
      err << "ffsim paper-mesh: cannot write " << file << "\n";
      return 1;
    }
    return 0;
  };
  return s;
}

}  // namespace ffsim::cli

#include "sim/cli/cli.h"

#include <algorithm>
#include <ostream>
#include <string>

namespace ffsim::cli {

const std::vector<Subcommand>& subcommands() {
  static const std::vector<Subcommand> all = {
      replay_command(),
      diff_command(),
      compare_command(),
      info_command(),
      paper_report_command(),
      paper_mesh_command(),
      bench_command(),
      stress_command(),
      bumpshadow_command(),
      profiles_command(),
      demo_command(),
  };
  return all;
}

bool wants_help(const std::vector<std::string>& args) {
  for (const auto& a : args)
    if (a == "--help" || a == "-h") return true;
  return false;
}

int usage_error(std::ostream& err, const std::string& subcommand, const std::string& message) {
  err << "ffsim" << (subcommand.empty() ? "" : " " + subcommand) << ": " << message
      << " (see `ffsim " << (subcommand.empty() ? "" : subcommand + " ") << "--help`)\n";
  return 2;
}

static void print_help(std::ostream& out) {
  out << "ffsim " FFSIM_VERSION " - a bit-exact simulator of the fixed-function GL pipeline of about 2000\n\n"
         "usage: ffsim [--help] [--version] COMMAND [ARGS...]\n\ncommands:\n";
  std::size_t width = 0;  // the summaries' column: two spaces after the longest name
  for (const auto& s : subcommands()) width = std::max(width, s.name.size() + 2);
  for (const auto& s : subcommands()) out << "  " << s.name << std::string(width - s.name.size(), ' ') << s.summary << "\n";
  out << "\n`ffsim COMMAND --help` describes a command. Exit codes: 0 success, 1 failure, 2 usage error.\n";
}

int run(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  if (args.empty()) {
    print_help(err);
    return 2;
  }
  const std::string& first = args[0];
  if (first == "--help" || first == "-h" || first == "help") {
    print_help(out);
    return 0;
  }
  if (first == "--version" || first == "-V") {
    out << "ffsim " FFSIM_VERSION "\n";
    return 0;
  }
  if (!first.empty() && first[0] == '-') return usage_error(err, "", "unknown option `" + first + "`");
  for (const auto& s : subcommands()) {
    if (s.name != first) continue;
    const std::vector<std::string> rest(args.begin() + 1, args.end());
    if (wants_help(rest) && !s.usage.empty()) {
      out << s.usage;
      return 0;
    }
    return s.run(rest, out, err);
  }
  return usage_error(err, "", "unknown command `" + first + "`");
}

}  // namespace ffsim::cli

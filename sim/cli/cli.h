// The ffsim command line: a table of subcommands, each a function of its
// arguments. main() only forwards argv here, so tests drive the CLI directly.
//
// Conventions (docs/cli.md): results on stdout, errors on stderr as one line
// `ffsim: ...`; exit code 0 success, 1 failure of the work itself (a trace error,
// images differ), 2 usage errors (unknown subcommand or flag, missing argument).
#pragma once
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace ffsim::cli {

struct Subcommand {
  std::string name;
  std::string summary;  // one line for `ffsim --help`
  std::string usage;    // full text for `ffsim NAME --help`
  std::function<int(const std::vector<std::string>& args, std::ostream& out, std::ostream& err)> run;
};

// All subcommands, in help order.
const std::vector<Subcommand>& subcommands();

// Entry point: args excludes argv[0].
int run(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

// Helpers for subcommands.
int usage_error(std::ostream& err, const std::string& subcommand, const std::string& message);
bool wants_help(const std::vector<std::string>& args);

// Subcommand implementations (one file each under sim/cli/).
Subcommand demo_command();
Subcommand profiles_command();
Subcommand bumpshadow_command();
Subcommand replay_command();
Subcommand diff_command();
Subcommand compare_command();
Subcommand info_command();
Subcommand paper_report_command();
Subcommand paper_mesh_command();
Subcommand bench_command();
Subcommand stress_command();

}  // namespace ffsim::cli

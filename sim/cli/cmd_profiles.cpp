// `ffsim profiles [NAME|FILE]`: list the built-in precision profiles or print one.
#include <ostream>

#include "sim/cli/cli.h"
#include "sim/profile_io.h"

namespace ffsim::cli {

Subcommand profiles_command() {
  Subcommand s;
  s.name = "profiles";
  s.summary = "list the precision profiles, or print one as a profile file";
  s.usage =
      "usage: ffsim profiles [NAME|FILE]\n\n"
      "Without an argument, lists the built-in precision profiles. With a profile name or\n"
      "a profile file, prints it in the profile-file format (key = value lines), which can\n"
      "be edited and passed back with --profile FILE.\n";
  s.run = [](const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    if (args.size() > 1) return usage_error(err, "profiles", "expected at most one argument");
    if (!args.empty() && !args[0].empty() && args[0][0] == '-')
      return usage_error(err, "profiles", "unknown option `" + args[0] + "`");
    if (args.empty()) {
      for (const auto& p : builtin_profiles()) out << p.name << "\t" << p.description << "\n";
      return 0;
    }
    try {
      out << format_profile(load_profile(args[0]));
      return 0;
    } catch (const ProfileError& e) {
      err << "ffsim profiles: " << e.what() << "\n";
      return 1;
    }
  };
  return s;
}

}  // namespace ffsim::cli

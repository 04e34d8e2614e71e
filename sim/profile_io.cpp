#include "sim/profile_io.h"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace ffsim {

Profile load_profile(const std::string& spec) {
  if (const Profile* p = find_builtin_profile(spec)) return *p;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(spec, ec)) {
    std::string names;
    for (const auto& p : builtin_profiles()) names += (names.empty() ? "" : ", ") + p.name;
    throw ProfileError(spec + ": not a built-in profile (" + names + ") and not a readable file");
  }
  std::ifstream in(spec, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) throw ProfileError(spec + ": read error");
  return parse_profile(text.str(), spec);
}

}  // namespace ffsim

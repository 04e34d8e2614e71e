// Profiles named on the command line or in a trace: a built-in name or a file.
#pragma once
#include <string>

#include "pipeline/number/profile.h"

namespace ffsim {

// `spec` is a built-in profile name (geforce256, rgba10, rgba12, float32, ideal)
// or the path of a profile file (docs/numerics.md §3). Throws ProfileError.
Profile load_profile(const std::string& spec);

}  // namespace ffsim

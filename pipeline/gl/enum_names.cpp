#include "pipeline/gl/enum_names.h"

#include <algorithm>
#include <cstdio>

namespace ffsim::gl {

namespace {
bool has_vendor_suffix(std::string_view n) {
  for (std::string_view s : {"_ARB", "_EXT", "_NV", "_SGI", "_SGIS", "_SGIX"})
    if (n.size() > s.size() && n.substr(n.size() - s.size()) == s) return true;
  return false;
}
}  // namespace

std::optional<GLenum> enum_value(std::string_view name) {
  std::string full = name.substr(0, 3) == "GL_" ? std::string(name) : "GL_" + std::string(name);
  // kEnumNames is sorted by name (generator guarantees it).
  auto it = std::lower_bound(kEnumNames, kEnumNames + kEnumNameCount, full,
                             [](const EnumName& e, const std::string& k) { return k.compare(e.name) > 0; });
  if (it != kEnumNames + kEnumNameCount && full == it->name) return it->value;
  return std::nullopt;
}

std::string enum_name(GLenum value, std::string_view hint) {
  const EnumName* best = nullptr;
  auto score = [&](const EnumName& e) {
    std::string_view n(e.name);
    int s = 0;
    if (!hint.empty() && n.substr(0, hint.size()) == hint) s += 4;
    if (!has_vendor_suffix(n)) s += 2;
    return s;
  };
  for (std::size_t i = 0; i < kEnumNameCount; ++i) {
    const EnumName& e = kEnumNames[i];
    if (e.value != value) continue;
    if (!best || score(e) > score(*best)) best = &e;
  }
  if (best) return best->name;
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%04X", static_cast<unsigned>(value));
  return buf;
}

}  // namespace ffsim::gl

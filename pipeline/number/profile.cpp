#include "pipeline/number/profile.h"

#include <charconv>
#include <sstream>

namespace ffsim {

namespace {

Profile make(std::string name, std::string desc, Arithmetic a, int color, int tex, int comb,
             int units, int combiners) {
  Profile p;
  p.name = std::move(name);
  p.description = std::move(desc);
  p.arithmetic = a;
  p.color_bits = color;
  p.texture_bits = tex;
  p.combiner_bits = comb;
  p.texture_units = units;
  p.general_combiners = combiners;
  return p;
}

struct IntField {
  const char* key;
  int Profile::*member;
  int lo, hi;
};
constexpr IntField kIntFields[] = {
    {"color_bits", &Profile::color_bits, 1, 16},
    {"texture_bits", &Profile::texture_bits, 1, 16},
    {"stencil_bits", &Profile::stencil_bits, 0, 8},
    {"depth_bits", &Profile::depth_bits, 0, 24},
    {"combiner_bits", &Profile::combiner_bits, 2, 17},
    {"bilinear_weight_bits", &Profile::bilinear_weight_bits, 1, 16},
    {"subpixel_bits", &Profile::subpixel_bits, 1, 8},
    {"texture_units", &Profile::texture_units, 1, 4},
    {"general_combiners", &Profile::general_combiners, 1, 8},
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

}  // namespace

const std::vector<Profile>& builtin_profiles() {
  static const std::vector<Profile> all = {
      make("geforce256",
           "NVIDIA GeForce 256 (NV10), 2000: RGBA8 framebuffer and textures, 8-bit stencil, "
           "9-bit signed combiner registers (8 bits plus sign), 2 texture units, 2 general combiners",
           Arithmetic::Fixed, 8, 8, 9, 2, 2),
      make("rgba10", "10 bits per channel everywhere (framebuffer, textures, 10 bits plus sign combiners), "
                     "4 texture units, 8 general combiners",
           Arithmetic::Fixed, 10, 10, 11, 4, 8),
      make("rgba12", "12 bits per channel everywhere (framebuffer, textures, 12 bits plus sign combiners), "
                     "4 texture units, 8 general combiners",
           Arithmetic::Fixed, 12, 12, 13, 4, 8),
      make("float32", "IEEE binary32 storage and arithmetic, spec clamps only; 4 units, 8 combiners",
           Arithmetic::Float32, 8, 8, 9, 4, 8),
      make("ideal", "IEEE binary64 reference: no quantisation, only the clamps the GL specs require; "
                    "4 units, 8 combiners",
           Arithmetic::Float64, 8, 8, 9, 4, 8),
  };
  return all;
}

const Profile* find_builtin_profile(std::string_view name) {
  for (const Profile& p : builtin_profiles())
    if (p.name == name) return &p;
  return nullptr;
}

std::string_view arithmetic_name(Arithmetic a) {
  switch (a) {
    case Arithmetic::Fixed: return "fixed";
    case Arithmetic::Float32: return "float32";
    case Arithmetic::Float64: return "float64";
  }
  return "fixed";
}

void validate_profile(const Profile& p, std::string_view source_name) {
  for (const IntField& f : kIntFields) {
    const int v = p.*(f.member);
    if (v < f.lo || v > f.hi)
      throw ProfileError(std::string(source_name) + ": " + f.key + " = " + std::to_string(v) +
                         " is out of range (expected " + std::to_string(f.lo) + ".." +
                         std::to_string(f.hi) + ")");
  }
  if (p.depth_bits != 0 && p.depth_bits != 16 && p.depth_bits != 24)
    throw ProfileError(std::string(source_name) + ": depth_bits = " + std::to_string(p.depth_bits) +
                       " (expected 0, 16 or 24)");
}

Profile parse_profile(std::string_view text, std::string_view source_name) {
  Profile p;
  p.description.clear();
  bool named = false;
  int line_no = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t nl = text.find('\n', pos);
    std::string_view line = text.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos);
    pos = nl == std::string_view::npos ? text.size() + 1 : nl + 1;
    ++line_no;
    if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    line = trim(line);
    if (line.empty()) continue;
    const std::string where = std::string(source_name) + ":" + std::to_string(line_no) + ": ";
    const auto eq = line.find('=');
    if (eq == std::string_view::npos)
      throw ProfileError(where + "expected `key = value`, got `" + std::string(line) + "`");
    const std::string_view key = trim(line.substr(0, eq));
    const std::string_view val = trim(line.substr(eq + 1));
    if (key == "base") {
      const Profile* b = find_builtin_profile(val);
      if (!b) throw ProfileError(where + "unknown base profile `" + std::string(val) + "`");
      p = *b;
      continue;
    }
    if (key == "name") { p.name = std::string(val); named = true; continue; }
    if (key == "description") { p.description = std::string(val); continue; }
    if (key == "arithmetic") {
      if (val == "fixed") p.arithmetic = Arithmetic::Fixed;
      else if (val == "float32") p.arithmetic = Arithmetic::Float32;
      else if (val == "float64") p.arithmetic = Arithmetic::Float64;
      else throw ProfileError(where + "arithmetic must be fixed, float32 or float64, got `" + std::string(val) + "`");
      continue;
    }
    bool found = false;
    for (const IntField& f : kIntFields) {
      if (key != f.key) continue;
      int v = 0;
      const auto [ptr, ec] = std::from_chars(val.data(), val.data() + val.size(), v);
      if (ec != std::errc() || ptr != val.data() + val.size())
        throw ProfileError(where + f.key + " expects an integer, got `" + std::string(val) + "`");
      if (v < f.lo || v > f.hi)
        throw ProfileError(where + f.key + " = " + std::to_string(v) + " is out of range (expected " +
                           std::to_string(f.lo) + ".." + std::to_string(f.hi) + ")");
      p.*(f.member) = v;
      found = true;
    }
    if (!found) throw ProfileError(where + "unknown key `" + std::string(key) + "`");
  }
  if (!named) p.name = std::string(source_name);
  validate_profile(p, source_name);
  return p;
}

std::string format_profile(const Profile& p) {
  std::ostringstream o;
  o << "name = " << p.name << "\n";
  if (!p.description.empty()) o << "description = " << p.description << "\n";
  o << "arithmetic = " << arithmetic_name(p.arithmetic) << "\n";
  for (const IntField& f : kIntFields) o << f.key << " = " << p.*(f.member) << "\n";
  return o.str();
}

}  // namespace ffsim

// Precision profiles: what the simulated hardware computes with, as plain data.
//
// A profile says how wide every stored and intermediate value is. The same trace
// runs under a hardware profile (integer codes, e.g. geforce256) and under the
// `ideal` profile (binary64, no quantisation; only the clamps the GL specs
// require); the difference is the hardware error. docs/numerics.md §3 lists
// each field's meaning and the named profiles.
#pragma once
#include <string>
#include <string_view>
#include <vector>

namespace ffsim {

// How values between stages are represented.
enum class Arithmetic {
  Fixed,    // integer codes of the widths below, stated rounding at each store
  Float32,  // IEEE binary32 everywhere a value is stored (no integer quantisation)
  Float64,  // IEEE binary64, the `ideal` reference
};

struct Profile {
  std::string name = "geforce256";
  std::string description;
  Arithmetic arithmetic = Arithmetic::Fixed;
  int color_bits = 8;            // framebuffer R, G, B, A bits per channel (1..16)
  int texture_bits = 8;          // texel component bits of unsized internal formats (1..16)
  int stencil_bits = 8;          // stencil buffer bits (0..8; 0 = no stencil buffer)
  int depth_bits = 24;           // depth buffer bits (0, 16 or 24; 0 = no depth buffer)
  int combiner_bits = 9;         // signed combiner register width incl. sign (2..17): codes /(2^(B-1)-1)
  int bilinear_weight_bits = 8;  // fractional bits of LINEAR/mipmap filter weights (1..16)
  int subpixel_bits = 4;         // rasterizer sub-pixel precision of window coordinates (1..8)
  int texture_units = 2;         // MAX_TEXTURE_UNITS (1..4)
  int general_combiners = 2;     // MAX_GENERAL_COMBINERS_NV (1..8)

  bool is_fixed() const { return arithmetic == Arithmetic::Fixed; }
  bool operator==(const Profile&) const = default;
};

// Built-in profiles: geforce256, rgba10, rgba12, float32, ideal.
const std::vector<Profile>& builtin_profiles();
// The named built-in profile, or nullptr.
const Profile* find_builtin_profile(std::string_view name);

// Parse a profile file: `key = value` lines, `#` comments. An optional first key
// `base = NAME` starts from a built-in profile; the other keys are the field names
// above (arithmetic = fixed|float32|float64). Unknown keys, bad or out-of-range
// values raise ProfileError naming source:line.
Profile parse_profile(std::string_view text, std::string_view source_name);

// Field ranges (throws ProfileError naming `source_name` when a field is out of range).
void validate_profile(const Profile& p, std::string_view source_name);

// The profile as the text parse_profile reads (round trips exactly).
std::string format_profile(const Profile& p);

std::string_view arithmetic_name(Arithmetic a);

struct ProfileError : std::exception {
  std::string message;
  explicit ProfileError(std::string m) : message(std::move(m)) {}
  const char* what() const noexcept override { return message.c_str(); }
};

}  // namespace ffsim

// Signed combiner values (NV_register_combiners, "signed [-1,1]" registers).
//
// Representation: a B-bit two's-complement register (B counts the sign bit) holds
// a code c in [-M, M] with M = 2^(B-1) - 1 and value c / M. For the geforce256
// profile B = 9 ("8 bits plus sign"), M = 255, so value = c / 255: the same grid
// as an 8-bit unorm, with -1, 0 and +1 exact. This is the scale NVIDIA's
// NV_texture_shader issue on signed precision gives for the 9-bit combiner type
// (255 -> +1.0, -255 -> -1.0); the extra code -256 that issue mentions is never
// produced because every register write clamps to [-1, 1] (NV_register_combiners
// §3.8.12.2). See docs/numerics.md §2.
//
// Rounding: exact rational value, then round half away from zero (sign
// symmetric, so negating an input negates the result), then saturate to [-M, M].
#pragma once
#include <cstdint>

namespace ffsim {

inline constexpr int kMinSnormBits = 2;
inline constexpr int kMaxSnormBits = 17;

// M = 2^(B-1) - 1, the code of +1.0.
constexpr std::int32_t snorm_max(int bits) { return (std::int32_t{1} << (bits - 1)) - 1; }

// Round half away from zero of the rational num / den, den > 0.
constexpr std::int64_t div_round_half_away(std::int64_t num, std::int64_t den) {
  const std::int64_t q = (2 * (num < 0 ? -num : num) + den) / (2 * den);
  return num < 0 ? -q : q;
}

constexpr std::int32_t snorm_saturate(std::int64_t c, int bits) {
  const std::int64_t m = snorm_max(bits);
  return static_cast<std::int32_t>(c > m ? m : (c < -m ? -m : c));
}

// float -> signed code: clamp to [-1,1], round half away from zero on the exact
// value of x. NaN -> 0 (same choice as unorm_from_double).
std::int32_t snorm_from_double(double x, int bits);

inline double snorm_to_double(std::int32_t c, int bits) {
  return static_cast<double>(c) / static_cast<double>(snorm_max(bits));
}

// An unsigned N-bit code k (value k / (2^N - 1)) as a signed code. Exact when the
// grids agree (8-bit unorm into a 9-bit register: c = k), else rounded.
std::int32_t snorm_from_unorm(std::uint32_t k, int unorm_bits, int snorm_bits);

// Saturating add: (a + b) clamped to [-M, M]. Exact before the clamp.
constexpr std::int32_t snorm_add_sat(std::int32_t a, std::int32_t b, int bits) {
  return snorm_saturate(std::int64_t{a} + b, bits);
}

// Saturating multiply: the exact product (a/M)(b/M) = a*b / M^2 rounded half
// away from zero to the /M grid, i.e. c = round(a*b / M). |result| <= M always
// holds for in-range operands; the saturation guards out-of-range inputs.
constexpr std::int32_t snorm_mul_sat(std::int32_t a, std::int32_t b, int bits) {
  return snorm_saturate(div_round_half_away(std::int64_t{a} * b, snorm_max(bits)), bits);
}

// A value type for code that prefers operators; all arithmetic defers to the
// functions above at the type's width.
struct Snorm {
  std::int32_t code = 0;
  int bits = 9;

  double value() const { return snorm_to_double(code, bits); }
  static Snorm from_double(double x, int bits) { return {snorm_from_double(x, bits), bits}; }
  friend Snorm operator+(Snorm a, Snorm b) { return {snorm_add_sat(a.code, b.code, a.bits), a.bits}; }
  friend Snorm operator*(Snorm a, Snorm b) { return {snorm_mul_sat(a.code, b.code, a.bits), a.bits}; }
  friend Snorm operator-(Snorm a) { return {-a.code, a.bits}; }
  friend bool operator==(Snorm a, Snorm b) { return a.code == b.code && a.bits == b.bits; }
};

}  // namespace ffsim

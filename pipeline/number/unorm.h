// Unsigned normalized fixed point (GL 1.2.1 §2.13.9): an N-bit code k in
// [0, 2^N - 1] represents the real k / (2^N - 1); all ones is exactly 1.0.
//
// Every conversion here rounds the *exact* real value once, to nearest, ties up
// (round half up; for the non-negative values involved this is also "ties away
// from zero"). See docs/numerics.md §1 for the evidence behind the tie rule.
#pragma once
#include <bit>
#include <cstdint>

namespace ffsim {

inline constexpr int kMinUnormBits = 1;
// Conversions support up to 24 bits (the depth buffer); colour and texture
// storage is at most 16 bits (kMaxColorBits).
inline constexpr int kMaxUnormBits = 24;
inline constexpr int kMaxColorBits = 16;

// 2^N - 1, the code of 1.0.
constexpr std::uint32_t unorm_max(int bits) { return (std::uint32_t{1} << bits) - 1u; }

// float -> fixed. Clamps to [0,1], then k = floor(x * (2^N - 1) + 1/2) evaluated on
// the exact binary64 value of x (no intermediate rounding). NaN -> 0 (documented
// choice: GL leaves it undefined; 0 is what a clamp with NaN-false comparisons
// yields). +Inf -> 2^N - 1, -Inf -> 0. A float argument converts exactly to double.
std::uint32_t unorm_from_double(double x, int bits);
// The same for a binary32 value (unorm_from_double(double(x), bits), which is
// exact), in 64-bit integers: a float's 24-bit significand times a code of at most
// 24 bits fits without the 128-bit product (inline: texture uploads convert every
// texel component with it).
inline std::uint32_t unorm_from_float(float x, int bits) {
  const std::uint32_t m = unorm_max(bits);
  if (!(x > 0.0f)) return 0;  // x <= 0 or NaN, as unorm_from_double
  if (x >= 1.0f) return m;
  // x = mant * 2^-s exactly: a normal x (biased exponent E <= 126, as x < 1) is
  // (2^23 + fraction)·2^(E − 150), so s = 150 − E >= 24. mant·m < 2^24·2^24, so
  // floor(x·m + 1/2) = (mant·m + 2^(s−1)) >> s in uint64 while s <= 63; for
  // s >= 64 (E <= 86, and every subnormal) x·m < 2^(48−64), far below 1/2: 0.
  const auto bits32 = std::bit_cast<std::uint32_t>(x);
  const int E = static_cast<int>(bits32 >> 23);  // the sign bit is 0 here (x > 0)
  if (E <= 86) return 0;
  const std::uint64_t mant = (bits32 & ((1u << 23) - 1)) | (1u << 23);
  const int s = 150 - E;
  return static_cast<std::uint32_t>((mant * m + (std::uint64_t{1} << (s - 1))) >> s);
}

// fixed -> float: the binary64 value nearest k / (2^N - 1). Converting it back with
// unorm_from_double gives k again for every k and N <= 16 (tested exhaustively).
inline double unorm_to_double(std::uint32_t k, int bits) {
  return static_cast<double>(k) / static_cast<double>(unorm_max(bits));
}

// Width conversion on the exact rational value: k' = round_half_up(k * (2^M - 1) / (2^N - 1)).
// Exact (no rounding happens) whenever N divides M, e.g. 8 -> 16 is k * 257.
std::uint32_t unorm_convert(std::uint32_t k, int from_bits, int to_bits);

// Round half up of the non-negative rational num / den (den > 0), in integers.
constexpr std::uint64_t div_round_half_up(std::uint64_t num, std::uint64_t den) {
  return (2 * num + den) / (2 * den);
}

}  // namespace ffsim

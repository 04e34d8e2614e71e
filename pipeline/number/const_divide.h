// Division of a bounded unsigned integer by a compile-time constant as one
// 32-bit multiply and a shift, for loops the compiler vectorises (AVX2 has no
// 32x32 -> 64-bit multiply across all eight lanes; a division by a constant
// otherwise takes two widening multiplies and a shuffle per eight lanes).
//
// floor(y / D) = (y * m) >> s for every 0 <= y <= kMax when
//   m = ceil(2^s / D),  m·D − 2^s <= 2^(s − N)  with kMax < 2^N
// (Granlund and Montgomery, "Division by invariant integers using
// multiplication", PLDI 1994, theorem 4.2), and kMax·m < 2^32 keeps the product
// in 32 bits. ConstDivide finds the smallest such s at compile time; `exact` is
// false when there is none (callers then divide). tests/pipeline/test_const_divide.cpp
// checks every y up to kMax for the divisors ffsim uses.
#pragma once
#include <cstdint>

namespace ffsim {

template <std::uint32_t kD, std::uint32_t kMax>
struct ConstDivide {
  struct Magic {
    bool exact = false;
    std::uint32_t m = 0;
    int s = 0;
  };
  static constexpr Magic find() {
    int n = 0;  // kMax < 2^n
    while (n < 32 && (std::uint64_t{1} << n) <= kMax) ++n;
    for (int s = 0; s < 64 - n; ++s) {
      const std::uint64_t p = std::uint64_t{1} << s;
      const std::uint64_t m = (p + kD - 1) / kD;
      if ((m * kD - p) << n > p) continue;  // the error bound, times 2^n
      if (m * kMax >= (std::uint64_t{1} << 32)) return {};  // larger s only grows m
      return {true, static_cast<std::uint32_t>(m), s};
    }
    return {};
  }
  static constexpr Magic magic = find();
  static constexpr bool exact = magic.exact;
  // floor(y / kD) for y <= kMax (only when exact).
  static constexpr std::uint32_t divide(std::uint32_t y) { return (y * magic.m) >> magic.s; }
};

}  // namespace ffsim

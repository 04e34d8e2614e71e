// ConstDivide (pipeline/number/const_divide.h): the multiply-and-shift quotient
// equals the integer quotient for every dividend in range, for the divisors the
// combiner kernel uses (M = 255: its output codes divide y <= M^2 by M), and a
// divisor/range pair with no 32-bit multiplier is reported as not exact.
#include <doctest/doctest.h>

#include <cstdint>

#include "pipeline/number/const_divide.h"

using namespace ffsim;

namespace {

template <std::uint32_t kD, std::uint32_t kMax>
void check_every_dividend() {
  using D = ConstDivide<kD, kMax>;
  REQUIRE(D::exact);
  std::uint32_t bad = 0;
  for (std::uint32_t y = 0; y <= kMax; ++y) bad += D::divide(y) != y / kD;
  CHECK(bad == 0);
}

}  // namespace

TEST_CASE("const divide: every dividend up to the bound, the combiner output divisor M = 255 over y <= M^2") {
  check_every_dividend<255, 255u * 255u>();
  static_assert(ConstDivide<255, 255u * 255u>::magic.m == 32897 && ConstDivide<255, 255u * 255u>::magic.s == 23,
                "m = ceil(2^23 / 255): the first s whose error 127 is within 2^(23-16)");
}

TEST_CASE("const divide: other divisors and bounds, a power of two and a product just below 2^32") {
  check_every_dividend<3, 60000>();
  check_every_dividend<7, 30000>();
  check_every_dividend<10, 65535>();
  check_every_dividend<127, 127u * 127u>();
  check_every_dividend<64, 1u << 24>();   // m = 1, s = 6
  check_every_dividend<1000, 60000>();    // m = 67109: 60000 m = 4026540000
}

TEST_CASE("const divide: no 32-bit multiplier for M = 511 or 1023 over y <= M^2 (callers divide)") {
  // The multiplier that meets the error bound times M^2 exceeds 2^32.
  CHECK_FALSE(ConstDivide<511, 511u * 511u>::exact);
  CHECK_FALSE(ConstDivide<1023, 1023u * 1023u>::exact);
  CHECK_FALSE(ConstDivide<3, 100000>::exact);
}

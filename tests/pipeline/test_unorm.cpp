// Unsigned normalized fixed point: conversions, rounding ties, widths, NaN.
// Expected values come from the closed forms in docs/numerics.md §1, evaluated
// here in exact integer or rational arithmetic independent of the code under test.
#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <random>

#include "pipeline/number/unorm.h"

using namespace ffsim;

TEST_CASE("unorm8: float -> fixed -> float round trip is the identity for all 256 codes") {
  for (std::uint32_t k = 0; k <= 255; ++k) {
    const double v = unorm_to_double(k, 8);
    CHECK(unorm_from_double(v, 8) == k);
    CHECK(unorm_from_double(static_cast<float>(v), 8) == k);  // binary32 input too
  }
}

TEST_CASE("unorm: round trip for every code of every width 1..16") {
  for (int bits = 1; bits <= 16; ++bits)
    for (std::uint32_t k = 0; k <= unorm_max(bits); ++k) REQUIRE(unorm_from_double(unorm_to_double(k, bits), bits) == k);
}

TEST_CASE("unorm8: every tie (k + 1/2)/255 rounds up, its neighbours round to nearest") {
  // The 255 tie points between codes k and k+1 are x = (2k+1)/510, which no
  // binary64 value equals exactly; so check the double nearest each tie and its
  // two neighbours against the exact rule (sign of 510x - (2k+1), computed with an
  // exact fma residual). Exactly representable ties are tested in the next case.
  CHECK(unorm_from_double(0.5, 1) == 1);                            // exact tie, rounds up
  CHECK(unorm_from_double(std::nextafter(0.5, 0.0), 1) == 0);       // just below
  for (std::uint32_t k = 0; k < 255; ++k) {
    const double tie = (2.0 * k + 1.0) / 510.0;  // nearest double to the tie
    const double below = std::nextafter(tie, 0.0), above = std::nextafter(tie, 1.0);
    // Decide each expectation in exact arithmetic: x*255 vs k + 1/2, i.e. sign of
    // 510x - (2k+1), computed with fma (exact residual of the product).
    for (double x : {below, tie, above}) {
      const double r = std::fma(510.0, x, -(2.0 * k + 1.0));  // exact: |r| tiny, representable
      const std::uint32_t expect = r >= 0 ? k + 1 : k;
      CHECK_MESSAGE(unorm_from_double(x, 8) == expect, "k=" << k << " x=" << x << " r=" << r);
    }
  }
}

TEST_CASE("unorm: exact ties at power-of-two denominators round half up at every width") {
  // m = 2^N - 1 is odd, so x = 1/2 gives x*m = (m-1)/2 + 1/2, an exact tie; x = 1/4
  // and 3/4 give fractions 1/4 or 3/4 (no tie) and must round to nearest.
  for (int bits = 1; bits <= 16; ++bits) {
    const std::uint32_t m = unorm_max(bits);
    // x = 1/2: m/2 = (m-1)/2 + 1/2, a tie; half up gives (m+1)/2.
    CHECK(unorm_from_double(0.5, bits) == (m + 1) / 2);
    // x = 1/4, 3/4: m/4 is never a tie for odd m (fraction 1/4 or 3/4) -> nearest.
    CHECK(unorm_from_double(0.25, bits) == (m + 2) / 4);
    CHECK(unorm_from_double(0.75, bits) == (3 * m + 2) / 4);
  }
}

TEST_CASE("unorm: saturation at both ends, infinities and NaN") {
  for (int bits : {1, 5, 8, 10, 12, 16}) {
    const std::uint32_t m = unorm_max(bits);
    CHECK(unorm_from_double(-1e-300, bits) == 0);
    CHECK(unorm_from_double(-0.0, bits) == 0);
    CHECK(unorm_from_double(-5.0, bits) == 0);
    CHECK(unorm_from_double(1.0, bits) == m);
    CHECK(unorm_from_double(1.0000001, bits) == m);
    CHECK(unorm_from_double(1e300, bits) == m);
    CHECK(unorm_from_double(std::numeric_limits<double>::infinity(), bits) == m);
    CHECK(unorm_from_double(-std::numeric_limits<double>::infinity(), bits) == 0);
    CHECK(unorm_from_double(std::numeric_limits<double>::quiet_NaN(), bits) == 0);  // documented: NaN -> 0
    CHECK(unorm_from_double(std::numeric_limits<double>::denorm_min(), bits) == 0);
  }
}

TEST_CASE("unorm: float -> fixed equals the exact rational rounding on a dense sweep") {
  // For x = i / 2^20 (exact in binary64) the exact rule is floor(i*m/2^20 + 1/2)
  // = (2*i*m + 2^20) / 2^21 in integers.
  for (int bits : {1, 2, 7, 8, 9, 10, 12, 16}) {
    const std::uint64_t m = unorm_max(bits);
    for (std::uint64_t i = 0; i <= (1u << 20); i += 7) {
      const double x = std::ldexp(static_cast<double>(i), -20);
      REQUIRE(unorm_from_double(x, bits) == (2 * i * m + (1u << 20)) / (1u << 21));
    }
  }
}

TEST_CASE("unorm: float -> fixed equals the rounding computed from frexp, random doubles of every exponent") {
  // unorm_from_double reads the binary64 fields; here x = f·2^e by std::frexp,
  // mant = f·2^53, and floor(x·m + 1/2) = (mant·m + 2^(s−1)) >> s with s = 53 − e
  // (the library decomposition as an independent reference). Random bit patterns
  // of doubles in (0, 1): every exponent down to the subnormals.
  std::mt19937_64 rng(31);
  __extension__ typedef unsigned __int128 u128;
  int nonzero = 0;
  for (int it = 0; it < 200000; ++it) {
    const std::uint64_t e = rng() % 1023;  // biased exponent 0 .. 1022: x < 1
    const std::uint64_t pattern = (e << 52) | (rng() & ((std::uint64_t{1} << 52) - 1));
    const double x = std::bit_cast<double>(pattern);
    if (!(x > 0.0)) continue;
    for (int bits : {1, 8, 10, 12, 16, 24}) {
      const std::uint64_t m = unorm_max(bits);
      int ex = 0;
      const double f = std::frexp(x, &ex);
      const auto mant = static_cast<std::uint64_t>(std::ldexp(f, 53));
      const int sh = 53 - ex;
      const std::uint32_t want =
          sh >= 120 ? 0u : static_cast<std::uint32_t>((static_cast<u128>(mant) * m + (static_cast<u128>(1) << (sh - 1))) >> sh);
      REQUIRE(unorm_from_double(x, bits) == want);
      nonzero += want != 0;
    }
  }
  CHECK(nonzero > 1000);
}

TEST_CASE("unorm: 24-bit conversions (depth codes) are exact") {
  // For x = i / 2^20 the exact rule is (2*i*m + 2^20) / 2^21 with m = 2^24 - 1.
  const std::uint64_t m = unorm_max(24);
  CHECK(m == 16777215u);
  for (std::uint64_t i = 0; i <= (1u << 20); i += 13) {
    const double x = std::ldexp(static_cast<double>(i), -20);
    REQUIRE(unorm_from_double(x, 24) == (2 * i * m + (1u << 20)) / (1u << 21));
  }
  CHECK(unorm_from_double(0.5, 24) == (m + 1) / 2);  // exact tie rounds up
  for (std::uint32_t k : {0u, 1u, 4096u, 8388607u, 16777215u}) CHECK(unorm_from_double(unorm_to_double(k, 24), 24) == k);
  CHECK(unorm_convert(65535, 16, 24) == 16777215u);
  CHECK(unorm_convert(255, 8, 24) == 16777215u);  // 8 divides 24: k * 65793
  CHECK(unorm_convert(1, 8, 24) == 65793u);
}

TEST_CASE("unorm: widening 8 -> 16 -> 8 is the identity and 8 -> 16 is k * 257") {
  for (std::uint32_t k = 0; k <= 255; ++k) {
    const std::uint32_t w = unorm_convert(k, 8, 16);
    CHECK(w == k * 257);
    CHECK(unorm_convert(w, 16, 8) == k);
  }
}

TEST_CASE("unorm: narrowing rounds the exact value half up (exhaustive 8 -> 1..7 and 16 -> 8)") {
  for (int to = 1; to < 8; ++to)
    for (std::uint32_t k = 0; k <= 255; ++k) {
      const std::uint32_t m = unorm_max(to);
      // exact: k*m/255, round half up = floor((2km + 255) / 510)
      REQUIRE(unorm_convert(k, 8, to) == (2 * k * m + 255) / 510);
    }
  for (std::uint32_t k = 0; k <= 65535; ++k) REQUIRE(unorm_convert(k, 16, 8) == (2 * k * 255 + 65535) / 131070);
  // 10 -> 8 tie example: 10-bit code 2 = 2/1023; *255 = 0.4985 -> 0; code 514 -> 128.12 -> 128.
  CHECK(unorm_convert(2, 10, 8) == 0);
  CHECK(unorm_convert(514, 10, 8) == 128);
}

TEST_CASE("unorm: width conversion is exact whenever the source width divides the target") {
  for (std::uint32_t k = 0; k <= 15; ++k) CHECK(unorm_convert(k, 4, 8) == k * 17);
  for (std::uint32_t k = 0; k <= 3; ++k) CHECK(unorm_convert(k, 2, 8) == k * 85);
  for (std::uint32_t k = 0; k <= 1; ++k) CHECK(unorm_convert(k, 1, 16) == k * 65535);
}

// unorm_from_float (64-bit integers) against unorm_from_double on the same value
// (the float converts to double exactly): every width 1..24 at the floats nearest
// each tie (k + 1/2)/(2^N − 1) and their neighbours (where a wrong shift or a
// missing rounding bit shows), every subnormal exponent, the special values, and
// random floats of every exponent.
TEST_CASE("unorm: unorm_from_float equals unorm_from_double on every kind of binary32 value") {
  long long checked = 0;
  auto same = [&](float x, int bits) {
    REQUIRE(unorm_from_float(x, bits) == unorm_from_double(static_cast<double>(x), bits));
    ++checked;
  };
  for (int bits = 1; bits <= 24; ++bits) {
    const double m = unorm_max(bits);
    const std::uint32_t step = bits <= 12 ? 1 : (unorm_max(bits) >> 12) | 1;
    for (std::uint32_t k = 0; k < unorm_max(bits); k += step) {
      const float tie = static_cast<float>((k + 0.5) / m);
      float lo = tie, hi = tie;
      for (int j = 0; j < 3; ++j) {
        same(lo, bits);
        same(hi, bits);
        lo = std::nextafter(lo, 0.0f);
        hi = std::nextafter(hi, 2.0f);
      }
      same(static_cast<float>(k / m), bits);
    }
    for (const float x : {0.0f, -0.0f, 1.0f, -1.0f, 2.0f, std::nextafter(1.0f, 0.0f), std::nextafter(0.0f, 1.0f),
                          std::numeric_limits<float>::min(), std::numeric_limits<float>::infinity(),
                          -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()})
      same(x, bits);
    for (int e = -149; e < 0; ++e) same(std::ldexp(1.0f, e) * 1.75f, bits);  // down through the subnormals
  }
  std::mt19937 rng(1124);
  for (int k = 0; k < 400000; ++k) {
    const float x = std::bit_cast<float>(static_cast<std::uint32_t>(rng()) & 0x3FFFFFFFu);  // [0, 2) and some above
    same(x, 1 + k % 24);
  }
  CHECK(checked > 800000);
}

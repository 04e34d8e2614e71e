// Signed combiner values: representation c/M, rounding half away from zero,
// saturating add and multiply. Expectations are closed forms in integers.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <limits>

#include "pipeline/number/snorm.h"
#include "pipeline/number/unorm.h"

using namespace ffsim;

TEST_CASE("snorm9 (geforce256): M = 255, -1, 0, +1 exact, round trip for all 511 codes") {
  CHECK(snorm_max(9) == 255);
  for (int c = -255; c <= 255; ++c) CHECK(snorm_from_double(snorm_to_double(c, 9), 9) == c);
  CHECK(snorm_from_double(-1.0, 9) == -255);
  CHECK(snorm_from_double(0.0, 9) == 0);
  CHECK(snorm_from_double(1.0, 9) == 255);
}

TEST_CASE("snorm: conversion clamps to [-1,1], rounds half away from zero, NaN -> 0") {
  CHECK(snorm_from_double(2.0, 9) == 255);
  CHECK(snorm_from_double(-2.0, 9) == -255);
  CHECK(snorm_from_double(std::numeric_limits<double>::infinity(), 9) == 255);
  CHECK(snorm_from_double(-std::numeric_limits<double>::infinity(), 9) == -255);
  CHECK(snorm_from_double(std::numeric_limits<double>::quiet_NaN(), 9) == 0);
  // Exact tie: 0.5 * 255 = 127.5 -> 128 and -128 (sign symmetric).
  CHECK(snorm_from_double(0.5, 9) == 128);
  CHECK(snorm_from_double(-0.5, 9) == -128);
  CHECK(snorm_from_double(std::nextafter(0.5, 0.0), 9) == 127);
  CHECK(snorm_from_double(std::nextafter(-0.5, 0.0), 9) == -127);
}

TEST_CASE("snorm: an 8-bit unorm code enters a 9-bit register unchanged") {
  for (std::uint32_t k = 0; k <= 255; ++k) CHECK(snorm_from_unorm(k, 8, 9) == static_cast<int>(k));
  // Into a 13-bit register (M = 4095 = 255 * 16.06...): exact rational rounding.
  for (std::uint32_t k = 0; k <= 255; ++k) CHECK(snorm_from_unorm(k, 8, 13) == static_cast<int>((2 * k * 4095 + 255) / 510));
}

TEST_CASE("snorm: saturating add at both ends") {
  CHECK(snorm_add_sat(200, 100, 9) == 255);
  CHECK(snorm_add_sat(-200, -100, 9) == -255);
  CHECK(snorm_add_sat(100, -30, 9) == 70);
  for (int a = -255; a <= 255; a += 5)
    for (int b = -255; b <= 255; b += 3) {
      const int s = a + b;
      REQUIRE(snorm_add_sat(a, b, 9) == (s > 255 ? 255 : (s < -255 ? -255 : s)));
    }
}

TEST_CASE("snorm: multiply is round(a*b/M) half away from zero, exhaustive at 9 bits") {
  for (int a = -255; a <= 255; ++a)
    for (int b = -255; b <= 255; ++b) {
      const long long p = static_cast<long long>(a) * b;
      const long long q = (2 * std::llabs(p) + 255) / 510;  // floor(|p|/255 + 1/2)
      REQUIRE(snorm_mul_sat(a, b, 9) == (p < 0 ? -q : q));
    }
  CHECK(snorm_mul_sat(255, 255, 9) == 255);     // 1 * 1 = 1
  CHECK(snorm_mul_sat(-255, 255, 9) == -255);   // -1 * 1 = -1
  CHECK(snorm_mul_sat(-255, -255, 9) == 255);   // -1 * -1 = 1
  CHECK(snorm_mul_sat(1, 1, 9) == 0);           // 1/65025 rounds to 0
  // Sign symmetry: (-a)*b == -(a*b) for every pair (the reason for half-away ties).
  for (int a = 0; a <= 255; ++a)
    for (int b = 0; b <= 255; b += 17) CHECK(snorm_mul_sat(-a, b, 9) == -snorm_mul_sat(a, b, 9));
}

TEST_CASE("snorm: the Snorm value type forwards to the same arithmetic") {
  const Snorm a{200, 9}, b{100, 9};
  CHECK((a + b).code == 255);
  CHECK((a * b).code == snorm_mul_sat(200, 100, 9));
  CHECK((-a).code == -200);
  CHECK(Snorm::from_double(-0.5, 9).code == -128);
  CHECK(a.value() == doctest::Approx(200.0 / 255.0));
}

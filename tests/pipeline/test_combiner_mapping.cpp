// Input mappings (RC Table NV_register_combiners.4) in the fixed-point register
// representation, against the table's formulas on exact rationals.
#include <doctest/doctest.h>

#include "combiner_test_support.h"
#include "pipeline/combiners/input_mapping.h"

using namespace ffsim;
using namespace ffsim::combiners;
using ffsim::test::Q;

TEST_CASE("combiner mapping: all eight mappings over every signed 9-bit code are exact") {
  // Codes -255..255 include the 256 unsigned codes 0..255 an 8-bit texel or colour
  // enters as. Expected: the table formula on the rational e = c/255; the
  // implementation's result is an integer in units of 1/510.
  const std::int32_t M = 255;
  for (GLenum gm : test::kMappings) {
    const MappingCoeffs k = mapping_coeffs(mapping_from_gl(gm), M);
    for (std::int32_t c = -M; c <= M; ++c) {
      const Q expected = test::spec_mapping(gm, Q(c, M));
      const Q got(map_fixed(k, c), 2 * M);
      if (!(got == expected)) FAIL_CHECK("mapping " << gm << " code " << c << ": got " << got.n << "/" << got.d);
    }
  }
}

TEST_CASE("combiner mapping: exact at other register widths (rgba10, rgba12, 17 bits)") {
  for (std::int32_t M : {1023, 4095, 65535}) {
    for (GLenum gm : test::kMappings) {
      const MappingCoeffs k = mapping_coeffs(mapping_from_gl(gm), M);
      for (std::int32_t c : {-M, -M + 1, -1, 0, 1, M / 2, M / 2 + 1, M - 1, M}) {
        CHECK(Q(map_fixed(k, c), 2 * M) == test::spec_mapping(gm, Q(c, M)));
      }
    }
  }
}

TEST_CASE("combiner mapping: hand values of spec-notes 7.5 for 8-bit codes") {
  const std::int32_t M = 255;
  auto map = [&](GLenum m, std::int32_t c) { return Q(map_fixed(mapping_coeffs(mapping_from_gl(m), M), c), 510); };
  // EXPAND_NORMAL: 0 -> -1, 127 -> -1/255, 128 -> +1/255, 255 -> +1; no code expands to 0.
  CHECK(map(gl::EXPAND_NORMAL_NV, 0) == Q(-1));
  CHECK(map(gl::EXPAND_NORMAL_NV, 127) == Q(-1, 255));
  CHECK(map(gl::EXPAND_NORMAL_NV, 128) == Q(1, 255));
  CHECK(map(gl::EXPAND_NORMAL_NV, 255) == Q(1));
  // HALF_BIAS_NORMAL of 128 is 1/510, half a register step.
  CHECK(map(gl::HALF_BIAS_NORMAL_NV, 128) == Q(1, 510));
  CHECK(map(gl::HALF_BIAS_NEGATE_NV, 0) == Q(1, 2));
  // Negative registers: non-SIGNED mappings clamp to 0 first.
  CHECK(map(gl::EXPAND_NORMAL_NV, -200) == Q(-1));
  CHECK(map(gl::UNSIGNED_INVERT_NV, -200) == Q(1));
  CHECK(map(gl::SIGNED_NEGATE_NV, -200) == Q(200, 255));
}

TEST_CASE("combiner mapping: float formulas at the table's points") {
  for (GLenum gm : test::kMappings) {
    for (int c = -4; c <= 4; ++c) {  // e in {-1, -3/4, ..., 1}: exact in binary32 and binary64
      const Q e(c, 4);
      const double expected = test::spec_mapping(gm, e).value();
      CHECK(map_float<double>(mapping_from_gl(gm), e.value()) == expected);
      CHECK(map_float<float>(mapping_from_gl(gm), static_cast<float>(e.value())) == static_cast<float>(expected));
    }
  }
}

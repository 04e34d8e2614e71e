// Logic op (GL121 §4.1.8), dithering rule and masked writes (§4.1.7, §4.2.2;
// docs/numerics.md §9.6-9.7). Expected values are the truth tables and closed forms.
#include <doctest/doctest.h>

#include <cmath>

#include "fragment_harness.h"
#include "pipeline/fragment/logic_op.h"
#include "pipeline/fragment/write_mask.h"

using namespace ffsim;
using namespace ffsim::test;

TEST_CASE("logic op: the 16 functions on s = 1100, d = 1010 (4-bit codes)") {
  // GL121 Table 4.3 evaluated by hand on the four (s, d) bit pairs (1,1), (1,0), (0,1), (0,0).
  struct Row { GLenum op; std::uint32_t want; };
  const Row rows[] = {
      {gl::CLEAR, 0b0000},        {gl::AND, 0b1000},         {gl::AND_REVERSE, 0b0100}, {gl::COPY, 0b1100},
      {gl::AND_INVERTED, 0b0010}, {gl::NOOP, 0b1010},        {gl::XOR, 0b0110},         {gl::OR, 0b1110},
      {gl::NOR, 0b0001},          {gl::EQUIV, 0b1001},       {gl::INVERT, 0b0101},      {gl::OR_REVERSE, 0b1101},
      {gl::COPY_INVERTED, 0b0011}, {gl::OR_INVERTED, 0b1011}, {gl::NAND, 0b0111},        {gl::SET, 0b1111},
  };
  for (const Row& r : rows) {
    CHECK_MESSAGE(logic_op(r.op, 0b1100, 0b1010, 15) == r.want, logic_op_name(r.op));
    CHECK(valid_logic_op(r.op));
  }
  CHECK(!valid_logic_op(gl::CLEAR - 1));
  CHECK(!valid_logic_op(gl::SET + 1));
}

TEST_CASE("logic op replaces blending on fixed colour, per channel under the colour mask") {
  const FragmentSpan sp = span_codes(0, 0, {{0xF0, 0x0F, 0xFF, 0x00}});
  FragmentOpsState s;
  s.logic = {true, gl::XOR};
  s.blend = {true, gl::ONE, gl::ONE, gl::FUNC_ADD, {}};  // skipped while the logic op is on
  s.color_mask = {true, true, true, false};
  Buffers b(target8(1, 1));
  b.codes = {0xFF, 0xFF, 0x0F, 0x55};
  const Buffers out = run_both(s, b, sp);
  CHECK(out.code(0, 0, 0) == 0x0F);
  CHECK(out.code(0, 0, 1) == 0xF0);
  CHECK(out.code(0, 0, 2) == 0xF0);
  CHECK(out.code(0, 0, 3) == 0x55);  // masked
}

TEST_CASE("dithering: identity at equal widths, truncation to a narrower buffer") {
  for (std::uint32_t k = 0; k < 256; ++k) CHECK(dither_code(k, 8, 8) == k);
  // 8 -> 4 bits: floor(k * 15 / 255) = floor(k / 17).
  CHECK(dither_code(255, 8, 4) == 15);
  CHECK(dither_code(136, 8, 4) == 8);  // 136/17 = 8 exactly
  CHECK(dither_code(135, 8, 4) == 7);  // 7.94 truncated, not rounded
  CHECK(dither_code(16, 8, 4) == 0);
  // 16 -> 8 bits: floor(k / 257).
  CHECK(dither_code(65535, 16, 8) == 255);
  CHECK(dither_code(257 * 100 + 256, 16, 8) == 100);
}

TEST_CASE("writes: float stores clamp, float32 rounds to binary32 first") {
  CHECK(store_float_color(1.5, Arithmetic::Float64) == 1.0);
  CHECK(store_float_color(-0.0, Arithmetic::Float64) == 0.0);
  CHECK(!std::signbit(store_float_color(-0.0, Arithmetic::Float64)));
  CHECK(store_float_color(0.1, Arithmetic::Float64) == 0.1);
  CHECK(store_float_color(0.1, Arithmetic::Float32) == static_cast<double>(0.1f));
  // DITHER on or off changes nothing (identity at the buffer width).
  const FragmentSpan sp = span_codes(0, 0, {{1, 2, 3, 4}});
  FragmentOpsState on, off;
  off.dither = false;
  CHECK(run_both(on, Buffers(target8(1, 1)), sp).same(run_both(off, Buffers(target8(1, 1)), sp)));
}

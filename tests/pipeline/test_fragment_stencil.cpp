// Stencil test and operations (GL121 §4.1.4, EXT_stencil_wrap; docs/numerics.md
// §9.3). Expected values are hand derived from the spec's definitions.
#include <doctest/doctest.h>

#include "fragment_harness.h"
#include "pipeline/fragment/stencil.h"

using namespace ffsim;
using namespace ffsim::test;

TEST_CASE("stencil ops at 8 bits: each op on 0, 1, 5, 254, 255 with ref 7") {
  const std::uint32_t olds[] = {0, 1, 5, 254, 255};
  struct Row { GLenum op; std::uint32_t want[5]; };
  const Row rows[] = {
      {gl::KEEP, {0, 1, 5, 254, 255}},
      {gl::ZERO, {0, 0, 0, 0, 0}},
      {gl::REPLACE, {7, 7, 7, 7, 7}},
      {gl::INCR, {1, 2, 6, 255, 255}},        // saturates at 255
      {gl::DECR, {0, 0, 4, 253, 254}},        // saturates at 0
      {gl::INVERT, {255, 254, 250, 1, 0}},    // ~old & 0xff
      {gl::INCR_WRAP, {1, 2, 6, 255, 0}},     // 255 + 1 wraps to 0
      {gl::DECR_WRAP, {255, 0, 4, 253, 254}}, // 0 - 1 wraps to 255
  };
  for (const Row& r : rows)
    for (int i = 0; i < 5; ++i) CHECK_MESSAGE(stencil_op(r.op, olds[i], 7, 255) == r.want[i], stencil_op_name(r.op));
}

TEST_CASE("stencil ops at 3 bits: saturation and wrap at 7, INVERT within 3 bits") {
  CHECK(stencil_op(gl::INCR, 7, 0, 7) == 7);
  CHECK(stencil_op(gl::INCR_WRAP, 7, 0, 7) == 0);
  CHECK(stencil_op(gl::DECR_WRAP, 0, 0, 7) == 7);
  CHECK(stencil_op(gl::INVERT, 5, 0, 7) == 2);
  CHECK(stencil_ref_clamped(300, 7) == 7);
  CHECK(stencil_ref_clamped(-5, 7) == 0);
  CHECK(stencil_ref_clamped(300, 255) == 255);
  CHECK(stencil_ref_clamped(3, 255) == 3);
}

TEST_CASE("stencil write mask: new = (old & ~wm) | (op(old) & wm)") {
  // old 1010'1010, INVERT -> 0101'0101; through wm 0000'1111: 1010'0101.
  CHECK(stencil_write(gl::INVERT, 0xAA, 0, 255, 0x0F) == 0xA5);
  // REPLACE with ref 0x3C through wm 0xF0: (0xAA & 0x0F) | (0x3C & 0xF0) = 0x0A | 0x30 = 0x3A.
  CHECK(stencil_write(gl::REPLACE, 0xAA, 0x3C, 255, 0xF0) == 0x3A);
  // INCR sees the full old value (255 saturates) even if wm hides the high bits.
  CHECK(stencil_write(gl::INCR, 0xFF, 0, 255, 0x0F) == 0xFF);
  CHECK(stencil_write(gl::INCR, 0x0F, 0, 255, 0x0F) == 0x00);  // 0x10 & 0x0F = 0 in the low nibble
  CHECK(stencil_write(gl::ZERO, 0xFF, 0, 255, 0) == 0xFF);     // mask 0 writes nothing
}

TEST_CASE("stencil test: (ref & mask) OP (stored & mask) through a span") {
  // ref 0x13, mask 0x0F: the masked ref is 3. Stored 0x23 (masked 3), 0x14 (4), 0x02 (2).
  const FragmentSpan sp = span_codes(0, 0, {{7, 0, 0, 0}, {7, 0, 0, 0}, {7, 0, 0, 0}});
  struct Row { GLenum f; bool pass[3]; };
  const Row rows[] = {
      {gl::EQUAL, {true, false, false}},   {gl::LESS, {false, true, false}},  // 3 < 4 only
      {gl::GREATER, {false, false, true}}, {gl::NOTEQUAL, {false, true, true}},
      {gl::LEQUAL, {true, true, false}},   {gl::GEQUAL, {true, false, true}},
      {gl::NEVER, {false, false, false}},  {gl::ALWAYS, {true, true, true}},
  };
  for (const Row& r : rows) {
    FragmentOpsState s;
    s.stencil = {true, r.f, 0x13, 0x0F, gl::ZERO, gl::KEEP, gl::INCR};
    Buffers b(target8(3, 1));
    b.stencil = {0x23, 0x14, 0x02};
    const Buffers out = run_both(s, b, sp);
    for (int x = 0; x < 3; ++x) {
      CHECK(out.code(x, 0, 0) == (r.pass[x] ? 7 : 0));
      // Failing fragments get sfail = ZERO, passing ones dppass = INCR (depth test disabled).
      CHECK(out.stencil[x] == (r.pass[x] ? b.stencil[x] + 1 : 0));
    }
  }
}

TEST_CASE("stencil: sfail, dpfail and dppass are chosen by the stencil and depth results") {
  // Fragment z 100 against stored z {50, 100, 200} with LESS: fail, fail, pass.
  // Stencil EQUAL 1 against stored {1, 1, 1} passes; a fourth pixel has stored 0 (fails).
  const FragmentSpan sp = span_codes(0, 0, {{1, 1, 1, 1}, {1, 1, 1, 1}, {1, 1, 1, 1}, {1, 1, 1, 1}}, {100, 100, 100, 100});
  FragmentOpsState s;
  s.stencil = {true, gl::EQUAL, 1, 0xFF, gl::INVERT, gl::INCR, gl::REPLACE};
  s.stencil.ref = 1;
  s.depth = {true, gl::LESS};
  Buffers b(target8(4, 1));
  b.stencil = {1, 1, 1, 0};
  b.depth = {50, 100, 200, 300};
  Buffers out = run_both(s, b, sp);
  CHECK(out.stencil[0] == 2);    // depth fail: INCR
  CHECK(out.stencil[1] == 2);    // depth fail (100 < 100 false): INCR
  CHECK(out.stencil[2] == 1);    // pass: REPLACE with ref 1
  CHECK(out.stencil[3] == 255);  // stencil fail: INVERT of 0
  CHECK(out.depth[2] == 100);    // depth written where both pass
  CHECK(out.depth[3] == 300);    // stencil fail: no depth write
  CHECK(out.code(2, 0, 0) == 1);
  CHECK(out.code(0, 0, 0) == 0);
  // Depth test disabled: the dppass op applies to every stencil-passing fragment.
  s.depth.enabled = false;
  out = run_both(s, b, sp);
  CHECK(out.stencil[0] == 1);
  CHECK(out.stencil[1] == 1);
  CHECK(out.stencil[3] == 255);
  CHECK(out.depth == b.depth);  // depth test disabled: no depth write
}

TEST_CASE("stencil: REPLACE writes the clamped reference, not masked by the value mask") {
  const FragmentSpan sp = span_codes(0, 0, {{0, 0, 0, 0}});
  FragmentOpsState s;
  s.stencil = {true, gl::ALWAYS, 1000, 0x0F, gl::KEEP, gl::KEEP, gl::REPLACE};
  Buffers out = run_both(s, Buffers(target8(1, 1)), sp);
  CHECK(out.stencil[0] == 255);  // 1000 clamped to 2^8 - 1
  Buffers b3(target8(1, 1, 3));
  out = run_both(s, b3, sp);
  CHECK(out.stencil[0] == 7);    // 3-bit buffer: clamped to 7
  s.stencil_writemask = 0x3;
  out = run_both(s, b3, sp);
  CHECK(out.stencil[0] == 3);    // through the write mask
}

TEST_CASE("stencil: no stencil buffer means the test passes and nothing is written") {
  const FragmentSpan sp = span_codes(0, 0, {{5, 5, 5, 5}});
  FragmentOpsState s;
  s.stencil = {true, gl::NEVER, 0, 0xFF, gl::ZERO, gl::ZERO, gl::ZERO};
  const Buffers out = run_both(s, Buffers(target8(1, 1, 0)), sp);
  CHECK(out.code(0, 0, 0) == 5);
}

TEST_CASE("paper hard shadows: alpha EQUAL 0 then stencil INCR marks shadowed pixels, stencil EQUAL 0 draws lit ones") {
  // §4.1.5 steps 12-16: CopyPixels of the alpha channel {0, 3, 0, 255} with the alpha
  // test EQUAL 0 and stencil op INCR (stencil func ALWAYS) sets stencil 1 where A = 0.
  const FragmentSpan copy = span_codes(0, 0, {{0, 0, 0, 0}, {0, 0, 0, 3}, {0, 0, 0, 0}, {0, 0, 0, 255}}, {0, 0, 0, 0});
  FragmentOpsState s;
  s.alpha = {true, gl::EQUAL, 0.0};
  s.stencil = {true, gl::ALWAYS, 0, 0xFF, gl::KEEP, gl::KEEP, gl::INCR};
  Buffers b = run_both(s, Buffers(target8(4, 1)), copy);
  CHECK(b.stencil == std::vector<std::uint8_t>{1, 0, 1, 0});
  // Step 16-17: alpha test off, stencil EQUAL 0, KEEP: the bump map is drawn on lit pixels only.
  s.alpha.enabled = false;
  s.stencil = {true, gl::EQUAL, 0, 0xFF, gl::KEEP, gl::KEEP, gl::KEEP};
  const FragmentSpan bump = span_codes(0, 0, {{200, 100, 50, 255}, {200, 100, 50, 255}, {200, 100, 50, 255}, {200, 100, 50, 255}});
  b = run_both(s, b, bump);
  CHECK(b.code(0, 0, 0) == 0);
  CHECK(b.code(1, 0, 0) == 200);
  CHECK(b.code(2, 0, 0) == 0);
  CHECK(b.code(3, 0, 0) == 200);
}

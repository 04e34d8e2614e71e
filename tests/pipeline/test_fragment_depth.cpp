// Depth test, depth mask and the scissor test (GL121 §4.1.2, §4.1.5, §4.2.2;
// docs/numerics.md §9.4). Expected values hand derived from "z OP stored".
#include <doctest/doctest.h>

#include <stdexcept>

#include "fragment_harness.h"

using namespace ffsim;
using namespace ffsim::test;

TEST_CASE("depth test: each function on z = stored - 1, stored, stored + 1") {
  struct Row { GLenum f; bool pass[3]; };
  const Row rows[] = {
      {gl::NEVER, {false, false, false}}, {gl::LESS, {true, false, false}},    {gl::EQUAL, {false, true, false}},
      {gl::LEQUAL, {true, true, false}},  {gl::GREATER, {false, false, true}}, {gl::NOTEQUAL, {true, false, true}},
      {gl::GEQUAL, {false, true, true}},  {gl::ALWAYS, {true, true, true}},
  };
  const FragmentSpan sp = span_codes(0, 0, {{1, 2, 3, 4}, {1, 2, 3, 4}, {1, 2, 3, 4}}, {999, 1000, 1001});
  for (const Row& r : rows)
    for (bool mask : {true, false}) {
      FragmentOpsState s;
      s.depth = {true, r.f};
      s.depth_mask = mask;
      Buffers b(target8(3, 1));
      b.depth = {1000, 1000, 1000};
      const Buffers out = run_both(s, b, sp);
      for (int x = 0; x < 3; ++x) {
        CHECK(out.code(x, 0, 3) == (r.pass[x] ? 4 : 0));
        CHECK(out.depth[x] == (r.pass[x] && mask ? sp.depth[x] : 1000u));
      }
    }
}

TEST_CASE("depth test disabled: no comparison and no depth write") {
  const FragmentSpan sp = span_codes(0, 0, {{1, 1, 1, 1}}, {5});
  FragmentOpsState s;  // depth test disabled, depth mask true
  Buffers b(target8(1, 1));
  b.depth = {0};
  const Buffers out = run_both(s, b, sp);
  CHECK(out.code(0, 0, 0) == 1);
  CHECK(out.depth[0] == 0);
}

TEST_CASE("depth test without a depth buffer passes everything") {
  const FragmentSpan sp = span_codes(0, 0, {{1, 1, 1, 1}}, {5});
  FragmentOpsState s;
  s.depth = {true, gl::NEVER};
  const Buffers out = run_both(s, Buffers(target8(1, 1, 8, 0)), sp);
  CHECK(out.code(0, 0, 0) == 1);
}

TEST_CASE("depth test: a span without depth is an error when the test is on") {
  const FragmentSpan sp = span_codes(0, 0, {{1, 1, 1, 1}});
  FragmentOpsState s;
  s.depth = {true, gl::LESS};
  Buffers b(target8(1, 1));
  CHECK_THROWS_AS(run_plan(s, b, sp), std::invalid_argument);
  CHECK_THROWS_AS(run_full(s, b, sp), std::invalid_argument);
}

TEST_CASE("scissor and pixel ownership cut spans to the window and the box") {
  // 8x4 window; scissor box x 2..5, y 1..2. A span on row 1 from x = -3 to 10.
  std::vector<std::array<std::uint16_t, 4>> frags(14, {9, 9, 9, 9});
  FragmentOpsState s;
  s.scissor = {true, 2, 1, 4, 2};
  Buffers out = run_both(s, Buffers(target8(8, 4)), span_codes(1, -3, frags));
  for (int x = 0; x < 8; ++x) CHECK(out.code(x, 1, 0) == (x >= 2 && x < 6 ? 9 : 0));
  // Row 3 is outside the box: nothing written.
  out = run_both(s, Buffers(target8(8, 4)), span_codes(3, 0, frags));
  for (int x = 0; x < 8; ++x) CHECK(out.code(x, 3, 0) == 0);
  // Scissor off: only ownership (the window) clips.
  s.scissor.enabled = false;
  out = run_both(s, Buffers(target8(8, 4)), span_codes(1, -3, frags));
  for (int x = 0; x < 8; ++x) CHECK(out.code(x, 1, 0) == 9);
  // Rows outside the window and spans entirely left or right of it write nothing.
  const Buffers empty(target8(8, 4));
  CHECK(run_both(s, empty, span_codes(-1, 0, frags)).same(empty));
  CHECK(run_both(s, empty, span_codes(4, 0, frags)).same(empty));
  CHECK(run_both(s, empty, span_codes(0, -20, frags)).same(empty));
  CHECK(run_both(s, empty, span_codes(0, 8, frags)).same(empty));
  // A scissor box reaching past the int range is clipped, not overflowed.
  s.scissor = {true, 2147483000, 0, 2147483647, 10};
  CHECK(run_both(s, empty, span_codes(0, 0, frags)).same(empty));
  s.scissor = {true, -2147483647, 0, 2147483647, 10};
  out = run_both(s, empty, span_codes(0, 0, frags));
  for (int x = 0; x < 8; ++x) CHECK(out.code(x, 0, 0) == 0);  // box ends at x = 0 (exclusive)
}

// Comparison functions and the alpha test (GL121 §4.1.3; docs/numerics.md §9.2).
// Expected values are hand derived from the spec's "A_s OP ref" and the reference
// conversion k = floor(ref * (2^m - 1) + 1/2).
#include <doctest/doctest.h>

#include <cmath>

#include "fragment_harness.h"
#include "pipeline/fragment/alpha_test.h"
#include "pipeline/fragment/test_func.h"

using namespace ffsim;
using namespace ffsim::test;

namespace {
constexpr GLenum kFuncs[] = {gl::NEVER, gl::LESS, gl::EQUAL, gl::LEQUAL, gl::GREATER, gl::NOTEQUAL, gl::GEQUAL, gl::ALWAYS};
}

TEST_CASE("test functions: all eight on a < b, a == b, a > b") {
  // Rows: the spec's definitions (§4.1.3 wording shared by §4.1.4 and §4.1.5).
  struct Row { GLenum f; bool lt, eq, gt; };
  const Row rows[] = {
      {gl::NEVER, false, false, false}, {gl::LESS, true, false, false},    {gl::EQUAL, false, true, false},
      {gl::LEQUAL, true, true, false},  {gl::GREATER, false, false, true}, {gl::NOTEQUAL, true, false, true},
      {gl::GEQUAL, false, true, true},  {gl::ALWAYS, true, true, true},
  };
  for (const Row& r : rows) {
    CHECK(test_func<int>(r.f, 1, 2) == r.lt);
    CHECK(test_func<int>(r.f, 2, 2) == r.eq);
    CHECK(test_func<int>(r.f, 3, 2) == r.gt);
    CHECK(valid_test_func(r.f));
  }
  CHECK(!valid_test_func(gl::NEVER - 1));
  CHECK(!valid_test_func(gl::ALWAYS + 1));
}

TEST_CASE("alpha test: reference converted like an A component, round half up") {
  CHECK(alpha_ref_code(0.0, 8) == 0);
  CHECK(alpha_ref_code(1.0, 8) == 255);
  CHECK(alpha_ref_code(0.5, 8) == 128);   // 127.5 -> 128 (half up, choice #30)
  CHECK(alpha_ref_code(-0.25, 8) == 0);   // clamped to [0,1]
  CHECK(alpha_ref_code(7.0, 8) == 255);
  CHECK(alpha_ref_code(1.0 / 255.0, 8) == 1);
  CHECK(alpha_ref_code(0.25, 8) == 64);   // 63.75 -> 64
  CHECK(alpha_ref_code(0.5, 10) == 512);  // 511.5 -> 512
  CHECK(alpha_ref_code(0.5, 4) == 8);     // 7.5 -> 8
  CHECK(alpha_ref_value(0.1, Arithmetic::Float64) == 0.1);
  CHECK(alpha_ref_value(0.1, Arithmetic::Float32) == static_cast<double>(0.1f));
  CHECK(alpha_ref_value(2.0, Arithmetic::Float32) == 1.0);
}

TEST_CASE("alpha test: each function over all 256 alpha codes with ref 0.5 (code 128)") {
  // Pass counts by hand for A in 0..255 against 128: LESS 0..127 (128), LEQUAL 129, EQUAL 1,
  // GREATER 129..255 (127), GEQUAL 128, NOTEQUAL 255, NEVER 0, ALWAYS 256.
  struct Row { GLenum f; int passing; };
  const Row rows[] = {{gl::NEVER, 0},     {gl::LESS, 128},     {gl::EQUAL, 1},   {gl::LEQUAL, 129},
                      {gl::GREATER, 127}, {gl::NOTEQUAL, 255}, {gl::GEQUAL, 128}, {gl::ALWAYS, 256}};
  std::vector<std::array<std::uint16_t, 4>> frags;
  for (std::uint16_t a = 0; a < 256; ++a) frags.push_back({255, 0, 0, a});
  const FragmentSpan sp = span_codes(0, 0, frags);
  for (const Row& r : rows) {
    FragmentOpsState s;
    s.alpha = {true, r.f, 0.5};
    s.color_mask = {true, false, false, false};  // R marks the fragments that passed
    const Buffers out = run_both(s, Buffers(target8(256, 1)), sp);
    int passing = 0;
    for (int x = 0; x < 256; ++x) {
      const bool passed = out.code(x, 0, 0) == 255;
      passing += passed;
      CHECK(passed == test_func<int>(r.f, x, 128));
    }
    CHECK_MESSAGE(passing == r.passing, test_func_symbol(r.f));
  }
}

TEST_CASE("alpha test: the paper's EQUAL 0 and GREATER 0 on quantised alpha") {
  // Paper §4.1.5 step 12: pass where alpha equals 0 (in shadow). GREATER 0 passes iff A >= 1/255.
  const FragmentSpan sp = span_codes(0, 0, {{9, 9, 9, 0}, {9, 9, 9, 1}, {9, 9, 9, 128}, {9, 9, 9, 255}});
  FragmentOpsState s;
  s.alpha = {true, gl::EQUAL, 0.0};
  Buffers out = run_both(s, Buffers(target8(4, 1)), sp);
  CHECK(out.code(0, 0, 0) == 9);
  CHECK(out.code(1, 0, 0) == 0);
  CHECK(out.code(2, 0, 0) == 0);
  CHECK(out.code(3, 0, 0) == 0);
  s.alpha = {true, gl::GREATER, 0.0};
  out = run_both(s, Buffers(target8(4, 1)), sp);
  CHECK(out.code(0, 0, 0) == 0);
  CHECK(out.code(1, 0, 0) == 9);
  CHECK(out.code(3, 0, 0) == 9);
  // A reference just below 1/255 * 1/2 rounds to code 0, so EQUAL keeps only A = 0.
  s.alpha = {true, gl::EQUAL, 0.4 / 255.0};
  out = run_both(s, Buffers(target8(4, 1)), sp);
  CHECK(out.code(0, 0, 0) == 9);
  CHECK(out.code(1, 0, 0) == 0);
}

TEST_CASE("alpha test: float profiles compare values, float32 after rounding both to binary32") {
  for (Arithmetic a : {Arithmetic::Float64, Arithmetic::Float32}) {
    const FragmentTarget t{3, 1, a, 8, 8, 24};
    FragmentSpan sp;
    sp.count = 3;
    const double half_up = std::nextafter(0.5, 1.0);  // rounds to 0.5f in binary32
    sp.values = {1, 1, 1, 0.5, 1, 1, 1, half_up, 1, 1, 1, 0.25};
    FragmentOpsState s;
    s.alpha = {true, gl::EQUAL, 0.5};
    const Buffers out = run_both(s, Buffers(t), sp);
    CHECK(out.values[0] == 1.0);
    CHECK(out.values[4] == (a == Arithmetic::Float32 ? 1.0 : 0.0));  // equal only after binary32 rounding
    CHECK(out.values[8] == 0.0);
  }
}

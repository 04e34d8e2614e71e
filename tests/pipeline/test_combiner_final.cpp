// The final combiner (RC §3.8.12.3) in fixed point (9-bit registers, 8-bit
// framebuffer) against the spec formula on exact rationals, rounded once half up
// to the colour width: fcoc.rgb = min(A*B + (1-A)*C + D, 1), fcoc.a = G.
#include <doctest/doctest.h>

#include "combiner_test_support.h"
#include "pipeline/combiners/final_combiner.h"

using namespace ffsim;
using namespace ffsim::combiners;
using ffsim::test::Q;

namespace {

constexpr std::int32_t M = 255;

PlannedFinal final_of(const CombinerState& s) { return plan_combiners(s, test::geforce_config(), false).final; }

void set_final(CombinerState& s, int v, GLenum input, GLenum mapping = gl::UNSIGNED_IDENTITY_NV,
               GLenum usage = gl::RGB) {
  REQUIRE(check_final_combiner_input(gl::VARIABLE_A_NV + static_cast<GLenum>(v), input, mapping, usage, 2));
  s.final_var[static_cast<std::size_t>(v)] = VariableState{input, mapping, usage};
}

std::array<std::uint16_t, 4> run(const PlannedFinal& f, const RegisterSet<std::int32_t>& r) {
  std::array<std::uint16_t, 4> out{};
  final_combiner_fixed<std::int64_t>(f, r, M, 8, out.data());
  return out;
}

std::int64_t fb(Q x) { return test::round_up(test::qmin(x, Q(1)), 255); }

}  // namespace

TEST_CASE("final combiner: A in {0, 1/2, 1} and edge codes, every B and C code, D zero and non-zero") {
  for (GLenum a_map : {gl::UNSIGNED_IDENTITY_NV, gl::UNSIGNED_INVERT_NV}) {
    CombinerState s;
    set_final(s, 0, gl::TEXTURE0, a_map);
    set_final(s, 1, gl::TEXTURE1);
    set_final(s, 2, gl::PRIMARY_COLOR_NV);
    set_final(s, 3, gl::SECONDARY_COLOR_NV);
    const PlannedFinal f = final_of(s);
    // 0, "1/2" (128/255, the 8-bit code of 0.5 by choice #36), 1, and the edges 1, 127, 254;
    // -255 and -1 (negative registers: max(0,x) makes them 0, UNSIGNED_INVERT makes them 1).
    for (std::int32_t a : {0, 128, 255, 1, 127, 254, -1, -255}) {
      const Q qa = test::spec_mapping(a_map, Q(a, M));
      for (std::int32_t d : {0, 1, 100, 255}) {
        for (std::int32_t b = 0; b < 256; b += 3)
          for (std::int32_t c = 0; c < 256; c += 5) {
            RegisterSet<std::int32_t> r{};
            for (int k = 0; k < 3; ++k) {
              r.v[kTexture0][k] = a;
              r.v[kTexture1][k] = b;
              r.v[kPrimaryColor][k] = c;
              r.v[kSecondaryColor][k] = d;
            }
            const Q x = qa * Q(b, M) + (Q(1) - qa) * Q(c, M) + Q(d, M);
            const auto out = run(f, r);
            if (out[0] != fb(x) || out[2] != fb(x))
              FAIL_CHECK("a=" << a << " b=" << b << " c=" << c << " d=" << d << " got " << out[0]);
          }
      }
    }
  }
}

TEST_CASE("final combiner: COLOR_SUM_CLAMP on and off") {
  for (bool clamp : {true, false}) {
    CombinerState s;
    s.color_sum_clamp = clamp;
    set_final(s, 0, gl::TEXTURE0);
    set_final(s, 1, gl::SPARE0_PLUS_SECONDARY_COLOR_NV);
    set_final(s, 2, gl::ZERO);
    const PlannedFinal f = final_of(s);
    int clamped = 0;
    for (std::int32_t a : {0, 64, 128, 200, 255})
      for (std::int32_t sp = -255; sp <= 255; sp += 17)
        for (std::int32_t sec = 0; sec <= 255; sec += 15) {
          RegisterSet<std::int32_t> r{};
          for (int k = 0; k < 3; ++k) {
            r.v[kTexture0][k] = a;
            r.v[kSpare0][k] = sp;
            r.v[kSecondaryColor][k] = sec;
          }
          Q sum = test::qmax(Q(0), Q(sp, M)) + Q(sec, M);
          if (clamp && Q(1) < sum) sum = Q(1), ++clamped;
          CHECK(run(f, r)[1] == fb(Q(a, M) * sum));
        }
    CHECK((clamped > 0) == clamp);
  }
  // The hand example: A = 128/255, spare0 = 200, secondary = 180 (sum 380/255).
  CombinerState s;
  set_final(s, 0, gl::TEXTURE0);
  set_final(s, 1, gl::SPARE0_PLUS_SECONDARY_COLOR_NV);
  set_final(s, 2, gl::ZERO);
  RegisterSet<std::int32_t> r{};
  for (int k = 0; k < 3; ++k) r.v[kTexture0][k] = 128, r.v[kSpare0][k] = 200, r.v[kSecondaryColor][k] = 180;
  CHECK(run(final_of(s), r)[0] == 128);  // clamped: 128/255 * 1
  s.color_sum_clamp = false;
  CHECK(run(final_of(s), r)[0] == 191);  // 128 * 380 / 255 = 190.745 -> 191
}

TEST_CASE("final combiner: E_TIMES_F in A and D, G with ALPHA and BLUE usage and UNSIGNED_INVERT") {
  CombinerState s;
  set_final(s, 0, gl::E_TIMES_F_NV);
  set_final(s, 1, gl::CONSTANT_COLOR0_NV);
  set_final(s, 2, gl::ZERO, gl::UNSIGNED_INVERT_NV);  // C = 1
  set_final(s, 3, gl::E_TIMES_F_NV, gl::UNSIGNED_INVERT_NV);
  set_final(s, 4, gl::TEXTURE0);
  set_final(s, 5, gl::TEXTURE1, gl::UNSIGNED_INVERT_NV);
  set_final(s, 6, gl::SPARE1_NV, gl::UNSIGNED_INVERT_NV, gl::BLUE);
  const PlannedFinal f = final_of(s);
  for (std::int32_t e = 0; e < 256; e += 7)
    for (std::int32_t fv = 0; fv < 256; fv += 11)
      for (std::int32_t k0 : {0, 77, 255}) {
        RegisterSet<std::int32_t> r{};
        for (int k = 0; k < 3; ++k) r.v[kTexture0][k] = e, r.v[kTexture1][k] = fv, r.v[kConstantColor0][k] = k0;
        r.v[kSpare1][2] = e - 128;
        const Q ef = Q(e, M) * (Q(1) - Q(fv, M));
        const Q x = ef * Q(k0, M) + (Q(1) - ef) * Q(1) + (Q(1) - ef);
        const auto out = run(f, r);
        CHECK(out[0] == fb(x));
        CHECK(out[3] == fb(test::spec_mapping(gl::UNSIGNED_INVERT_NV, Q(e - 128, M))));
      }
}

TEST_CASE("final combiner: sums up to 3 clamp at 1 and the GeForce 256 above-2 case is flagged") {
  CombinerState s;
  s.color_sum_clamp = false;
  set_final(s, 0, gl::ZERO, gl::UNSIGNED_INVERT_NV);  // A = 1
  set_final(s, 1, gl::SPARE0_PLUS_SECONDARY_COLOR_NV);
  set_final(s, 3, gl::SPARE0_PLUS_SECONDARY_COLOR_NV);
  const CombinerPlan p = plan_combiners(s, test::geforce_config());
  CHECK(p.final_may_exceed_two);
  RegisterSet<std::int32_t> r{};
  for (int k = 0; k < 3; ++k) r.v[kSpare0][k] = 255, r.v[kSecondaryColor][k] = 255;
  CHECK(run(p.final, r)[0] == 255);
  s.color_sum_clamp = true;
  CHECK_FALSE(plan_combiners(s, test::geforce_config()).final_may_exceed_two);
  CHECK_FALSE(plan_combiners(CombinerState{}, test::geforce_config()).final_may_exceed_two);
}

TEST_CASE("final combiner: float path is the formula with min(.,1) only") {
  CombinerState s;
  s.color_sum_clamp = false;
  set_final(s, 0, gl::TEXTURE0);
  set_final(s, 1, gl::SPARE0_PLUS_SECONDARY_COLOR_NV);
  set_final(s, 2, gl::TEXTURE1);
  set_final(s, 3, gl::ZERO);
  CombinerConfig cfg = test::geforce_config();
  cfg.arithmetic = Arithmetic::Float64;
  const PlannedFinal f = plan_combiners(s, cfg, false).final;
  RegisterSet<double> r{};
  for (int k = 0; k < 4; ++k) r.v[kTexture0][k] = 0.5, r.v[kTexture1][k] = 0.25, r.v[kSpare0][k] = 0.75,
                              r.v[kSecondaryColor][k] = 0.5;
  double out[4];
  final_combiner_float<double>(f, r, out);
  CHECK(out[0] == 0.5 * 1.25 + 0.5 * 0.25);  // 0.75: the unclamped colour sum 1.25 is kept
}

TEST_CASE("final combiner: the 128-bit accumulator agrees with 64 bits where both fit") {
  CombinerState s;
  set_final(s, 0, gl::E_TIMES_F_NV);
  set_final(s, 1, gl::TEXTURE0);
  set_final(s, 2, gl::SPARE0_PLUS_SECONDARY_COLOR_NV);
  set_final(s, 3, gl::TEXTURE1, gl::UNSIGNED_INVERT_NV);
  set_final(s, 4, gl::TEXTURE1);
  set_final(s, 5, gl::PRIMARY_COLOR_NV);
  const PlannedFinal f = final_of(s);
  CHECK_FALSE(final_needs_int128(255, 8));
  CHECK(final_needs_int128(65535, 16));
  for (std::int32_t v = -255; v <= 255; v += 3) {
    RegisterSet<std::int32_t> r{};
    for (int k = 0; k < 4; ++k) {
      r.v[kTexture0][k] = v;
      r.v[kTexture1][k] = (v * 3 + 400) % 256;
      r.v[kPrimaryColor][k] = (v * 7 + 1000) % 256;
      r.v[kSpare0][k] = -v;
      r.v[kSecondaryColor][k] = (v + 255) / 2;
    }
    std::uint16_t a[4], b[4];
    final_combiner_fixed<std::int64_t>(f, r, M, 8, a);
    final_combiner_fixed<Int128>(f, r, M, 8, b);
    for (int k = 0; k < 4; ++k) CHECK(a[k] == b[k]);
  }
}

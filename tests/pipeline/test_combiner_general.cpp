// General combiner stages (RC §3.8.12.2) in fixed point (geforce256: 9-bit
// registers, value = code/255) and in floating point. Expected values are the
// spec's formulas evaluated on exact rationals in the test, rounded once to the
// register grid half away from zero (docs/numerics.md §10, choice #22).
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "combiner_test_support.h"
#include "pipeline/combiners/general_combiner.h"

using namespace ffsim;
using namespace ffsim::combiners;
using ffsim::test::Q;

namespace {

constexpr std::int32_t M = 255;

PlannedStage stage0(const CombinerState& s, CombinerRounding r = CombinerRounding::PerStage) {
  CombinerConfig cfg = test::geforce_config();
  cfg.rounding = r;
  return plan_combiners(s, cfg, false).stages[0];
}

RegisterSet<std::int32_t> zero_regs() {
  RegisterSet<std::int32_t> r{};
  return r;
}

void set_var(PortionState& p, int v, GLenum input, GLenum mapping, GLenum usage) {
  p.var[static_cast<std::size_t>(v)] = VariableState{input, mapping, usage};
}

// A stage whose AB = A (B = 1) and CD = C (D = 1) in both portions.
CombinerState pass_through(GLenum a, GLenum a_map, GLenum c, GLenum c_map) {
  CombinerState s;
  for (int portion = 0; portion < 2; ++portion) {
    PortionState& p = portion == 0 ? s.stages[0].rgb : s.stages[0].alpha;
    const GLenum u = portion == 0 ? gl::RGB : gl::ALPHA;
    set_var(p, 0, a, a_map, u);
    set_var(p, 1, gl::ZERO, gl::UNSIGNED_INVERT_NV, u);
    set_var(p, 2, c, c_map, u);
    set_var(p, 3, gl::ZERO, gl::UNSIGNED_INVERT_NV, u);
    p.ab_output = gl::DISCARD_NV;
    p.cd_output = gl::DISCARD_NV;
    p.sum_output = gl::DISCARD_NV;
  }
  return s;
}

struct ScaleBias {
  GLenum scale, bias;
  Q s, b;
};
constexpr GLenum kNone = gl::NONE;
const ScaleBias kLegal[] = {
    {kNone, kNone, Q(1), Q(0)},
    {gl::SCALE_BY_TWO_NV, kNone, Q(2), Q(0)},
    {gl::SCALE_BY_FOUR_NV, kNone, Q(4), Q(0)},
    {gl::SCALE_BY_ONE_HALF_NV, kNone, Q(1, 2), Q(0)},
    {kNone, gl::BIAS_BY_NEGATIVE_ONE_HALF_NV, Q(1), Q(-1, 2)},
    {gl::SCALE_BY_TWO_NV, gl::BIAS_BY_NEGATIVE_ONE_HALF_NV, Q(2), Q(-1, 2)},
};

std::int32_t expected_out(Q x, const ScaleBias& sb) {
  return static_cast<std::int32_t>(test::round_away(test::qclamp((x + sb.b) * sb.s, Q(-1), Q(1)), M));
}

}  // namespace

TEST_CASE("general combiner: every legal scale/bias on every signed code, AB, CD and SUM, both portions") {
  for (const ScaleBias& sb : kLegal) {
    CombinerState s = pass_through(gl::TEXTURE0, gl::SIGNED_IDENTITY_NV, gl::TEXTURE1, gl::SIGNED_IDENTITY_NV);
    for (PortionState* p : {&s.stages[0].rgb, &s.stages[0].alpha}) {
      p->ab_output = gl::SPARE0_NV;
      p->cd_output = gl::SPARE1_NV;
      p->sum_output = gl::PRIMARY_COLOR_NV;
      p->scale = sb.scale;
      p->bias = sb.bias;
    }
    REQUIRE(check_combiner_output(gl::RGB, gl::SPARE0_NV, gl::SPARE1_NV, gl::PRIMARY_COLOR_NV, sb.scale, sb.bias,
                                  false, false, 2));
    const PlannedStage st = stage0(s);
    for (std::int32_t c = -M; c <= M; ++c) {
      const std::int32_t d = (c * 7 + 300) % (2 * M + 1) - M;  // a second code walking the range differently
      RegisterSet<std::int32_t> r = zero_regs();
      for (int k = 0; k < 4; ++k) r.v[kTexture0][k] = c, r.v[kTexture1][k] = d;
      general_combiner_fixed(st, r, M, false);
      const Q qc(c, M), qd(d, M);
      for (int k = 0; k < 4; ++k) {
        CHECK(r.v[kSpare0][k] == expected_out(qc, sb));
        CHECK(r.v[kSpare1][k] == expected_out(qd, sb));
        CHECK(r.v[kPrimaryColor][k] == expected_out(qc + qd, sb));  // sums overflowing [-1,1] clamp
      }
    }
  }
}

TEST_CASE("general combiner: products of every mapped 8-bit code pair round once (sampled pairs, all mappings)") {
  std::mt19937 rng(5);
  for (GLenum ma : test::kMappings)
    for (GLenum mb : test::kMappings) {
      CombinerState s;
      PortionState& p = s.stages[0].rgb;
      set_var(p, 0, gl::TEXTURE0, ma, gl::RGB);
      set_var(p, 1, gl::TEXTURE1, mb, gl::RGB);
      p.ab_output = gl::SPARE1_NV;
      p.sum_output = gl::DISCARD_NV;
      const PlannedStage st = stage0(s);
      for (int n = 0; n < 400; ++n) {
        const std::int32_t a = static_cast<std::int32_t>(rng() % 256), b = static_cast<std::int32_t>(rng() % 256);
        RegisterSet<std::int32_t> r = zero_regs();
        for (int k = 0; k < 3; ++k) r.v[kTexture0][k] = a, r.v[kTexture1][k] = b;
        general_combiner_fixed(st, r, M, false);
        const Q x = test::spec_mapping(ma, Q(a, M)) * test::spec_mapping(mb, Q(b, M));
        CHECK(r.v[kSpare1][0] == test::round_away(test::qclamp(x, Q(-1), Q(1)), M));
      }
    }
}

TEST_CASE("general combiner: illegal scale/bias pairs are refused") {
  for (GLenum scale : {gl::SCALE_BY_FOUR_NV, gl::SCALE_BY_ONE_HALF_NV})
    CHECK(check_combiner_output(gl::RGB, gl::SPARE0_NV, gl::DISCARD_NV, gl::DISCARD_NV, scale,
                                gl::BIAS_BY_NEGATIVE_ONE_HALF_NV, false, false, 2)
              .error == gl::INVALID_OPERATION);
}

TEST_CASE("general combiner: dot products broadcast to R,G,B and leave alpha alone") {
  std::mt19937 rng(7);
  CombinerState s;
  PortionState& p = s.stages[0].rgb;
  set_var(p, 0, gl::TEXTURE0, gl::EXPAND_NORMAL_NV, gl::RGB);
  set_var(p, 1, gl::TEXTURE1, gl::EXPAND_NORMAL_NV, gl::RGB);
  set_var(p, 2, gl::CONSTANT_COLOR0_NV, gl::EXPAND_NORMAL_NV, gl::RGB);
  set_var(p, 3, gl::TEXTURE1, gl::HALF_BIAS_NORMAL_NV, gl::RGB);
  p.ab_output = gl::SPARE0_NV;
  p.cd_output = gl::SPARE1_NV;
  p.sum_output = gl::SECONDARY_COLOR_NV;
  p.ab_dot_product = p.cd_dot_product = true;
  s.stages[0].alpha.sum_output = gl::DISCARD_NV;
  const PlannedStage st = stage0(s);
  for (int n = 0; n < 20000; ++n) {
    std::int32_t t0[3], t1[3], k0[3];
    RegisterSet<std::int32_t> r = zero_regs();
    for (int c = 0; c < 3; ++c) {
      t0[c] = r.v[kTexture0][c] = static_cast<std::int32_t>(rng() % 256);
      t1[c] = r.v[kTexture1][c] = static_cast<std::int32_t>(rng() % 256);
      k0[c] = r.v[kConstantColor0][c] = static_cast<std::int32_t>(rng() % 256);
    }
    r.v[kSpare0][3] = 77;
    r.v[kSpare1][3] = 78;
    general_combiner_fixed(st, r, M, false);
    Q ab(0), cd(0);
    for (int c = 0; c < 3; ++c) {
      ab = ab + test::spec_mapping(gl::EXPAND_NORMAL_NV, Q(t0[c], M)) * test::spec_mapping(gl::EXPAND_NORMAL_NV, Q(t1[c], M));
      cd = cd + test::spec_mapping(gl::EXPAND_NORMAL_NV, Q(k0[c], M)) * test::spec_mapping(gl::HALF_BIAS_NORMAL_NV, Q(t1[c], M));
    }
    const auto want = [](Q x) { return test::round_away(test::qclamp(x, Q(-1), Q(1)), M); };
    for (int c = 0; c < 3; ++c) {
      CHECK(r.v[kSpare0][c] == want(ab));
      CHECK(r.v[kSpare1][c] == want(cd));
      CHECK(r.v[kSecondaryColor][c] == want(ab + cd));  // sum of the two dot products (choice #26)
    }
    CHECK(r.v[kSpare0][3] == 77);
    CHECK(r.v[kSpare1][3] == 78);
  }
}

TEST_CASE("general combiner: mux on spare0 alpha just below, at and just above 1/2") {
  CombinerState s = pass_through(gl::TEXTURE0, gl::UNSIGNED_IDENTITY_NV, gl::TEXTURE1, gl::UNSIGNED_IDENTITY_NV);
  for (PortionState* p : {&s.stages[0].rgb, &s.stages[0].alpha}) {
    p->sum_output = gl::SPARE1_NV;
    p->mux_sum = true;
  }
  // Fixed: 1/2 is not a 9-bit code; 127/255 < 1/2 selects AB, 128/255 >= 1/2 selects CD.
  const PlannedStage st = stage0(s);
  for (auto [a, want_cd] : {std::pair{0, false}, {127, false}, {128, true}, {255, true}}) {
    RegisterSet<std::int32_t> r = zero_regs();
    for (int k = 0; k < 4; ++k) r.v[kTexture0][k] = 10, r.v[kTexture1][k] = 200;
    r.v[kSpare0][3] = a;
    general_combiner_fixed(st, r, M, false);
    for (int k = 0; k < 4; ++k) CHECK(r.v[kSpare1][k] == (want_cd ? 200 : 10));
  }
  // Float (ideal): 1/2 exactly selects CD; the next double below selects AB.
  CombinerConfig cfg = test::geforce_config();
  cfg.arithmetic = Arithmetic::Float64;
  const PlannedStage fst = plan_combiners(s, cfg, false).stages[0];
  for (auto [a, want_cd] : {std::pair{std::nextafter(0.5, 0.0), false}, {0.5, true}, {std::nextafter(0.5, 1.0), true}}) {
    RegisterSet<double> r{};
    for (int k = 0; k < 4; ++k) r.v[kTexture0][k] = 0.25, r.v[kTexture1][k] = 0.75;
    r.v[kSpare0][3] = a;
    general_combiner_float<double>(fst, r);
    for (int k = 0; k < 4; ++k) CHECK(r.v[kSpare1][k] == (want_cd ? 0.75 : 0.25));
  }
}

TEST_CASE("general combiner: both portions read the input set, RGB and alpha writes are separate") {
  CombinerState s = pass_through(gl::TEXTURE0, gl::SIGNED_IDENTITY_NV, gl::ZERO, gl::UNSIGNED_IDENTITY_NV);
  s.stages[0].rgb.ab_output = gl::SPARE0_NV;  // spare0.rgb = tex0.rgb
  set_var(s.stages[0].alpha, 0, gl::SPARE0_NV, gl::SIGNED_IDENTITY_NV, gl::BLUE);
  s.stages[0].alpha.sum_output = gl::SPARE0_NV;  // spare0.a = spare0.b of the *input* set
  const PlannedStage st = stage0(s);
  RegisterSet<std::int32_t> r = zero_regs();
  for (int k = 0; k < 4; ++k) r.v[kTexture0][k] = 100 + k;
  r.v[kSpare0][2] = -40;
  general_combiner_fixed(st, r, M, false);
  CHECK(r.v[kSpare0][0] == 100);
  CHECK(r.v[kSpare0][1] == 101);
  CHECK(r.v[kSpare0][2] == 102);
  CHECK(r.v[kSpare0][3] == -40);
}

TEST_CASE("general combiner: per-product rounding mode rounds each product, then the stage") {
  std::mt19937 rng(11);
  for (const ScaleBias& sb : kLegal) {
    CombinerState s;
    PortionState& p = s.stages[0].rgb;
    set_var(p, 0, gl::TEXTURE0, gl::HALF_BIAS_NORMAL_NV, gl::RGB);
    set_var(p, 1, gl::TEXTURE1, gl::EXPAND_NORMAL_NV, gl::RGB);
    set_var(p, 2, gl::TEXTURE1, gl::HALF_BIAS_NEGATE_NV, gl::RGB);
    set_var(p, 3, gl::TEXTURE0, gl::SIGNED_IDENTITY_NV, gl::RGB);
    p.sum_output = gl::SPARE1_NV;
    p.scale = sb.scale;
    p.bias = sb.bias;
    const PlannedStage per_product = stage0(s, CombinerRounding::PerProduct), per_stage = stage0(s);
    int differ = 0;
    for (int n = 0; n < 3000; ++n) {
      const std::int32_t a = static_cast<std::int32_t>(rng() % 256), b = static_cast<std::int32_t>(rng() % 256);
      RegisterSet<std::int32_t> r1 = zero_regs();
      for (int k = 0; k < 3; ++k) r1.v[kTexture0][k] = a, r1.v[kTexture1][k] = b;
      RegisterSet<std::int32_t> r2 = r1;
      general_combiner_fixed(per_product, r1, M, true);
      general_combiner_fixed(per_stage, r2, M, false);
      const Q x1 = test::spec_mapping(gl::HALF_BIAS_NORMAL_NV, Q(a, M)) * test::spec_mapping(gl::EXPAND_NORMAL_NV, Q(b, M));
      const Q x2 = test::spec_mapping(gl::HALF_BIAS_NEGATE_NV, Q(b, M)) * Q(a, M);
      const Q rounded = Q(test::round_away(x1, M), M) + Q(test::round_away(x2, M), M);
      CHECK(r1.v[kSpare1][0] == expected_out(rounded, sb));
      CHECK(r2.v[kSpare1][0] == expected_out(x1 + x2, sb));
      differ += r1.v[kSpare1][0] != r2.v[kSpare1][0];
    }
    CHECK(differ > 0);  // the two modes are distinguishable on these inputs
  }
}

TEST_CASE("general combiner: float path evaluates the spec formulas with only the spec clamps") {
  CombinerState s = pass_through(gl::TEXTURE0, gl::EXPAND_NORMAL_NV, gl::TEXTURE1, gl::HALF_BIAS_NEGATE_NV);
  for (PortionState* p : {&s.stages[0].rgb, &s.stages[0].alpha}) {
    p->ab_output = gl::SPARE0_NV;
    p->sum_output = gl::SPARE1_NV;
    p->scale = gl::SCALE_BY_TWO_NV;
    p->bias = gl::BIAS_BY_NEGATIVE_ONE_HALF_NV;
  }
  CombinerConfig cfg = test::geforce_config();
  cfg.arithmetic = Arithmetic::Float64;
  const PlannedStage st = plan_combiners(s, cfg, false).stages[0];
  RegisterSet<double> r{};
  for (int k = 0; k < 4; ++k) r.v[kTexture0][k] = 0.625, r.v[kTexture1][k] = 0.125;
  general_combiner_float<double>(st, r);
  // AB = 2*0.625-1 = 0.25 -> (0.25-0.5)*2 = -0.5; SUM = 0.25 + (0.5-0.125) = 0.625 -> 0.25.
  for (int k = 0; k < 4; ++k) {
    CHECK(r.v[kSpare0][k] == -0.5);
    CHECK(r.v[kSpare1][k] == 0.25);
  }
}

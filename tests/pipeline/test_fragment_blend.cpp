// Blending (pipeline/fragment/blend.h): every factor and equation, clamping at
// both ends, exhaustive 8-bit sweeps against an exact rational reference written
// here independently of the code under test (docs/numerics.md §9.5).
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <tuple>
#include <vector>

#include "fragment_harness.h"
#include "pipeline/fragment/blend.h"
#include "pipeline/fragment/constant_source.h"

using namespace ffsim;

namespace {

// Exact rational with a positive denominator, 128-bit so that sums of products of
// 16-bit codes (denominators up to (2^16-1)^4) cannot overflow.
__extension__ typedef __int128 i128;
struct Q {
  i128 n, d;  // d > 0
};
i128 gcd128(i128 a, i128 b) {
  if (a < 0) a = -a;
  while (b != 0) {
    const i128 t = a % b;
    a = b;
    b = t;
  }
  return a;
}
Q q(i128 n, i128 d) {
  const i128 g = gcd128(n, d);
  return {n / (g ? g : 1), d / (g ? g : 1)};
}
Q add(Q a, Q b) { return q(a.n * b.d + b.n * a.d, a.d * b.d); }
Q sub(Q a, Q b) { return q(a.n * b.d - b.n * a.d, a.d * b.d); }
Q mul(Q a, Q b) { return q(a.n * b.n, a.d * b.d); }
bool lt(Q a, Q b) { return a.n * b.d < b.n * a.d; }
Q qmin(Q a, Q b) { return lt(b, a) ? b : a; }
Q qmax(Q a, Q b) { return lt(a, b) ? b : a; }

// Nearest code to v in [0,1] on the /M grid, ties up: of the two grid points
// around v (k0 = floor(v*M) and k0+1) take the one at the smaller distance,
// comparing the distances as rationals (not the floor((2n+M)/2M) formula).
std::uint32_t nearest_code(Q v, std::uint32_t M) {
  if (!lt(q(0, 1), v)) return 0;
  if (!lt(v, q(1, 1))) return M;
  const i128 k0 = v.n * M / v.d;
  const Q below = sub(v, q(k0, M)), above = sub(q(k0 + 1, M), v);
  return static_cast<std::uint32_t>(lt(below, above) ? k0 : k0 + 1);  // equal distances: up
}

// The reference: GL121 §4.1.6 in exact rationals on k/M values.
std::uint32_t ref_blend(GLenum eq, GLenum sf, GLenum df, int c, const std::uint32_t* s, const std::uint32_t* d,
                        const std::uint32_t* k, std::uint32_t M) {
  Q S[4], D[4], K[4];
  for (int i = 0; i < 4; ++i) S[i] = q(s[i], M), D[i] = q(d[i], M), K[i] = q(k[i], M);
  const Q one = q(1, 1);
  const auto factor = [&](GLenum f) -> Q {
    switch (f) {
      case gl::ZERO: return q(0, 1);
      case gl::ONE: return one;
      case gl::SRC_COLOR: return S[c];
      case gl::ONE_MINUS_SRC_COLOR: return sub(one, S[c]);
      case gl::DST_COLOR: return D[c];
      case gl::ONE_MINUS_DST_COLOR: return sub(one, D[c]);
      case gl::SRC_ALPHA: return S[3];
      case gl::ONE_MINUS_SRC_ALPHA: return sub(one, S[3]);
      case gl::DST_ALPHA: return D[3];
      case gl::ONE_MINUS_DST_ALPHA: return sub(one, D[3]);
      case gl::CONSTANT_COLOR: return K[c];
      case gl::ONE_MINUS_CONSTANT_COLOR: return sub(one, K[c]);
      case gl::CONSTANT_ALPHA: return K[3];
      case gl::ONE_MINUS_CONSTANT_ALPHA: return sub(one, K[3]);
      case gl::SRC_ALPHA_SATURATE: return c == 3 ? one : qmin(S[3], sub(one, D[3]));
      default: FAIL("bad factor"); return one;
    }
  };
  Q v;
  if (eq == gl::MIN) v = qmin(S[c], D[c]);
  else if (eq == gl::MAX) v = qmax(S[c], D[c]);
  else {
    const Q a = mul(S[c], factor(sf)), b = mul(D[c], factor(df));
    v = eq == gl::FUNC_ADD ? add(a, b) : eq == gl::FUNC_SUBTRACT ? sub(a, b) : sub(b, a);
  }
  return nearest_code(v, M);
}

std::uint32_t blend8(GLenum eq, GLenum sf, GLenum df, int c, const std::uint32_t* s, const std::uint32_t* d,
                     const std::uint32_t* k = nullptr) {
  static const std::uint32_t zero[4] = {0, 0, 0, 0};
  if (!k) k = zero;
  return blend_code(eq, s[c], blend_factor<std::uint32_t>(sf, c, s, d, k, 255), d[c],
                    blend_factor<std::uint32_t>(df, c, s, d, k, 255), 255);
}

constexpr GLenum kEquations[] = {gl::FUNC_ADD, gl::FUNC_SUBTRACT, gl::FUNC_REVERSE_SUBTRACT, gl::MIN, gl::MAX};
constexpr GLenum kSrcFactors[] = {gl::ZERO, gl::ONE, gl::DST_COLOR, gl::ONE_MINUS_DST_COLOR, gl::SRC_ALPHA,
                                  gl::ONE_MINUS_SRC_ALPHA, gl::DST_ALPHA, gl::ONE_MINUS_DST_ALPHA, gl::CONSTANT_COLOR,
                                  gl::ONE_MINUS_CONSTANT_COLOR, gl::CONSTANT_ALPHA, gl::ONE_MINUS_CONSTANT_ALPHA,
                                  gl::SRC_ALPHA_SATURATE};
constexpr GLenum kDstFactors[] = {gl::ZERO, gl::ONE, gl::SRC_COLOR, gl::ONE_MINUS_SRC_COLOR, gl::SRC_ALPHA,
                                  gl::ONE_MINUS_SRC_ALPHA, gl::DST_ALPHA, gl::ONE_MINUS_DST_ALPHA, gl::CONSTANT_COLOR,
                                  gl::ONE_MINUS_CONSTANT_COLOR, gl::CONSTANT_ALPHA, gl::ONE_MINUS_CONSTANT_ALPHA};

}  // namespace

TEST_CASE("blend: the reference rounds on the exact value (self-check of the test's rational search)") {
  // 1/2 on the /255 grid is 127.5/255: the tie goes up to 128 (choice #29 half up).
  CHECK(nearest_code(q(1, 2), 255) == 128);
  CHECK(nearest_code(q(127, 255), 255) == 127);
  CHECK(nearest_code(q(-3, 7), 255) == 0);
  CHECK(nearest_code(q(9, 7), 255) == 255);
  // 100*100/255^2 = 0.153787... -> 255*v = 39.2157 -> 39.
  CHECK(nearest_code(q(10000, 65025), 255) == 39);
}

TEST_CASE("blend8: ADD, SUBTRACT, REVERSE_SUBTRACT, MIN, MAX with (ONE, ONE) for all 256x256 (s, d)") {
  for (GLenum eq : kEquations)
    for (std::uint32_t a = 0; a < 256; ++a)
      for (std::uint32_t b = 0; b < 256; ++b) {
        const std::uint32_t s[4] = {a, b, a, a}, d[4] = {b, a, b, b};
        // Closed forms (spec §4.1.6 with factors 1, exact integers): no rounding happens.
        const std::uint32_t want = eq == gl::FUNC_ADD ? std::min(255u, a + b)
                                   : eq == gl::FUNC_SUBTRACT ? (a > b ? a - b : 0)
                                   : eq == gl::FUNC_REVERSE_SUBTRACT ? (b > a ? b - a : 0)
                                   : eq == gl::MIN ? std::min(a, b) : std::max(a, b);
        const std::uint32_t got = blend8(eq, gl::ONE, gl::ONE, 0, s, d);
        if (got != want) FAIL_CHECK("eq " << blend_equation_name(eq) << " s " << a << " d " << b << " got " << got);
        REQUIRE(got == ref_blend(eq, gl::ONE, gl::ONE, 0, s, d, s, 255));
      }
}

TEST_CASE("blend8: FUNC_SUBTRACT leaves exactly 0 where the destination exceeds the source") {
  const std::uint32_t s[4] = {10, 10, 10, 100}, d[4] = {11, 255, 10, 101};
  CHECK(blend8(gl::FUNC_SUBTRACT, gl::ONE, gl::ONE, 0, s, d) == 0);   // 10 - 11 -> clamp 0
  CHECK(blend8(gl::FUNC_SUBTRACT, gl::ONE, gl::ONE, 1, s, d) == 0);   // 10 - 255
  CHECK(blend8(gl::FUNC_SUBTRACT, gl::ONE, gl::ONE, 2, s, d) == 0);   // equal
  CHECK(blend8(gl::FUNC_SUBTRACT, gl::ONE, gl::ONE, 3, s, d) == 0);   // 100 - 101
  CHECK(blend8(gl::FUNC_REVERSE_SUBTRACT, gl::ONE, gl::ONE, 3, s, d) == 1);  // d - s = 1
  // The source minus the destination, not the reverse: 200 - 50 = 150.
  const std::uint32_t s2[4] = {200, 0, 0, 0}, d2[4] = {50, 0, 0, 0};
  CHECK(blend8(gl::FUNC_SUBTRACT, gl::ONE, gl::ONE, 0, s2, d2) == 150);
  CHECK(blend8(gl::FUNC_REVERSE_SUBTRACT, gl::ONE, gl::ONE, 0, s2, d2) == 0);
}

TEST_CASE("blend8: (DST_ALPHA, ONE) doubles alpha and saturates at 1, all 256x256 (A_s, A_d)") {
  // Paper §4.2 step 12-14: source colour (0,0,0,1) so A = A_s*A_d + A_d = 2*A_d when A_s = 1.
  for (std::uint32_t d = 0; d < 256; ++d) {
    const std::uint32_t s[4] = {0, 0, 0, 255}, dd[4] = {0, 0, 0, d};
    REQUIRE(blend8(gl::FUNC_ADD, gl::DST_ALPHA, gl::ONE, 3, s, dd) == std::min(255u, 2 * d));
  }
  {
    const std::uint32_t s[4] = {0, 0, 0, 255}, d[4] = {0, 0, 0, 100};
    CHECK(blend8(gl::FUNC_ADD, gl::DST_ALPHA, gl::ONE, 3, s, d) == 200);  // 100 doubled
    const std::uint32_t d2[4] = {0, 0, 0, 200};
    CHECK(blend8(gl::FUNC_ADD, gl::DST_ALPHA, gl::ONE, 3, s, d2) == 255);  // 400/255 > 1 -> 1
    const std::uint32_t d3[4] = {0, 0, 0, 128};
    CHECK(blend8(gl::FUNC_ADD, gl::DST_ALPHA, gl::ONE, 3, s, d3) == 255);  // 256/255 -> clamp
    const std::uint32_t d4[4] = {0, 0, 0, 127};
    CHECK(blend8(gl::FUNC_ADD, gl::DST_ALPHA, gl::ONE, 3, s, d4) == 254);
  }
  for (std::uint32_t a = 0; a < 256; ++a)
    for (std::uint32_t b = 0; b < 256; ++b) {
      const std::uint32_t s[4] = {a, a, a, a}, d[4] = {b, b, b, b};
      REQUIRE(blend8(gl::FUNC_ADD, gl::DST_ALPHA, gl::ONE, 3, s, d) == ref_blend(gl::FUNC_ADD, gl::DST_ALPHA, gl::ONE, 3, s, d, s, 255));
    }
}

TEST_CASE("blend8: (DST_ALPHA, DST_ALPHA) modulation, all 256x256 pairs for colour and alpha") {
  // Paper §4.2 step 19-20: source (1,1,1,1) gives C = C_s*A_d + C_d*A_d = (1 + C_d)*A_d.
  {
    const std::uint32_t s[4] = {255, 255, 255, 255}, d[4] = {100, 0, 255, 51};
    // R: (255*51 + 100*51)/255^2 = 18105/65025 -> 255 v = 71.0  (exactly 71: 355*51/255 = 71)
    CHECK(blend8(gl::FUNC_ADD, gl::DST_ALPHA, gl::DST_ALPHA, 0, s, d) == 71);
    CHECK(blend8(gl::FUNC_ADD, gl::DST_ALPHA, gl::DST_ALPHA, 1, s, d) == 51);   // (1+0)*0.2
    CHECK(blend8(gl::FUNC_ADD, gl::DST_ALPHA, gl::DST_ALPHA, 2, s, d) == 102);  // (1+1)*0.2 = 0.4
    CHECK(blend8(gl::FUNC_ADD, gl::DST_ALPHA, gl::DST_ALPHA, 3, s, d) == 61);   // (1+0.2)*0.2 = 0.24 -> 61.2
  }
  // Colour channel c (factor from A_d) and alpha channel (both operands alpha).
  for (std::uint32_t a = 0; a < 256; ++a)
    for (std::uint32_t b = 0; b < 256; ++b) {
      const std::uint32_t s[4] = {a, 0, 0, a}, d[4] = {b, 0, 0, b};
      for (int c : {0, 3})
        REQUIRE(blend8(gl::FUNC_ADD, gl::DST_ALPHA, gl::DST_ALPHA, c, s, d) ==
                ref_blend(gl::FUNC_ADD, gl::DST_ALPHA, gl::DST_ALPHA, c, s, d, s, 255));
      // Same pairs with alpha factors from a fixed third value: s colour a, d colour b, A_d = 77.
      const std::uint32_t s2[4] = {a, 0, 0, 200}, d2[4] = {b, 0, 0, 77};
      for (GLenum sf : {gl::DST_ALPHA, gl::ONE_MINUS_DST_ALPHA})
        for (GLenum df : {gl::DST_ALPHA, gl::ONE_MINUS_DST_ALPHA, gl::ONE})
          for (GLenum eq : {gl::FUNC_ADD, gl::FUNC_SUBTRACT, gl::FUNC_REVERSE_SUBTRACT})
            REQUIRE(blend8(eq, sf, df, 0, s2, d2) == ref_blend(eq, sf, df, 0, s2, d2, s2, 255));
    }
}

TEST_CASE("blend8: each factor at one hand-computed point") {
  // s = (0.2, 0.4, 0.6, 0.8) = codes (51, 102, 153, 204); d = (1, 0, 1/3, 2/3) = (255, 0, 85, 170);
  // constant (0.25, 0.5, 0.75, 1) rounded to codes (64, 128, 191, 255) (63.75, 127.5, 191.25, 255).
  const std::uint32_t s[4] = {51, 102, 153, 204}, d[4] = {255, 0, 85, 170}, k[4] = {64, 128, 191, 255};
  // Factor codes for channel G (c = 1), by hand from GL121 Table 4.1/4.2.
  struct F { GLenum f; std::uint32_t want; };
  const F cases[] = {
      {gl::ZERO, 0}, {gl::ONE, 255}, {gl::SRC_COLOR, 102}, {gl::ONE_MINUS_SRC_COLOR, 153},
      {gl::DST_COLOR, 0}, {gl::ONE_MINUS_DST_COLOR, 255}, {gl::SRC_ALPHA, 204}, {gl::ONE_MINUS_SRC_ALPHA, 51},
      {gl::DST_ALPHA, 170}, {gl::ONE_MINUS_DST_ALPHA, 85}, {gl::CONSTANT_COLOR, 128},
      {gl::ONE_MINUS_CONSTANT_COLOR, 127}, {gl::CONSTANT_ALPHA, 255}, {gl::ONE_MINUS_CONSTANT_ALPHA, 0},
      {gl::SRC_ALPHA_SATURATE, 85},  // min(A_s, 1 - A_d) = min(0.8, 1/3) = 1/3
  };
  for (const F& f : cases) CHECK_MESSAGE(blend_factor<std::uint32_t>(f.f, 1, s, d, k, 255) == f.want, blend_factor_name(f.f));
  // SRC_ALPHA_SATURATE is (f, f, f, 1): the alpha factor is 1.
  CHECK(blend_factor<std::uint32_t>(gl::SRC_ALPHA_SATURATE, 3, s, d, k, 255) == 255);
  // Whole blends at this point, G channel (s_G = 0.4, d_G = 0):
  // (SRC_ALPHA, ONE_MINUS_SRC_ALPHA): 0.4*0.8 + 0 = 0.32 -> 81.6 -> 82.
  CHECK(blend8(gl::FUNC_ADD, gl::SRC_ALPHA, gl::ONE_MINUS_SRC_ALPHA, 1, s, d, k) == 82);
  // R channel (s_R = 0.2, d_R = 1): 0.2*0.8 + 1*0.2 = 0.36 -> 91.8 -> 92.
  CHECK(blend8(gl::FUNC_ADD, gl::SRC_ALPHA, gl::ONE_MINUS_SRC_ALPHA, 0, s, d, k) == 92);
  // B, (CONSTANT_COLOR, ONE_MINUS_CONSTANT_COLOR): 0.6*191/255 + (1/3)*(64/255) -> (153*191 + 85*64)/255 = 136.0 -> 136.
  CHECK(blend8(gl::FUNC_ADD, gl::CONSTANT_COLOR, gl::ONE_MINUS_CONSTANT_COLOR, 2, s, d, k) == 136);
  // R, (SRC_ALPHA_SATURATE, ZERO): 0.2 * min(0.8, 1/3) = 0.0667 -> 17.0 -> 17.
  CHECK(blend8(gl::FUNC_ADD, gl::SRC_ALPHA_SATURATE, gl::ZERO, 0, s, d, k) == 17);
  // A, (SRC_ALPHA_SATURATE, ZERO): A_s * 1 = 204.
  CHECK(blend8(gl::FUNC_ADD, gl::SRC_ALPHA_SATURATE, gl::ZERO, 3, s, d, k) == 204);
  // ADD clamps at 1: R with (ONE, ONE) = 0.2 + 1 -> 255; REVERSE_SUBTRACT with (ONE, ONE): 1 - 0.2 = 204.
  CHECK(blend8(gl::FUNC_ADD, gl::ONE, gl::ONE, 0, s, d, k) == 255);
  CHECK(blend8(gl::FUNC_REVERSE_SUBTRACT, gl::ONE, gl::ONE, 0, s, d, k) == 204);
}

TEST_CASE("blend8: every (equation, source factor, destination factor) against the exact reference") {
  // Random operands (fixed seed) over all 5 x 13 x 12 combinations and all channels.
  std::mt19937 rng(20001);
  std::uniform_int_distribution<std::uint32_t> code(0, 255);
  for (GLenum eq : kEquations)
    for (GLenum sf : kSrcFactors)
      for (GLenum df : kDstFactors)
        for (int trial = 0; trial < 40; ++trial) {
          std::uint32_t s[4], d[4], k[4];
          for (int i = 0; i < 4; ++i) s[i] = code(rng), d[i] = code(rng), k[i] = code(rng);
          if (trial == 0) for (int i = 0; i < 4; ++i) s[i] = 255, d[i] = 255;  // both ends
          if (trial == 1) for (int i = 0; i < 4; ++i) s[i] = 0, d[i] = 255;
          for (int c = 0; c < 4; ++c) {
            const std::uint32_t got = blend8(eq, sf, df, c, s, d, k), want = ref_blend(eq, sf, df, c, s, d, k, 255);
            if (got != want)
              FAIL_CHECK(blend_equation_name(eq) << " " << blend_factor_name(sf) << " " << blend_factor_name(df) << " c " << c
                                                 << " s " << s[c] << " d " << d[c] << " got " << got << " want " << want);
          }
        }
}

TEST_CASE("blend: wide codes (10, 12, 16 bits) against the exact reference, no overflow at 16 bits") {
  std::mt19937 rng(777);
  for (int bits : {10, 12, 16}) {
    const std::uint32_t M = (1u << bits) - 1;
    std::uniform_int_distribution<std::uint32_t> code(0, M);
    for (int trial = 0; trial < 300; ++trial) {
      std::uint32_t s[4], d[4], k[4];
      for (int i = 0; i < 4; ++i) s[i] = code(rng), d[i] = code(rng), k[i] = code(rng);
      if (trial == 0) for (int i = 0; i < 4; ++i) s[i] = d[i] = M;
      const GLenum eq = kEquations[trial % 5], sf = kSrcFactors[trial % 13], df = kDstFactors[(trial / 13) % 12];
      for (int c = 0; c < 4; ++c) {
        const std::uint32_t got = blend_code(eq, s[c], blend_factor<std::uint32_t>(sf, c, s, d, k, M), d[c],
                                             blend_factor<std::uint32_t>(df, c, s, d, k, M), M);
        REQUIRE(got == ref_blend(eq, sf, df, c, s, d, k, M));
      }
    }
    // ONE + ONE of all ones saturates to all ones; the largest product n = 2 M^2 fits.
    CHECK(blend_code(gl::FUNC_ADD, M, M, M, M, M) == M);
    CHECK(blend_code(gl::FUNC_SUBTRACT, 0, M, M, M, M) == 0);
  }
}

TEST_CASE("blend: float paths compute the formula in binary64 / binary32 and clamp to [0,1]") {
  // ideal: exact reals where representable: 0.5*0.5 + 0.25*1 = 0.5.
  CHECK(blend_value<double>(gl::FUNC_ADD, 0.5, 0.5, 0.25, 1.0) == 0.5);
  CHECK(blend_value<double>(gl::FUNC_ADD, 0.75, 1.0, 0.5, 1.0) == 1.0);         // 1.25 -> 1
  CHECK(blend_value<double>(gl::FUNC_SUBTRACT, 0.25, 1.0, 0.5, 1.0) == 0.0);    // -0.25 -> 0
  CHECK(!std::signbit(blend_value<double>(gl::FUNC_SUBTRACT, 0.0, 1.0, 0.0, 1.0)));  // -0 -> +0
  CHECK(blend_value<double>(gl::FUNC_REVERSE_SUBTRACT, 0.25, 1.0, 0.5, 1.0) == 0.25);
  CHECK(blend_value<double>(gl::MIN, 0.25, 0.0, 0.5, 0.0) == 0.25);
  CHECK(blend_value<double>(gl::MAX, 0.25, 0.0, 0.5, 0.0) == 0.5);
  // float32: 0.1f*0.3f computed in binary32 (not binary64 then rounded): the expected
  // value is the product of the two floats rounded once to binary32.
  const float a = 0.1f, b = 0.3f;
  const float want = a * b;
  CHECK(blend_value<float>(gl::FUNC_ADD, a, b, 0.0f, 0.0f) == want);
  // The float and exact answers differ from the 8-bit one: 100/255 + 100/255*... kept for the record:
  // (DST_ALPHA, ONE) doubling 0.6 saturates at 1 in every arithmetic.
  CHECK(blend_value<double>(gl::FUNC_ADD, 1.0, 0.6, 0.6, 1.0) == 1.0);
  CHECK(blend_value<float>(gl::FUNC_ADD, 1.0f, 0.6f, 0.6f, 1.0f) == 1.0f);
}

TEST_CASE("blend: factor validity per GL 1.2.1 + EXT_blend_color (SRC_ALPHA_SATURATE is source only)") {
  for (GLenum f : kSrcFactors) CHECK(valid_blend_src_factor(f));
  for (GLenum f : kDstFactors) CHECK(valid_blend_dst_factor(f));
  CHECK(!valid_blend_dst_factor(gl::SRC_ALPHA_SATURATE));
  CHECK(!valid_blend_dst_factor(gl::DST_COLOR));
  CHECK(!valid_blend_dst_factor(gl::ONE_MINUS_DST_COLOR));
  CHECK(!valid_blend_src_factor(gl::SRC_COLOR));
  CHECK(!valid_blend_src_factor(gl::ONE_MINUS_SRC_COLOR));
  CHECK(!valid_blend_src_factor(gl::BLEND));
  for (GLenum e : kEquations) CHECK(valid_blend_equation(e));
  CHECK(!valid_blend_equation(gl::ONE));
  CHECK(!valid_blend_equation(gl::ZERO));
}

TEST_CASE("blend8 through the planned path: all 256x256 (s, d) for the paper's modes and every equation") {
  // A 256x256 buffer holding d = y in every channel; row y receives fragments with
  // s = x in every channel. Each pixel is checked against the exact reference.
  struct Mode { GLenum eq, sf, df; };
  const Mode modes[] = {
      {gl::FUNC_ADD, gl::ONE, gl::ONE},           {gl::FUNC_SUBTRACT, gl::ONE, gl::ONE},
      {gl::FUNC_REVERSE_SUBTRACT, gl::ONE, gl::ONE}, {gl::MIN, gl::ONE, gl::ZERO},
      {gl::MAX, gl::ONE, gl::ZERO},                {gl::FUNC_ADD, gl::DST_ALPHA, gl::ONE},
      {gl::FUNC_ADD, gl::DST_ALPHA, gl::DST_ALPHA}, {gl::FUNC_ADD, gl::SRC_ALPHA, gl::ONE_MINUS_SRC_ALPHA},
      {gl::FUNC_ADD, gl::ONE_MINUS_DST_ALPHA, gl::ZERO}, {gl::FUNC_SUBTRACT, gl::ONE, gl::ONE_MINUS_DST_ALPHA},
  };
  const FragmentTarget t{256, 256, Arithmetic::Fixed, 8, 0, 0};
  for (const Mode& m : modes) {
    ffsim::test::Buffers b(t);
    for (int y = 0; y < 256; ++y)
      for (int x = 0; x < 256; ++x)
        for (int c = 0; c < 4; ++c) b.codes[4 * b.px(x, y) + c] = static_cast<std::uint16_t>(y);
    FragmentOpsState s;
    s.blend = {true, m.sf, m.df, m.eq, {}};
    const FragmentPlan plan = build_fragment_plan(fragment_plan_key(s, t));
    const FragmentConstants k = fragment_constants(s, t);
    FragmentSpan sp;
    sp.count = 256;
    for (int x = 0; x < 256; ++x)
      for (int c = 0; c < 4; ++c) sp.codes.push_back(static_cast<std::uint16_t>(x));
    for (int y = 0; y < 256; ++y) {
      sp.y = y;
      run_fragment_plan(plan, k, sp, b.view(), t.width);
    }
    long wrong = 0;
    for (std::uint32_t y = 0; y < 256; ++y)
      for (std::uint32_t x = 0; x < 256; ++x) {
        const std::uint32_t sv[4] = {x, x, x, x}, dv[4] = {y, y, y, y}, kv[4] = {0, 0, 0, 0};
        for (int c : {0, 3})
          wrong += b.code(static_cast<int>(x), static_cast<int>(y), c) != ref_blend(m.eq, m.sf, m.df, c, sv, dv, kv, 255);
      }
    CHECK_MESSAGE(wrong == 0, blend_equation_name(m.eq) << " " << blend_factor_name(m.sf) << " " << blend_factor_name(m.df));
  }
}

TEST_CASE("blend8 on listed pixels and rows: every equation, factor pair and colour mask against the exact reference") {
  // The 8-bit colour stage computes four pixels' channels in 16-bit lanes
  // (pipeline/fragment/blend_lanes8.h) for rows and for listed pixels (the
  // terrain's triangle groups). Every (equation, source, destination) triple, a
  // random colour mask and constant colour for each, 1023 fragments at distinct
  // pixels in a random order (several 256-fragment chunks and a tail of three),
  // every channel of every pixel compared with the exact rational reference.
  std::mt19937 rng(22001);
  const FragmentTarget t{64, 16, Arithmetic::Fixed, 8, 0, 0};
  const int n = 1023;
  long compared = 0, wrong = 0;
  for (GLenum eq : kEquations)
    for (GLenum sf : kSrcFactors)
      for (GLenum df : kDstFactors)
        for (const bool listed : {true, false}) {
          FragmentOpsState s;
          std::uint32_t k[4];
          for (int c = 0; c < 4; ++c) {
            k[c] = rng() % 256;
            s.blend.color[c] = k[c] / 255.0;
          }
          s.blend = {true, sf, df, eq, s.blend.color};
          const unsigned mask = 1 + rng() % 15;
          s.color_mask = {(mask & 1) != 0, (mask & 2) != 0, (mask & 4) != 0, (mask & 8) != 0};
          const FragmentPlan plan = build_fragment_plan(fragment_plan_key(s, t));
          const FragmentConstants kk = fragment_constants(s, t);
          REQUIRE(kk.blend_color_code == std::array<std::uint32_t, 4>{k[0], k[1], k[2], k[3]});
          ffsim::test::Buffers b(t);
          for (auto& v : b.codes) v = static_cast<std::uint16_t>(rng() % 4 == 0 ? 255 * (rng() % 2) : rng() % 256);
          const std::vector<std::uint16_t> before = b.codes;
          std::vector<std::uint32_t> pixel(static_cast<std::size_t>(t.width * t.height));
          for (std::size_t i = 0; i < pixel.size(); ++i) pixel[i] = static_cast<std::uint32_t>(i);
          if (listed) std::shuffle(pixel.begin(), pixel.end(), rng);
          pixel.resize(n);
          std::vector<std::uint16_t> in(4 * static_cast<std::size_t>(n));
          for (auto& v : in) v = static_cast<std::uint16_t>(rng() % 4 == 0 ? 255 * (rng() % 2) : rng() % 256);
          if (listed) {
            run_fragment_plan_pixels(plan, kk, in.data(), nullptr, pixel.data(), n, b.view());
          } else {  // rows: the first n pixels in 64-pixel spans
            for (int y = 0; 64 * y < n; ++y) {
              FragmentSpan sp;
              sp.y = y;
              sp.count = std::min(64, n - 64 * y);
              sp.codes.assign(in.begin() + 4 * 64 * y, in.begin() + 4 * (64 * y + sp.count));
              run_fragment_plan(plan, kk, sp, b.view(), t.width);
            }
          }
          for (int i = 0; i < n; ++i) {
            const std::size_t p = pixel[static_cast<std::size_t>(i)];
            std::uint32_t sv[4], dv[4];
            for (int c = 0; c < 4; ++c) sv[c] = in[4 * static_cast<std::size_t>(i) + c], dv[c] = before[4 * p + c];
            for (int c = 0; c < 4; ++c) {
              const std::uint32_t want = (mask >> c & 1) ? ref_blend(eq, sf, df, c, sv, dv, k, 255) : dv[c];
              ++compared;
              if (b.codes[4 * p + c] != want && ++wrong <= 5)
                FAIL_CHECK(blend_equation_name(eq) << " " << blend_factor_name(sf) << " " << blend_factor_name(df)
                                                   << (listed ? " listed" : " rows") << " mask " << mask << " c " << c
                                                   << " s " << sv[c] << " d " << dv[c] << " got " << b.codes[4 * p + c]
                                                   << " want " << want);
            }
          }
        }
  CHECK(wrong == 0);
  CHECK(compared == 5L * 13 * 12 * 2 * n * 4);
}

// colour_stage_keeps (pipeline/fragment/constant_source.h): a colour stage fed one
// known source colour is said to keep every destination only when it does. The
// truth is computed here by brute force over destinations with blend_code and
// blend_factor (the formula the reference above checks), and for a sample of the
// "keeps" answers by the planned path itself on a buffer of every (d_c, A_d).
TEST_CASE("colour_stage_keeps: exact where it says yes, for every equation, factor pair, mask and source (8 bits)") {
  const FragmentTarget t{256, 256, Arithmetic::Fixed, 8, 0, 0};
  const std::uint32_t kCodes[] = {0, 1, 128, 255};
  const std::array<std::array<bool, 4>, 4> kMasks{{{true, true, true, true}, {false, false, false, true},
                                                    {true, true, true, false}, {true, false, true, false}}};
  const std::array<std::array<double, 4>, 2> kConstants{{{0, 0, 0, 0}, {1, 0, 1, 1}}};
  // The planned path on a buffer holding d = (x, x, x, y) at pixel (x, y).
  ffsim::test::Buffers every(t);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x)
      for (int c = 0; c < 4; ++c) every.codes[4 * every.px(x, y) + c] = static_cast<std::uint16_t>(c == 3 ? y : x);
  std::set<std::tuple<FragmentPlanKey, std::array<std::uint32_t, 4>, std::array<std::uint32_t, 4>>> seen;
  long said_yes = 0, missed = 0, kernel_runs = 0;
  bool paper_case = false;
  for (GLenum eq : kEquations)
    for (GLenum sf : kSrcFactors)
      for (GLenum df : kDstFactors)
        for (const auto& mask : kMasks)
          for (const auto& constant : kConstants)
            for (std::uint32_t rgb : kCodes)
              for (std::uint32_t a : kCodes) {
                FragmentOpsState s;
                s.blend = {true, sf, df, eq, constant};
                s.color_mask = mask;
                const FragmentPlanKey key = fragment_plan_key(s, t);
                const FragmentConstants k = fragment_constants(s, t);
                const std::array<std::uint32_t, 4> src{rgb, rgb, rgb, a};
                // (each distinct question once: the key drops what no channel uses)
                if (!seen.insert({key, k.blend_color_code, src}).second) continue;
                const bool yes = colour_stage_keeps(key, k, src);
                // Brute force: every (d_c, A_d), every written channel.
                bool keeps = true;
                for (std::uint32_t y = 0; y < 256 && keeps; ++y)
                  for (std::uint32_t x = 0; x < 256 && keeps; ++x) {
                    const std::uint32_t d[4] = {x, x, x, y};
                    for (int c = 0; c < 4 && keeps; ++c)
                      if (mask[static_cast<std::size_t>(c)])
                        keeps = blend_code(eq, src[static_cast<std::size_t>(c)],
                                           blend_factor<std::uint32_t>(sf, c, src.data(), d, k.blend_color_code.data(), 255),
                                           d[c], blend_factor<std::uint32_t>(df, c, src.data(), d, k.blend_color_code.data(), 255),
                                           255) == d[c];
                  }
                if (yes && !keeps)
                  FAIL_CHECK("says keeps but does not: " << blend_equation_name(eq) << " " << blend_factor_name(sf) << " "
                                                         << blend_factor_name(df) << " source " << rgb << "," << a);
                said_yes += yes;
                missed += keeps && !yes;
                paper_case |= yes && eq == gl::FUNC_ADD && sf == gl::DST_ALPHA && df == gl::ONE && a == 0 && !mask[0] && mask[3];
                if (yes && said_yes % 97 == 1) {  // the planned path leaves the buffer as it is
                  ffsim::test::Buffers b = every;
                  FragmentSpan sp;
                  sp.count = 256;
                  for (int x = 0; x < 256; ++x)
                    for (std::uint32_t c : src) sp.codes.push_back(static_cast<std::uint16_t>(c));
                  const FragmentPlan plan = build_fragment_plan(key);
                  for (int y = 0; y < 256; ++y) {
                    sp.y = y;
                    run_fragment_plan(plan, k, sp, b.view(), t.width);
                  }
                  REQUIRE(b.same(every));
                  ++kernel_runs;
                }
              }
  MESSAGE("distinct cases: " << seen.size() << ", said keeps: " << said_yes << ", keeps but not said: " << missed << ", checked on the planned path: " << kernel_runs);
  CHECK(paper_case);  // the paper's third penumbra pass at penumbra 2 (section 4.2)
  CHECK(said_yes > 1000);
  CHECK(kernel_runs > 10);
}

TEST_CASE("colour_stage_keeps: hand cases, 8 and 12 bits, and float arithmetic never") {
  for (const int bits : {8, 12}) {
    const std::uint32_t M = (1u << bits) - 1;
    const FragmentTarget t{4, 4, Arithmetic::Fixed, bits, 0, 0};
    auto keeps = [&](GLenum eq, GLenum sf, GLenum df, std::array<std::uint32_t, 4> src,
                     std::array<bool, 4> mask = {true, true, true, true}) {
      FragmentOpsState s;
      s.blend = {true, sf, df, eq, {}};
      s.color_mask = mask;
      return colour_stage_keeps(fragment_plan_key(s, t), fragment_constants(s, t), src);
    };
    const std::array<bool, 4> alpha_only{false, false, false, true};
    CHECK(keeps(gl::FUNC_ADD, gl::DST_ALPHA, gl::ONE, {0, 0, 0, 0}, alpha_only));        // A_s·A_d + A_d, A_s = 0
    CHECK_FALSE(keeps(gl::FUNC_ADD, gl::DST_ALPHA, gl::ONE, {0, 0, 0, 1}, alpha_only));  // the smallest A_s changes A_d = M/2
    CHECK(keeps(gl::FUNC_ADD, gl::ONE, gl::ONE, {0, 0, 0, 0}));
    CHECK(keeps(gl::FUNC_REVERSE_SUBTRACT, gl::ONE, gl::ONE, {0, 0, 0, 0}));
    CHECK_FALSE(keeps(gl::FUNC_SUBTRACT, gl::ONE, gl::ONE, {0, 0, 0, 0}));  // 0 − d clamps to 0
    CHECK(keeps(gl::FUNC_ADD, gl::SRC_ALPHA, gl::ONE_MINUS_SRC_ALPHA, {M, 7, 0, 0}));  // A_s = 0: S = 0, D = M
    CHECK_FALSE(keeps(gl::FUNC_ADD, gl::SRC_ALPHA, gl::ONE_MINUS_SRC_ALPHA, {M, 7, 0, 1}));
    CHECK(keeps(gl::MIN, gl::ONE, gl::ONE, {M, M, M, M}));
    CHECK_FALSE(keeps(gl::MIN, gl::ONE, gl::ONE, {M, M, M - 1, M}));
    CHECK(keeps(gl::MAX, gl::ONE, gl::ONE, {0, 0, 0, 0}));
    CHECK_FALSE(keeps(gl::MAX, gl::ONE, gl::ONE, {0, 1, 0, 0}));
    CHECK(keeps(gl::FUNC_ADD, gl::ZERO, gl::ONE, {5, 5, 5, 5}));   // a kept channel (the key's own rule)
    CHECK_FALSE(keeps(gl::FUNC_ADD, gl::ONE, gl::ZERO, {0, 0, 0, 0}));  // the source copied
    CHECK(keeps(gl::FUNC_ADD, gl::ONE, gl::ZERO, {0, 0, 0, 0}, {false, false, false, false}));  // nothing written
    CHECK_FALSE(keeps(gl::FUNC_ADD, gl::ONE, gl::ONE, {0, 0, 0, M + 1}));  // not a code
    // Spot check of the claim's arithmetic at this width: n = d·M rounds to d.
    for (std::uint32_t d = 0; d <= M; ++d) REQUIRE(blend_code(gl::FUNC_ADD, 0, M, d, M, M) == d);
  }
  const FragmentTarget f{4, 4, Arithmetic::Float64, 8, 0, 0};
  FragmentOpsState s;
  s.blend = {true, gl::ONE, gl::ONE, gl::FUNC_ADD, {}};
  CHECK_FALSE(colour_stage_keeps(fragment_plan_key(s, f), fragment_constants(s, f), {0, 0, 0, 0}));
}

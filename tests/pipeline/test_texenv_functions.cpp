// Texture environments and the colour sum (pipeline/texenv/texenv.h). Expected
// values: the closed-form integer formulas of the exact rule "evaluate on
// k/255, round half up once" (docs/numerics.md §8.6), e.g. MODULATE
// rnd(a·b/255) = (2ab + 255) / 510, swept over all 8-bit operand pairs.
#include <doctest/doctest.h>

#include <algorithm>
#include <random>

#include "pipeline/texenv/shading.h"

using namespace ffsim;

namespace {

const ColorFormat kC8{Arithmetic::Fixed, 8};
const ColorFormat kIdeal{Arithmetic::Float64, 0};

Rgba rgba(std::uint32_t r, std::uint32_t g, std::uint32_t b, std::uint32_t a) {
  Rgba c;
  c.code = {r, g, b, a};
  for (int i = 0; i < 4; ++i) c.value[i] = c.code[i] / 255.0;
  return c;
}
Texel texel(BaseFormat base, std::array<std::uint32_t, 4> stored) {
  Texel t = expand_texel(base, 8, stored);
  for (int i = 0; i < 4; ++i) t.value[i] = t.code[i] / 255.0;
  return t;
}
TexEnvState mode(GLenum m) {
  TexEnvState e;
  e.mode = m;
  return e;
}
TexEnvState combine(GLenum rgb, GLenum alpha) {
  TexEnvState e;
  e.mode = gl::COMBINE;
  e.combine_rgb = rgb;
  e.combine_alpha = alpha;
  return e;
}
std::uint32_t rnd_div(std::uint64_t num, std::uint64_t den) { return static_cast<std::uint32_t>((2 * num + den) / (2 * den)); }

}  // namespace

TEST_CASE("texenv: MODULATE is exact for all 8-bit pairs") {
  const TexEnvState env = mode(gl::MODULATE);
  for (std::uint32_t a = 0; a < 256; ++a)
    for (std::uint32_t b = 0; b < 256; ++b) {
      const Rgba r = texture_environment(env, rgba(a, a, a, a), rgba(0, 0, 0, 0), texel(BaseFormat::RGBA, {b, b, b, b}), kC8);
      REQUIRE_MESSAGE(r.code[0] == rnd_div(a * b, 255), a << " * " << b);
      REQUIRE(r.code[3] == r.code[0]);
    }
}

TEST_CASE("texenv: classic functions per base format (GL121 Tables 3.18-3.19)") {
  const Rgba cf = rgba(200, 100, 50, 128);
  const Rgba none{};
  SUBCASE("REPLACE") {
    const TexEnvState e = mode(gl::REPLACE);
    CHECK(texture_environment(e, cf, none, texel(BaseFormat::Alpha, {9}), kC8).code == std::array<std::uint32_t, 4>{200, 100, 50, 9});
    CHECK(texture_environment(e, cf, none, texel(BaseFormat::Luminance, {9}), kC8).code == std::array<std::uint32_t, 4>{9, 9, 9, 128});
    CHECK(texture_environment(e, cf, none, texel(BaseFormat::RGB, {1, 2, 3}), kC8).code == std::array<std::uint32_t, 4>{1, 2, 3, 128});
    CHECK(texture_environment(e, cf, none, texel(BaseFormat::Intensity, {7}), kC8).code == std::array<std::uint32_t, 4>{7, 7, 7, 7});
  }
  SUBCASE("DECAL: RGBA blends by texture alpha, alpha from the fragment") {
    // R = rnd((200·(255-51) + 255·51)/255) = rnd((40800 + 13005)/255) = rnd(211.0) = 211.
    const Rgba r = texture_environment(mode(gl::DECAL), cf, none, texel(BaseFormat::RGBA, {255, 0, 0, 51}), kC8);
    CHECK(r.code[0] == 211);
    CHECK(r.code[1] == rnd_div(100 * 204, 255));  // 80
    CHECK(r.code[3] == 128);
  }
  SUBCASE("BLEND with the environment colour") {
    TexEnvState e = mode(gl::BLEND);
    e.color = {1, 0, 0, 1};
    // LUMINANCE 64: R = Cf(1-L) + Cc·L = (200·191 + 255·64)/255 = (38200 + 16320)/255 = 213.8 -> 214.
    const Rgba r = texture_environment(e, cf, none, texel(BaseFormat::Luminance, {64}), kC8);
    CHECK(r.code[0] == 214);
    CHECK(r.code[1] == rnd_div(100 * 191, 255));  // 74.9 -> 75
    CHECK(r.code[3] == 128);                      // LUMINANCE: A = Af
    // INTENSITY blends alpha too: (128·191 + 255·64)/255 = (24448 + 16320)/255 = 159.9 -> 160.
    CHECK(texture_environment(e, cf, none, texel(BaseFormat::Intensity, {64}), kC8).code[3] == 160);
  }
  SUBCASE("ADD saturates colour at 1 and modulates alpha") {
    const Rgba r = texture_environment(mode(gl::ADD), cf, none, texel(BaseFormat::RGBA, {100, 100, 100, 128}), kC8);
    CHECK(r.code == std::array<std::uint32_t, 4>{255, 200, 150, rnd_div(128 * 128, 255)});
    CHECK(texture_environment(mode(gl::ADD), cf, none, texel(BaseFormat::Intensity, {200}), kC8).code[3] == 255);
  }
}

TEST_CASE("texenv: COMBINE functions, operands, scales and clamps") {
  const Rgba none{};
  SUBCASE("ADD_SIGNED is k1 + k2 - 127 (the tie 127.5 rounds up), clamped, for all pairs") {
    TexEnvState e = combine(gl::ADD_SIGNED, gl::ADD_SIGNED);
    for (std::uint32_t a = 0; a < 256; ++a)
      for (std::uint32_t b = 0; b < 256; b += 3) {
        const Rgba r = texture_environment(e, rgba(b, b, b, b), none, texel(BaseFormat::RGBA, {a, a, a, a}), kC8);
        const int want = std::clamp(static_cast<int>(a + b) - 127, 0, 255);
        REQUIRE_MESSAGE(static_cast<int>(r.code[0]) == want, a << " + " << b);
      }
  }
  SUBCASE("SUBTRACT clamps at 0, ADD clamps at 1") {
    TexEnvState e = combine(gl::SUBTRACT, gl::ADD);
    const Rgba r = texture_environment(e, rgba(200, 50, 0, 200), none, texel(BaseFormat::RGBA, {100, 100, 100, 100}), kC8);
    CHECK(r.code == std::array<std::uint32_t, 4>{0, 50, 100, 255});  // texture - previous; alpha 100 + 200 -> 1
  }
  SUBCASE("INTERPOLATE a0·a2 + a1·(1 - a2) with a CONSTANT source, exact") {
    TexEnvState e = combine(gl::INTERPOLATE, gl::REPLACE);
    e.source_rgb = {gl::TEXTURE, gl::PREVIOUS, gl::CONSTANT};
    e.operand_rgb = {gl::SRC_COLOR, gl::SRC_COLOR, gl::SRC_COLOR};
    for (std::uint32_t k = 0; k < 256; k += 5) {
      e.color = {k / 255.0, 0, 0, 0};  // converted to the 8-bit code k
      const Rgba r = texture_environment(e, rgba(30, 0, 0, 0), none, texel(BaseFormat::RGB, {220, 0, 0}), kC8);
      CHECK(r.code[0] == rnd_div(220 * k + 30 * (255 - k), 255));
    }
  }
  SUBCASE("operands ONE_MINUS_SRC_COLOR and SRC_ALPHA, PRIMARY_COLOR source") {
    TexEnvState e = combine(gl::MODULATE, gl::REPLACE);
    e.source_rgb = {gl::PRIMARY_COLOR, gl::TEXTURE, gl::CONSTANT};
    e.operand_rgb = {gl::ONE_MINUS_SRC_COLOR, gl::SRC_ALPHA, gl::SRC_ALPHA};
    e.source_alpha = {gl::PRIMARY_COLOR, gl::PREVIOUS, gl::CONSTANT};
    e.operand_alpha = {gl::ONE_MINUS_SRC_ALPHA, gl::SRC_ALPHA, gl::SRC_ALPHA};
    const Rgba r = texture_environment(e, rgba(1, 2, 3, 4), rgba(55, 0, 255, 5), texel(BaseFormat::RGBA, {0, 0, 0, 128}), kC8);
    CHECK(r.code[0] == rnd_div(200 * 128, 255));  // (1 - 55/255)·128/255
    CHECK(r.code[1] == 128);
    CHECK(r.code[2] == 0);
    CHECK(r.code[3] == 250);  // 1 - primary alpha
  }
  SUBCASE("RGB_SCALE 4 and ALPHA_SCALE 2 multiply before the clamp") {
    TexEnvState e = combine(gl::MODULATE, gl::MODULATE);
    e.rgb_scale = 4;
    e.alpha_scale = 2;
    const Rgba r = texture_environment(e, rgba(50, 100, 0, 100), none, texel(BaseFormat::RGBA, {255, 255, 0, 255}), kC8);
    CHECK(r.code == std::array<std::uint32_t, 4>{200, 255, 0, 200});
  }
}

TEST_CASE("texenv: DOT3 is sum (2k0-255)(2k1-255)/65025, ARB scales, EXT does not") {
  TexEnvState e = combine(gl::DOT3_RGB, gl::REPLACE);
  e.source_rgb = {gl::TEXTURE, gl::PREVIOUS, gl::CONSTANT};
  const Rgba none{};
  for (std::uint32_t a = 0; a < 256; a += 7)
    for (std::uint32_t b = 0; b < 256; b += 11) {
      const Rgba prev = rgba(b, 128, 200, 77);
      const Texel t = texel(BaseFormat::RGB, {a, 255, 90});
      const long long d = (2LL * a - 255) * (2LL * b - 255) + (255LL) * (1) + (2LL * 90 - 255) * (2LL * 200 - 255);
      // d/65025 clamped to [0,1], times 255, rounded half up: (2·d·255 + 65025) / 130050.
      const long long code = d <= 0 ? 0 : (d >= 65025 ? 255 : (2 * d * 255 + 65025) / 130050);
      const Rgba r = texture_environment(e, prev, none, t, kC8);
      REQUIRE_MESSAGE(static_cast<long long>(r.code[0]) == code, a << " . " << b);
      CHECK(r.code[1] == r.code[0]);
      CHECK(r.code[3] == 255);  // DOT3_RGB: alpha from COMBINE_ALPHA (REPLACE of TEXTURE alpha = 1)
    }
  // Texel (255,128,128) · previous (159,128,128): terms 255·63 + 1·1 + 1·1 = 16067, d = 16067/65025.
  const Texel t = texel(BaseFormat::RGB, {255, 128, 128});
  const Rgba p = rgba(159, 128, 128, 0);
  e.rgb_scale = 2;
  CHECK(texture_environment(e, p, none, t, kC8).code[0] == 126);  // ARB: 2·16067·255/65025 = 126.016 -> 126
  e.combine_rgb = gl::DOT3_RGB_EXT;
  CHECK(texture_environment(e, p, none, t, kC8).code[0] == 63);  // EXT ignores RGB_SCALE: 63.008 -> 63
  e.combine_rgb = gl::DOT3_RGBA;
  e.alpha_scale = 1;
  const Rgba r = texture_environment(e, p, none, t, kC8);
  CHECK(r.code[0] == 126);  // RGB_SCALE 2 still applies to RGB
  CHECK(r.code[3] == 63);   // DOT3_RGBA: the dot product in alpha, scaled by ALPHA_SCALE (1 here)
}

TEST_CASE("texenv: colour sum adds RGB, clamps at 1, keeps primary alpha") {
  const Rgba r = color_sum(rgba(200, 10, 0, 77), rgba(100, 20, 0, 255), kC8);
  CHECK(r.code == std::array<std::uint32_t, 4>{255, 30, 0, 77});
  const Rgba f = color_sum(rgba(200, 10, 0, 77), rgba(100, 20, 0, 255), kIdeal);
  CHECK(f.value[0] == 1.0);
  CHECK(f.value[1] == doctest::Approx(30 / 255.0));
  CHECK(f.value[3] == 77 / 255.0);
}

TEST_CASE("texenv: ideal profile evaluates in binary64 without rounding to codes") {
  TexEnvState e = combine(gl::ADD_SIGNED, gl::REPLACE);
  Rgba prev, prim;
  prev.value = {0.3, 0.5, 0.9, 1};
  Texel t = expand_texel(BaseFormat::RGB, {0.4, 0.1, 0.8, 0});
  const Rgba r = texture_environment(e, prev, prim, t, kIdeal);
  CHECK(r.value[0] == doctest::Approx(0.2));
  CHECK(r.value[1] == doctest::Approx(0.1));
  CHECK(r.value[2] == 1.0);  // 1.2 clamped
}

// The span paths of texturing against the per-fragment stages:
//  - sample_span_fixed (pipeline/texture/texture_sample.cpp) == sample_texture
//    on random 2D textures (every base format, 1..64 texels a side, border 0/1,
//    NEAREST/LINEAR, every wrap, weight bits 1..16, texel widths 1..16) at random
//    coordinates (texel centres, edges, far outside, negative, ±inf, NaN; whole
//    spans of texel centres);
//  - texture_environment_span_fixed (pipeline/texenv/texenv.cpp) ==
//    texture_environment on random environments (every classic mode and base
//    format, every COMBINE function, source, operand and scale, DOT3 ARB/EXT)
//    and random codes at widths 1..16.
#include <doctest/doctest.h>

#include <cmath>
#include <ios>
#include <limits>
#include <random>
#include <vector>

#include "pipeline/texenv/texenv.h"
#include "pipeline/texture/texture_sample.h"

using namespace ffsim;

namespace {

template <class T, std::size_t N>
T pick(std::mt19937& g, const T (&a)[N]) { return a[g() % N]; }

const BaseFormat kBases[] = {BaseFormat::Alpha, BaseFormat::Luminance, BaseFormat::LuminanceAlpha,
                             BaseFormat::Intensity, BaseFormat::RGB, BaseFormat::RGBA};

TextureObject random_texture(std::mt19937& g, int bits) {
  TextureObject t;
  TextureImage im;
  im.border = g() % 4 == 0 ? 1 : 0;
  const int w = 1 << (g() % 7), h = 1 << (g() % 7);
  im.width = w + 2 * im.border;
  im.height = h + 2 * im.border;
  im.base = pick(g, kBases);
  im.bits = bits;
  const std::uint32_t max = (1u << bits) - 1;
  im.codes.resize(static_cast<std::size_t>(im.width) * static_cast<std::size_t>(im.height) * component_count(im.base));
  for (auto& k : im.codes) k = static_cast<std::uint16_t>(g() % 5 == 0 ? (g() % 2) * max : g() % (max + 1));
  t.levels.push_back(im);
  const GLenum filters[] = {gl::NEAREST, gl::LINEAR};
  const GLenum wraps[] = {gl::REPEAT, gl::CLAMP, gl::CLAMP_TO_EDGE};
  t.params.min_filter = t.params.mag_filter = pick(g, filters);
  t.params.wrap_s = pick(g, wraps);
  t.params.wrap_t = pick(g, wraps);
  std::uniform_real_distribution<double> u(0, 1);
  for (double& c : t.params.border_color) c = u(g);
  return t;
}

double random_coord(std::mt19937& g, int size) {
  std::uniform_real_distribution<double> u(-3, 3);
  switch (g() % 8) {
    case 0: return (static_cast<int>(g() % (4 * size)) - size + 0.5) / size;  // texel centres
    case 1: return static_cast<double>(static_cast<int>(g() % (4 * size)) - size) / size;  // texel edges
    case 2: return u(g) * 1e7;
    case 3: return g() % 2 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
    case 4: return g() % 2 ? std::nan("") : -0.0;
    default: return u(g);
  }
}

// repeat_linear: every texture LINEAR with REPEAT on both axes (the two-pass
// kernel span_linear_repeat, for every base format and width).
void compare_sampling(unsigned seed, int iterations, bool repeat_linear = false) {
  std::mt19937 g(seed);
  int linear = 0;
  for (int it = 0; it < iterations; ++it) {
    const int bits = it % 3 == 0 ? 1 + static_cast<int>(g() % 16) : 8;
    TextureObject tex = random_texture(g, bits);
    if (repeat_linear) {
      tex.params.min_filter = tex.params.mag_filter = gl::LINEAR;
      tex.params.wrap_s = tex.params.wrap_t = gl::REPEAT;
    }
    const SampleFormat fmt{Arithmetic::Fixed, it % 4 == 0 ? 1 + static_cast<int>(g() % 16) : 8};
    REQUIRE(sample_span_supported(tex, 2, fmt));
    linear += tex.params.mag_filter == gl::LINEAR;
    const int n = 1 + static_cast<int>(g() % 40);
    std::vector<double> s(static_cast<std::size_t>(n)), t(static_cast<std::size_t>(n));
    const bool row = g() % 2;  // one t for the whole span (the constant-t shortcut)
    // Texel-aligned spans: every coordinate a texel centre, so every LINEAR weight
    // is 0 (the one-texel shortcut of span_linear_repeat).
    const bool aligned = g() % 5 == 0;
    // In order: consecutive texel centres along s (one pixel per texel, wrapping
    // around the row: the row-copy shortcut of span_linear_repeat).
    const bool in_order = aligned && g() % 2;
    const int ws = level_width(tex.levels[0]), hs = level_height(tex.levels[0], 2);
    const int start = static_cast<int>(g() % (4 * ws)) - ws;
    for (int f = 0; f < n; ++f) {
      s[static_cast<std::size_t>(f)] = in_order  ? (start + f + 0.5) / ws
                                       : aligned ? (static_cast<int>(g() % (4 * ws)) - ws + 0.5) / ws
                                                 : random_coord(g, ws);
      t[static_cast<std::size_t>(f)] = row && f > 0 ? t[0]
                                       : aligned ? (static_cast<int>(g() % (4 * hs)) - hs + 0.5) / hs
                                                 : random_coord(g, hs);
    }
    std::vector<std::uint16_t> out(4 * static_cast<std::size_t>(n));
    // The span sampler takes the binary32 values sample_texture rounds s and t to.
    const std::vector<float> sf(s.begin(), s.end()), tf(t.begin(), t.end());
    sample_span_fixed(tex, 2, sf.data(), tf.data(), n, fmt, out.data());
    for (int f = 0; f < n; ++f) {
      const Texel want = sample_texture(tex, 2, s[static_cast<std::size_t>(f)], t[static_cast<std::size_t>(f)], 0.0, fmt);
      for (int c = 0; c < 4; ++c) {
        INFO("iteration ", it, " fragment ", f, " s ", s[static_cast<std::size_t>(f)], " t ", t[static_cast<std::size_t>(f)]);
        REQUIRE(out[4 * static_cast<std::size_t>(f) + static_cast<std::size_t>(c)] == want.code[static_cast<std::size_t>(c)]);
      }
    }
  }
  CHECK(linear > iterations / 4);
}

// LINEAR with REPEAT at the limits of span_linear_repeat's 16-bit pair sums
// (linear_repeat_pairs, and the one-component gather path): texel codes of up to
// 15 bits and weights of up to 14 take pmaddwd; 16-bit codes or 15-bit weights
// (where 1 − a = 2^15 does not fit int16) must not. Codes at the extremes, many
// coordinates at texel centres (a = 0, so 1 − a = 2^B) or just past them, spans
// long enough for several groups of eight and several 64-fragment chunks.
void compare_pair_limits(unsigned seed, int bits, int B, int iterations) {
  std::mt19937 g(seed);
  const std::uint32_t max = (1u << bits) - 1;
  const BaseFormat bases[] = {BaseFormat::RGBA, BaseFormat::RGB, BaseFormat::Luminance, BaseFormat::Alpha};
  for (int it = 0; it < iterations; ++it) {
    TextureObject tex;
    TextureImage im;
    im.border = g() % 4 == 0 ? 1 : 0;
    const int w = 2 << (g() % 6), h = 1 << (g() % 7);
    im.width = w + 2 * im.border;
    im.height = h + 2 * im.border;
    im.base = bases[it % 4];
    im.bits = bits;
    im.codes.resize(static_cast<std::size_t>(im.width) * static_cast<std::size_t>(im.height) * component_count(im.base));
    for (auto& k : im.codes) k = static_cast<std::uint16_t>(g() % 3 ? max - g() % 2 : g() % (max + 1));
    tex.levels.push_back(im);
    tex.params.min_filter = tex.params.mag_filter = gl::LINEAR;
    tex.params.wrap_s = tex.params.wrap_t = gl::REPEAT;
    const SampleFormat fmt{Arithmetic::Fixed, B};
    const int n = 1 + static_cast<int>(g() % 200);
    const bool row = g() % 2;
    std::vector<double> s(static_cast<std::size_t>(n)), t(s.size());
    auto coord = [&](int size) {
      const double centre = (static_cast<int>(g() % (3 * size)) - size + 0.5) / size;
      switch (g() % 3) {
        case 0: return centre;                                                      // a = 0
        case 1: return centre + std::ldexp(1.0, -B) / size * (1 + g() % 3);         // a = 1, 2, 3 / 2^B
        default: return centre + (static_cast<double>(g() % 1000) / 1000.0) / size;  // anywhere in the texel
      }
    };
    for (int f = 0; f < n; ++f) {
      s[static_cast<std::size_t>(f)] = coord(w);
      t[static_cast<std::size_t>(f)] = row && f > 0 ? t[0] : coord(h);
    }
    const std::vector<float> sf(s.begin(), s.end()), tf(t.begin(), t.end());
    std::vector<std::uint16_t> out(4 * static_cast<std::size_t>(n));
    sample_span_fixed(tex, 2, sf.data(), tf.data(), n, fmt, out.data());
    for (int f = 0; f < n; ++f) {
      const Texel want = sample_texture(tex, 2, sf[static_cast<std::size_t>(f)], tf[static_cast<std::size_t>(f)], 0.0, fmt);
      for (int c = 0; c < 4; ++c) {
        INFO("bits ", bits, " B ", B, " iteration ", it, " fragment ", f);
        REQUIRE(out[4 * static_cast<std::size_t>(f) + static_cast<std::size_t>(c)] == want.code[static_cast<std::size_t>(c)]);
      }
    }
  }
}

TexEnvState random_env(std::mt19937& g) {
  TexEnvState e;
  const GLenum modes[] = {gl::REPLACE, gl::MODULATE, gl::DECAL, gl::BLEND, gl::ADD, gl::COMBINE, gl::COMBINE};
  const GLenum rgb[] = {gl::REPLACE, gl::MODULATE, gl::ADD, gl::ADD_SIGNED, gl::INTERPOLATE, gl::SUBTRACT,
                        gl::DOT3_RGB, gl::DOT3_RGBA, gl::DOT3_RGB_EXT, gl::DOT3_RGBA_EXT};
  const GLenum alpha[] = {gl::REPLACE, gl::MODULATE, gl::ADD, gl::ADD_SIGNED, gl::INTERPOLATE, gl::SUBTRACT};
  const GLenum srcs[] = {gl::TEXTURE, gl::CONSTANT, gl::PRIMARY_COLOR, gl::PREVIOUS};
  const GLenum ops_rgb[] = {gl::SRC_COLOR, gl::ONE_MINUS_SRC_COLOR, gl::SRC_ALPHA, gl::ONE_MINUS_SRC_ALPHA};
  const GLenum ops_a[] = {gl::SRC_ALPHA, gl::ONE_MINUS_SRC_ALPHA};
  const double scales[] = {1, 2, 4};
  e.mode = pick(g, modes);
  std::uniform_real_distribution<double> u(0, 1);
  for (double& c : e.color) c = g() % 4 == 0 ? static_cast<double>(g() % 2) : u(g);
  e.combine_rgb = pick(g, rgb);
  e.combine_alpha = pick(g, alpha);
  for (int i = 0; i < 3; ++i) {
    e.source_rgb[i] = pick(g, srcs);
    e.source_alpha[i] = pick(g, srcs);
    e.operand_rgb[i] = pick(g, ops_rgb);
    e.operand_alpha[i] = pick(g, ops_a);
  }
  e.rgb_scale = pick(g, scales);
  e.alpha_scale = pick(g, scales);
  return e;
}

// Returns how many fragments differ between the span kernel and the reference.
// dot3: COMBINE with a DOT3 function, the alpha REPLACE half of the time (the
// 8-bit DOT3 kernel, combine_dot3_span_8). Spans of 1 .. max_n fragments.
int compare_env(std::mt19937& g, int bits, bool plant, bool dot3 = false, int max_n = 24) {
  TexEnvState env = random_env(g);
  if (dot3) {
    const GLenum f[] = {gl::DOT3_RGB, gl::DOT3_RGBA, gl::DOT3_RGB_EXT, gl::DOT3_RGBA_EXT};
    env.mode = gl::COMBINE;
    env.combine_rgb = pick(g, f);
    if (g() % 2) env.combine_alpha = gl::REPLACE;
  }
  const BaseFormat base = pick(g, kBases);
  const ColorFormat fmt{Arithmetic::Fixed, bits};
  const std::uint32_t max = (1u << bits) - 1;
  const int n = 1 + static_cast<int>(g() % static_cast<unsigned>(max_n));
  std::vector<std::uint16_t> prev(4 * static_cast<std::size_t>(n)), prim(prev.size()), tex(prev.size()), out(prev.size());
  for (auto* v : {&prev, &prim, &tex})
    for (auto& k : *v) k = static_cast<std::uint16_t>(g() % 4 == 0 ? (g() % 2) * max : g() % (max + 1));
  for (int f = 0; f < n; ++f) {  // texels as sampling expands them (Table 3.23)
    std::uint16_t* t = &tex[4 * static_cast<std::size_t>(f)];
    std::array<std::uint32_t, 4> comps{t[0], t[1], t[2], t[3]};
    const Texel e = expand_texel(base, bits, comps);
    for (int c = 0; c < 4; ++c) t[c] = static_cast<std::uint16_t>(e.code[static_cast<std::size_t>(c)]);
  }
  const bool in_place = g() % 2;
  std::vector<std::uint16_t> prev_copy = prev;
  std::uint16_t* dst = in_place ? prev.data() : out.data();
  REQUIRE(texture_environment_span_fixed(env, base, bits, prev.data(), prim.data(), tex.data(), n, fmt, dst));
  if (plant) env.rgb_scale = env.rgb_scale == 1 ? 2 : 1;  // the reference computes another state
  int differing = 0;
  for (int f = 0; f < n; ++f) {
    const std::size_t o = 4 * static_cast<std::size_t>(f);
    Rgba p, q;
    Texel t;
    t.base = base;
    t.bits = bits;
    for (int c = 0; c < 4; ++c) {
      p.code[static_cast<std::size_t>(c)] = prev_copy[o + static_cast<std::size_t>(c)];
      q.code[static_cast<std::size_t>(c)] = prim[o + static_cast<std::size_t>(c)];
      t.code[static_cast<std::size_t>(c)] = tex[o + static_cast<std::size_t>(c)];
    }
    const Rgba want = texture_environment(env, p, q, t, fmt);
    bool same = true;
    for (int c = 0; c < 4; ++c) same &= dst[o + static_cast<std::size_t>(c)] == want.code[static_cast<std::size_t>(c)];
    if (!same && !plant) {
      FAIL_CHECK("span kernel != texture_environment: mode " << env.mode << " rgb " << env.combine_rgb
                                                            << " alpha " << env.combine_alpha << " bits " << bits
                                                            << " fragment " << f);
      return 1;
    }
    differing += !same;
  }
  return differing;
}

}  // namespace

TEST_CASE("fast texture: sample_span_fixed == sample_texture, random textures and coordinates") {
  compare_sampling(41, 3000);
}

TEST_CASE("fast texture: sample_span_fixed == sample_texture, LINEAR and REPEAT on both axes") {
  compare_sampling(44, 3000, true);
}

TEST_CASE("fast texture: LINEAR and REPEAT at the limits of the 16-bit pair sums (texel bits, weight bits)") {
  // (bits, B) with bits + 2B <= 31 (span_linear_repeat's 32-bit sums): the
  // first five take the pair sums, the last three must not.
  const int cases[][2] = {{8, 8}, {15, 8}, {1, 14}, {3, 14}, {14, 8}, {16, 7}, {16, 1}, {1, 15}};
  unsigned seed = 60;
  for (const auto& c : cases) compare_pair_limits(seed++, c[0], c[1], 400);
}

TEST_CASE("fast texture: texture_environment_span_fixed == texture_environment, widths 8, 10, 12 and odd") {
  std::mt19937 g(42);
  for (int it = 0; it < 6000; ++it) {
    const int bits = it % 4 == 0 ? 8 : it % 4 == 1 ? 10 : it % 4 == 2 ? 12 : 1 + static_cast<int>(g() % 16);
    REQUIRE(compare_env(g, bits, false) == 0);
  }
}

TEST_CASE("fast texture: 8-bit DOT3 environments (every source, operand, scale, in place or not) == texture_environment") {
  std::mt19937 g(45);
  for (int it = 0; it < 4000; ++it) REQUIRE(compare_env(g, 8, false, true) == 0);
  // spans longer than the kernel's blocks of 256 fragments (reads, then writes)
  for (int it = 0; it < 300; ++it) REQUIRE(compare_env(g, 8, false, true, 800) == 0);
  int detected = 0;  // and a planted difference (another RGB scale) is seen
  for (int it = 0; it < 200; ++it) detected += compare_env(g, 8, true, true) > 0;
  CHECK(detected > 50);
}

TEST_CASE("fast texture: 8-bit DOT3 of texture and primary colour, every pair of red codes, every scale") {
  // The bump-mapping case (both arguments vary, colour operands): red codes
  // (x, y) over all 256 x 256 pairs, green and blue chosen so that their products
  // cancel ((2·128 − 255)(2·128 − 255) + (2·128 − 255)(2·127 − 255) = 0), so the
  // sum is (2x − 255)(2y − 255): every product of two odd factors in [−255, 255],
  // through the 8-wide sums and the binary32 rounding of finish. Alpha REPLACE
  // of the primary alpha, or the dot product (DOT3_RGBA).
  const ColorFormat fmt{Arithmetic::Fixed, 8};
  for (const GLenum f : {gl::DOT3_RGB, gl::DOT3_RGBA})
    for (const double scale : {1.0, 2.0, 4.0}) {
      TexEnvState env;
      env.mode = gl::COMBINE;
      env.combine_rgb = f;
      env.combine_alpha = gl::REPLACE;
      env.source_rgb[0] = gl::TEXTURE;
      env.source_rgb[1] = gl::PRIMARY_COLOR;
      env.operand_rgb[0] = env.operand_rgb[1] = gl::SRC_COLOR;
      env.source_alpha[0] = gl::PRIMARY_COLOR;
      env.operand_alpha[0] = gl::SRC_ALPHA;
      env.rgb_scale = env.alpha_scale = scale;
      for (int x = 0; x < 256; ++x) {
        const int n = 256;
        std::vector<std::uint16_t> tex(4 * n), prim(4 * n), prev(4 * n, 0), out(4 * n);
        for (int y = 0; y < n; ++y) {
          const std::size_t o = 4 * static_cast<std::size_t>(y);
          tex[o] = static_cast<std::uint16_t>(x), tex[o + 1] = 128, tex[o + 2] = 128, tex[o + 3] = 255;
          prim[o] = static_cast<std::uint16_t>(y), prim[o + 1] = 128, prim[o + 2] = 127;
          prim[o + 3] = static_cast<std::uint16_t>((x + y) & 255);
        }
        REQUIRE(texture_environment_span_fixed(env, BaseFormat::RGBA, 8, prev.data(), prim.data(), tex.data(), n, fmt,
                                               out.data()));
        for (int y = 0; y < n; ++y) {
          const std::size_t o = 4 * static_cast<std::size_t>(y);
          Rgba p, q;
          Texel t;
          t.base = BaseFormat::RGBA;
          t.bits = 8;
          for (std::size_t c = 0; c < 4; ++c) {
            q.code[c] = prim[o + c];
            t.code[c] = tex[o + c];
          }
          const Rgba want = texture_environment(env, p, q, t, fmt);
          for (std::size_t c = 0; c < 4; ++c) {
            INFO("x ", x, " y ", y, " scale ", scale, " channel ", c);
            REQUIRE(out[o + c] == want.code[c]);
          }
        }
      }
    }
}

TEST_CASE("fast texture: the environment comparison detects a planted difference, and other widths are refused") {
  std::mt19937 g(43);
  int differing = 0;
  for (int it = 0; it < 300; ++it) differing += compare_env(g, 8, true) > 0;
  CHECK(differing > 30);
  TexEnvState env;
  std::uint16_t a[4] = {1, 2, 3, 4};
  CHECK_FALSE(texture_environment_span_fixed(env, BaseFormat::RGBA, 8, a, a, a, 1, ColorFormat{Arithmetic::Fixed, 10}, a));
  CHECK_FALSE(texture_environment_span_fixed(env, BaseFormat::RGBA, 8, a, a, a, 1, ColorFormat{Arithmetic::Float32, 8}, a));
}

// The bilinear-before-squaring example of Kautz, Heidrich, Daubert,
// "Bump Map Shadows for OpenGL Rendering" §5 (../shared/papers/001_*.txt):
// a 2x1 texture holding -1 and +1, stored biased as codes 0 and 255, magnified
// with LINEAR so that texel centres land two pixels apart (a span twice as wide
// as the texture), expanded to [-1, 1] and squared per fragment.
//
// Span: pixels x = 0..3 with centres x + 1/2 and u = 2s = x/2 (s = x/4, i.e. a
// quad from x = 0 to 4 with s from -1/8 to 7/8; the sim test in
// tests/sim/test_draw_paper_example.cpp draws exactly that). The three
// characteristic pixels are x = 1 (u = 0.5, the centre of texel 0), x = 2
// (u = 1, midway) and x = 3 (u = 1.5, the centre of texel 1).
//
// Here the expansion and squaring are done in the test on the filtered texel
// codes that sample_level produces: e = (2k - 255)/255 exactly, e² rounded half
// up to 8 bits: rnd(255·e²) = rnd((2k - 255)² / 255).
#include <doctest/doctest.h>

#include "pipeline/texture/texture_sample.h"

using namespace ffsim;

namespace {

TextureObject two_texels(std::uint16_t k0, std::uint16_t k1) {
  TextureObject t;
  TextureImage im;
  im.width = 2;
  im.height = 1;
  im.base = BaseFormat::Luminance;
  im.bits = 8;
  im.codes = {k0, k1};
  im.values = {k0 / 255.0, k1 / 255.0};
  t.levels.push_back(im);
  t.params.min_filter = t.params.mag_filter = gl::LINEAR;
  t.params.wrap_s = gl::CLAMP_TO_EDGE;
  return t;
}

std::uint32_t square_expanded(std::uint32_t k) {
  const std::int64_t e = 2 * static_cast<std::int64_t>(k) - 255;  // 255·(expanded value)
  return static_cast<std::uint32_t>((2 * e * e + 255) / 510);      // rnd(e²/255)
}

}  // namespace

TEST_CASE("paper example: squaring after bilinear interpolation gives 1, 0, 1 (geforce256)") {
  const SampleFormat fx{Arithmetic::Fixed, 8};
  const TextureObject t = two_texels(0, 255);
  std::array<std::uint32_t, 4> filtered{}, squared{};
  for (int x = 0; x < 4; ++x) {
    filtered[x] = sample_level(t, 0, 1, gl::LINEAR, x / 4.0, 0, fx).code[0];
    squared[x] = square_expanded(filtered[x]);
  }
  // Filtered codes: u = 0 clamps to texel 0; u = 0.5: weight 0 -> 0; u = 1: a = 128,
  // (255·128 + 128) >> 8 = 128 (the real value 127.5 rounds half up); u = 1.5 -> 255.
  CHECK(filtered == std::array<std::uint32_t, 4>{0, 0, 128, 255});
  // Squared: e = -1, -1, +1/255, +1 -> e² = 1, 1, 1/65025, 1 -> codes 255, 255, 0, 255.
  CHECK(squared == std::array<std::uint32_t, 4>{255, 255, 0, 255});
}

TEST_CASE("paper example: ideal profile gives exactly 1, 0, 1") {
  const SampleFormat fl{Arithmetic::Float64, 8};
  const TextureObject t = two_texels(0, 255);
  std::array<double, 3> sq{};
  for (int x = 1; x <= 3; ++x) {
    const double v = sample_level(t, 0, 1, gl::LINEAR, x / 4.0, 0, fl).value[0];
    const double e = 2 * v - 1;
    sq[x - 1] = e * e;
  }
  CHECK(sq == std::array<double, 3>{1.0, 0.0, 1.0});  // midpoint 0.5 exactly -> e = 0
}

TEST_CASE("paper example: squaring first (pre-squared texture) gives 1 everywhere") {
  // (-1)² = (+1)² = 1 is stored as code 255 in both texels; LINEAR of 255 and 255 is 255.
  const SampleFormat fx{Arithmetic::Fixed, 8};
  const TextureObject t = two_texels(255, 255);
  for (int x = 0; x < 4; ++x) CHECK(sample_level(t, 0, 1, gl::LINEAR, x / 4.0, 0, fx).code[0] == 255);
}

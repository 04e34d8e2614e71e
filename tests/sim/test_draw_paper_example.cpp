// The paper's bilinear-before-squaring example (Kautz, Heidrich, Daubert §5)
// drawn end to end: glBegin(QUADS) over pixels x = 0..3 of a 4x1 window with
// s from -1/8 to 7/8, so that pixel centres sample u = 2s = 0, 0.5, 1, 1.5 of a
// 2x1 texture (LINEAR, CLAMP_TO_EDGE). The expansion to [-1,1] and the squaring
// happen in the texture environment: COMBINE DOT3_RGB with TEXTURE as both
// arguments, on an RGB texture whose R holds the signed value (codes 0 = -1 and
// 255 = +1) and whose G, B hold 128. DOT3 computes
//   d = ((2R-255)² + (2G-255)² + (2B-255)²) / 65025,
// i.e. the square of R's expanded value plus 2/65025 from G and B (128 expands
// to +1/255: an 8-bit zero does not exist), clamped to [0,1].
#include <doctest/doctest.h>

#include "draw_test_util.h"

using namespace ffsim;
using namespace ffsim::test;

namespace {

void draw_example(Context& ctx, std::uint16_t r0, std::uint16_t r1) {
  ortho_window(ctx);
  set_level(ctx, gl::TEXTURE_2D, 0, BaseFormat::RGB, 2, 1, {r0, 128, 128, r1, 128, 128});
  ctx.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MIN_FILTER, gl::LINEAR);
  ctx.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MAG_FILTER, gl::LINEAR);
  ctx.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_WRAP_S, gl::CLAMP_TO_EDGE);
  ctx.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_WRAP_T, gl::CLAMP_TO_EDGE);
  ctx.enable(gl::TEXTURE_2D);
  ctx.texEnvi(gl::TEXTURE_ENV, gl::TEXTURE_ENV_MODE, gl::COMBINE);
  ctx.texEnvi(gl::TEXTURE_ENV, gl::COMBINE_RGB, gl::DOT3_RGB);
  ctx.texEnvi(gl::TEXTURE_ENV, gl::SOURCE0_RGB, gl::TEXTURE);
  ctx.texEnvi(gl::TEXTURE_ENV, gl::SOURCE1_RGB, gl::TEXTURE);
  ctx.begin(gl::QUADS);
  ctx.texCoord2(-0.125, 0.5);
  ctx.vertex2(0, 0);
  ctx.texCoord2(0.875, 0.5);
  ctx.vertex2(4, 0);
  ctx.vertex2(4, 1);
  ctx.texCoord2(-0.125, 0.5);
  ctx.vertex2(0, 1);
  ctx.end();
}

}  // namespace

TEST_CASE("paper example drawn: squaring after interpolation gives 255, 0, 255 on geforce256") {
  Context ctx(profile_named("geforce256"), 4, 1);
  draw_example(ctx, 0, 255);
  // Filtered R at u = 0, 0.5, 1, 1.5: 0, 0, 128 (127.5 rounded up), 255 (pipeline test
  // test_texture_paper_example.cpp). DOT3: (65025 + 2)/65025 -> clamped to 1 -> 255;
  // at the midpoint (1 + 1 + 1)/65025 = 3/65025 -> 255·3/65025 = 0.0118 -> 0.
  CHECK(code_at(ctx, 0, 0, 0) == 255);
  CHECK(code_at(ctx, 1, 0, 0) == 255);  // texel 0's centre: (-1)² = 1
  CHECK(code_at(ctx, 2, 0, 0) == 0);    // midway: 0² (up to 3/65025)
  CHECK(code_at(ctx, 3, 0, 0) == 255);  // texel 1's centre: (+1)² = 1
}

TEST_CASE("paper example drawn: the ideal profile gives 1, 2/65025, 1 (the squared R term is exactly 0)") {
  Context ctx(profile_named("ideal"), 4, 1);
  draw_example(ctx, 0, 255);
  // Ideal: filtered R = 0.5 exactly at the midpoint; G = B = 128/255 expand to 1/255 each,
  // so the midpoint is 2/65025 (the G, B terms), not 0; the R term alone is 0.
  const auto& v = ctx.framebuffer().values();
  CHECK(v[4 * 1] == 1.0);
  CHECK(v[4 * 2] == doctest::Approx(2.0 / 65025).epsilon(1e-12));
  CHECK(v[4 * 3] == 1.0);
}

TEST_CASE("paper example drawn: pre-squared texels give 255 everywhere") {
  // Squaring first: (-1)² = (+1)² = 1, so both texels store +1 (code 255) and every
  // interpolated value is 255 -> DOT3 = (65025 + 2)/65025 -> 1 at every pixel.
  Context ctx(profile_named("geforce256"), 4, 1);
  draw_example(ctx, 255, 255);
  for (int x = 0; x < 4; ++x) CHECK(code_at(ctx, x, 0, 0) == 255);
}

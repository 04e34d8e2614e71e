// Register combiners in the draw path: with REGISTER_COMBINERS_NV enabled the
// combiners replace the texture environments (RC §3.8.11), reading the filtered
// texels of enabled units and the interpolated colours. Textures are uploaded
// through glTexImage2D, so this also checks the pixel path -> texture -> sampling
// -> combiners -> fragment operations chain end to end.
#include <doctest/doctest.h>

#include <vector>

#include "draw_test_util.h"
#include "sim/hash.h"

using namespace ffsim;
using namespace ffsim::test;

namespace {

// A 2x2 RGBA8 texture, NEAREST, drawn texel-aligned onto a 4x4 window (each texel
// covers 2x2 pixels).
const std::vector<std::uint8_t> kTexels = {10, 20, 30, 40,   200, 150, 100, 50,    // row 0 (t = 0)
                                           0, 255, 128, 127, 77, 88, 99, 111};     // row 1

void setup_texture(Context& ctx, int unit) {
  ctx.activeTexture(gl::TEXTURE0 + static_cast<GLenum>(unit));
  ctx.bindTexture(gl::TEXTURE_2D, 1 + static_cast<std::uint32_t>(unit));
  ctx.texImage2D(gl::TEXTURE_2D, 0, gl::RGBA8, 2, 2, 0, gl::RGBA, gl::UNSIGNED_BYTE, kTexels.data());
  ctx.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MIN_FILTER, gl::NEAREST);
  ctx.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MAG_FILTER, gl::NEAREST);
  ctx.enable(gl::TEXTURE_2D);
  ctx.activeTexture(gl::TEXTURE0);
}

void textured_quad(Context& ctx) {
  ctx.begin(gl::QUADS);
  ctx.multiTexCoord2(gl::TEXTURE0, 0, 0);
  ctx.multiTexCoord2(gl::TEXTURE1, 0, 0);
  ctx.vertex2(0, 0);
  ctx.multiTexCoord2(gl::TEXTURE0, 1, 0);
  ctx.multiTexCoord2(gl::TEXTURE1, 1, 0);
  ctx.vertex2(4, 0);
  ctx.multiTexCoord2(gl::TEXTURE0, 1, 1);
  ctx.multiTexCoord2(gl::TEXTURE1, 1, 1);
  ctx.vertex2(4, 4);
  ctx.multiTexCoord2(gl::TEXTURE0, 0, 1);
  ctx.multiTexCoord2(gl::TEXTURE1, 0, 1);
  ctx.vertex2(0, 4);
  ctx.end();
}

}  // namespace

TEST_CASE("draw with combiners: the initial combiner state passes the primary colour through") {
  // RC Table .5/.6 initial state: spare0 = primary (A = PRIMARY, B = 1), final
  // fcoc.rgb = fog.a*(spare0 + secondary) + (1 - fog.a)*fog.rgb with FOG.a = 1
  // (fog disabled) and a zero secondary colour, fcoc.a = spare0.a. So the colour
  // codes of glColor4(0.2, 0.4, 0.6, 0.8) = 51, 102, 153, 204 arrive unchanged.
  Context ctx(profile_named("geforce256"), 4, 4);
  ortho_window(ctx);
  ctx.enable(gl::REGISTER_COMBINERS_NV);
  ctx.color4(0.2, 0.4, 0.6, 0.8);
  quad(ctx, 0, 0, 4, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      CHECK(code_at(ctx, x, y, 0) == 51);
      CHECK(code_at(ctx, x, y, 1) == 102);
      CHECK(code_at(ctx, x, y, 2) == 153);
      CHECK(code_at(ctx, x, y, 3) == 204);
    }
  CHECK(ctx.getError() == gl::NO_ERROR);
}

TEST_CASE("draw with combiners: texture 0 RGB times 1 into spare0, texel codes reach the framebuffer") {
  // Stage 0 RGB: A = TEXTURE0 (UNSIGNED_IDENTITY), B = ZERO (UNSIGNED_INVERT = 1),
  // C = D = 0, sum -> spare0: spare0.rgb = tex0.rgb exactly (8-bit codes enter a
  // 9-bit register unchanged, numerics §2). Alpha keeps the initial spare0.a =
  // primary.a. Expected framebuffer = texel RGB codes, alpha = 255 (white primary).
  Context ctx(profile_named("geforce256"), 4, 4);
  ortho_window(ctx);
  setup_texture(ctx, 0);
  ctx.enable(gl::REGISTER_COMBINERS_NV);
  ctx.combinerInput(gl::COMBINER0_NV, gl::RGB, gl::VARIABLE_A_NV, gl::TEXTURE0, gl::UNSIGNED_IDENTITY_NV, gl::RGB);
  ctx.combinerInput(gl::COMBINER0_NV, gl::RGB, gl::VARIABLE_B_NV, gl::ZERO, gl::UNSIGNED_INVERT_NV, gl::RGB);
  ctx.color4(1, 1, 1, 1);
  textured_quad(ctx);
  REQUIRE(ctx.getError() == gl::NO_ERROR);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const std::size_t t = 4 * (static_cast<std::size_t>(y / 2) * 2 + static_cast<std::size_t>(x / 2));
      for (int c = 0; c < 3; ++c) CHECK(code_at(ctx, x, y, c) == kTexels[t + static_cast<std::size_t>(c)]);
      CHECK(code_at(ctx, x, y, 3) == 255);
    }
}

TEST_CASE("draw with combiners: dot product of two expanded textures into alpha, and planned == full path") {
  // Stage 0 RGB: spare0.rgb = dot(expand(tex0), expand(tex1)) (broadcast); the
  // final combiner's G reads spare0 with BLUE usage, so fcoc.a = max(0, dot). With the same texture on both units the dot
  // is |expand(t)|^2 per texel: sum over RGB of (2k-255)^2/65025, rounded once to
  // /255 at the register write (half away from zero), clamped to 1.
  for (const char* profile : {"geforce256", "ideal"}) {
    Context ctx(profile_named(profile), 4, 4);
    ortho_window(ctx);
    setup_texture(ctx, 0);
    setup_texture(ctx, 1);
    ctx.enable(gl::REGISTER_COMBINERS_NV);
    ctx.combinerInput(gl::COMBINER0_NV, gl::RGB, gl::VARIABLE_A_NV, gl::TEXTURE0, gl::EXPAND_NORMAL_NV, gl::RGB);
    ctx.combinerInput(gl::COMBINER0_NV, gl::RGB, gl::VARIABLE_B_NV, gl::TEXTURE1, gl::EXPAND_NORMAL_NV, gl::RGB);
    ctx.combinerOutput(gl::COMBINER0_NV, gl::RGB, gl::SPARE0_NV, gl::DISCARD_NV, gl::DISCARD_NV, gl::NONE, gl::NONE,
                       true, false, false);
    ctx.finalCombinerInput(gl::VARIABLE_G_NV, gl::SPARE0_NV, gl::UNSIGNED_IDENTITY_NV, gl::BLUE);
    textured_quad(ctx);
    REQUIRE(ctx.getError() == gl::NO_ERROR);
    for (int ty = 0; ty < 2; ++ty)
      for (int tx = 0; tx < 2; ++tx) {
        const std::size_t t = 4 * (static_cast<std::size_t>(ty) * 2 + static_cast<std::size_t>(tx));
        long long num = 0;  // 65025 * dot
        for (int c = 0; c < 3; ++c) {
          const long long e = 2LL * kTexels[t + static_cast<std::size_t>(c)] - 255;
          num += e * e;
        }
        const double exact = static_cast<double>(num) / 65025.0;
        if (ctx.profile().is_fixed()) {
          // register write: round(num / 255) half up (num >= 0), clamp to 255; final
          // combiner converts the /255 register code to the 8-bit alpha exactly.
          const long long reg = std::min<long long>((2 * num + 255) / 510, 255);
          CHECK(code_at(ctx, 2 * tx, 2 * ty, 3) == reg);
        } else {
          const double a = ctx.framebuffer().values()[4 * ctx.framebuffer().index(2 * tx, 2 * ty) + 3];
          CHECK(a == doctest::Approx(std::min(exact, 1.0)).epsilon(1e-12));
        }
      }
    // The planned path (units the combiners read, portions with live outputs)
    // equals the full path bit for bit.
    const auto planned = buffer_hash(ctx.framebuffer(), BufferKind::Color);
    ctx.set_full_shading(true);
    ctx.clear(gl::COLOR_BUFFER_BIT);
    textured_quad(ctx);
    CHECK(buffer_hash(ctx.framebuffer(), BufferKind::Color) == planned);
  }
}

// The paper's hard-shadow steps 12-16 (Kautz et al. §4.1.5) across three areas:
// CopyPixels (pixel path) generates fragments that go through the alpha test and
// the stencil operation (per-fragment operations), GL121 §4.3.3 and §4.1.
#include <doctest/doctest.h>

#include "draw_test_util.h"

using namespace ffsim;
using namespace ffsim::test;

TEST_CASE("copy pixels: alpha test EQUAL 0 then stencil INCR marks exactly the zero-alpha pixels") {
  Context ctx(profile_named("geforce256"), 8, 4);
  // Alpha pattern written as in step 11: 0 (shadow) where (x + y) % 3 == 0, else x*30 + 1.
  Framebuffer& fb = ctx.framebuffer();
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) {
      const std::size_t i = 4 * fb.index(x, y);
      fb.codes()[i + 0] = static_cast<std::uint16_t>(10 * x);
      fb.codes()[i + 3] = static_cast<std::uint16_t>((x + y) % 3 == 0 ? 0 : x * 30 + 1);
    }
  ortho_window(ctx);
  ctx.enable(gl::ALPHA_TEST);
  ctx.alphaFunc(gl::EQUAL, 0.0);               // step 12: pass when alpha equals 0
  ctx.enable(gl::STENCIL_TEST);
  ctx.stencilFunc(gl::ALWAYS, 0, 0xFF);
  ctx.stencilOp(gl::KEEP, gl::KEEP, gl::INCR);  // step 13
  ctx.rasterPos2(0, 0);
  ctx.copyPixels(0, 0, 8, 4, gl::COLOR);        // step 14
  REQUIRE(ctx.getError() == gl::NO_ERROR);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) {
      INFO("x=" << x << " y=" << y);
      CHECK(fb.stencil()[fb.index(x, y)] == ((x + y) % 3 == 0 ? 1 : 0));
      CHECK(code_at(ctx, x, y, 0) == 10 * x);  // the copy onto itself leaves colour unchanged
    }
  // Step 16: stencil test EQUAL 0 lets a later draw through only where lit.
  ctx.disable(gl::ALPHA_TEST);
  ctx.stencilFunc(gl::EQUAL, 0, 0xFF);
  ctx.stencilOp(gl::KEEP, gl::KEEP, gl::KEEP);
  ctx.color4(1, 1, 1, 1);
  quad(ctx, 0, 0, 8, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) CHECK(code_at(ctx, x, y, 1) == ((x + y) % 3 == 0 ? 0 : 255));
}

TEST_CASE("copy pixels: an active colour matrix re-transforms the copied alpha (why the traces reset it)") {
  // The paper leaves M and the lookup table set from step 2 when it reaches step
  // 14; CopyPixels runs the whole pixel transfer path (GL121 §4.3.3), so with
  // M still loaded the alpha test would see M applied again. Here a COLOR matrix
  // scaling alpha by 0.4: code 1 -> 0.4/255 -> final conversion rounds to 0, so
  // that pixel now passes EQUAL 0 (stencil 1, alpha written as 0); code 2 ->
  // 0.8/255 -> 1 fails and is discarded (alpha stays 2, stencil 0).
  Context ctx(profile_named("geforce256"), 3, 1);
  Framebuffer& fb = ctx.framebuffer();
  fb.codes()[4 * 0 + 3] = 0;
  fb.codes()[4 * 1 + 3] = 1;
  fb.codes()[4 * 2 + 3] = 2;
  ortho_window(ctx);
  ctx.matrixMode(gl::COLOR);
  const double m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0.4};
  ctx.loadMatrix(m);
  ctx.matrixMode(gl::MODELVIEW);
  ctx.enable(gl::ALPHA_TEST);
  ctx.alphaFunc(gl::EQUAL, 0.0);
  ctx.enable(gl::STENCIL_TEST);
  ctx.stencilFunc(gl::ALWAYS, 0, 0xFF);
  ctx.stencilOp(gl::KEEP, gl::KEEP, gl::INCR);
  ctx.rasterPos2(0, 0);
  ctx.copyPixels(0, 0, 3, 1, gl::COLOR);
  CHECK(fb.stencil()[0] == 1);
  CHECK(fb.stencil()[1] == 1);  // would be 0 without the matrix
  CHECK(fb.stencil()[2] == 0);
  CHECK(code_at(ctx, 1, 0, 3) == 0);  // the passing fragment wrote its transformed alpha
  CHECK(code_at(ctx, 2, 0, 3) == 2);  // the failing fragment was discarded
}

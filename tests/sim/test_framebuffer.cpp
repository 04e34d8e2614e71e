#include <doctest/doctest.h>

#include "pipeline/number/unorm.h"
#include "sim/context.h"
#include "sim/framebuffer.h"

using namespace ffsim;

TEST_CASE("framebuffer: sizes are validated with a reason") {
  FramebufferFormat f;
  f.width = 0;
  CHECK_THROWS_WITH_AS(Framebuffer{f}, "framebuffer 0x256: each side must be 1..16384", FramebufferError);
  f.width = 20000;
  CHECK_THROWS_AS(Framebuffer{f}, FramebufferError);
  f.width = 16384;
  f.height = 16384;  // 2^28 pixels > 2^26
  CHECK_THROWS_WITH_AS(Framebuffer{f}, "framebuffer 16384x16384: more than 67108864 pixels", FramebufferError);
  f.width = f.height = 1;
  CHECK_NOTHROW(Framebuffer{f});
}

TEST_CASE("framebuffer: store/read color at 8, 12 bits and float") {
  for (int bits : {8, 12}) {
    FramebufferFormat f;
    f.width = 4;
    f.height = 2;
    f.color_bits = bits;
    Framebuffer fb(f);
    fb.store_color_value(1, 1, 2, 0.5);
    CHECK(fb.codes()[4 * fb.index(1, 1) + 2] == (unorm_max(bits) + 1) / 2);  // 0.5 is a tie: rounds up
    fb.store_color_value(0, 0, 0, 7.0);
    CHECK(fb.color_value(0, 0, 0) == 1.0);  // clamped
    fb.store_color_value(0, 0, 1, -1.0);
    CHECK(fb.color_value(0, 0, 1) == 0.0);
  }
  FramebufferFormat f;
  f.color_arith = Arithmetic::Float32;
  Framebuffer fb(f);
  fb.store_color_value(3, 3, 0, 0.1);
  CHECK(fb.color_value(3, 3, 0) == static_cast<double>(0.1f));  // rounded to binary32
  f.color_arith = Arithmetic::Float64;
  Framebuffer fb64(f);
  fb64.store_color_value(3, 3, 0, 0.1);
  CHECK(fb64.color_value(3, 3, 0) == 0.1);
}

TEST_CASE("context: glClear honours clear values, color mask, stencil mask, scissor") {
  Context ctx(*find_builtin_profile("geforce256"), 8, 8);
  ctx.clearColor(1.0, 0.5, -3.0, 2.0);  // clamped at specification (§4.2.3)
  ctx.clearStencil(0x1FF);              // masked to 8 bits on use
  ctx.clearDepth(0.25);
  ctx.clear(gl::COLOR_BUFFER_BIT | gl::STENCIL_BUFFER_BIT | gl::DEPTH_BUFFER_BIT);
  const Framebuffer& fb = ctx.framebuffer();
  CHECK(fb.codes()[0] == 255);
  CHECK(fb.codes()[1] == 128);
  CHECK(fb.codes()[2] == 0);
  CHECK(fb.codes()[3] == 255);
  CHECK(fb.stencil()[0] == 0xFF);
  CHECK(fb.depth()[0] == unorm_from_double(0.25, 24));

  ctx.colorMask(false, true, false, false);
  ctx.stencilMask(0x0F);
  ctx.enable(gl::SCISSOR_TEST);
  ctx.scissor(2, 3, 2, 1);
  ctx.clearColor(0, 0, 0, 0);
  ctx.clearStencil(0);
  ctx.clear(gl::COLOR_BUFFER_BIT | gl::STENCIL_BUFFER_BIT);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const bool inside = x >= 2 && x < 4 && y == 3;
      const std::size_t i = fb.index(x, y);
      CHECK(fb.codes()[4 * i + 0] == 255);               // R masked off
      CHECK(fb.codes()[4 * i + 1] == (inside ? 0 : 128));  // G cleared inside the scissor box
      CHECK(fb.stencil()[i] == (inside ? 0xF0 : 0xFF));     // only the low 4 bits written
    }
  CHECK(ctx.getError() == gl::NO_ERROR);
}

TEST_CASE("context: GL errors are latched once, logged with the call site, state unchanged") {
  Context ctx(*find_builtin_profile("geforce256"), 4, 4);
  std::vector<std::string> seen;
  ctx.set_error_callback([&](const GLErrorEvent& e) { seen.push_back(e.str()); });
  ctx.set_call_site({"t.trace", 7, 1});
  ctx.scissor(0, 0, -1, 4);
  ctx.enable(0x1234);
  REQUIRE(seen.size() == 2);
  CHECK(seen[0] == "t.trace:7:1: glScissor: GL_INVALID_VALUE: width and height must not be negative (got -1, 4)");
  CHECK(seen[1] == "t.trace:7:1: glEnable: GL_INVALID_ENUM: 0x1234 is not a capability this context knows");
  CHECK(ctx.scissor_state().box.width == 4);  // unchanged by the failed call
  CHECK(ctx.getError() == gl::INVALID_VALUE);  // the first error
  CHECK(ctx.getError() == gl::NO_ERROR);
  ctx.clear(0x1);
  CHECK(ctx.getError() == gl::INVALID_VALUE);
}

TEST_CASE("context: matrix modes and stack errors") {
  Context ctx(*find_builtin_profile("geforce256"), 4, 4);
  ctx.matrixMode(gl::COLOR);
  ctx.scale(0.5, 0.5, 0.5);
  CHECK(ctx.color_matrix().top()[0][0] == 0.5);
  CHECK(ctx.modelview().top() == glm::dmat4(1.0));
  ctx.pushMatrix();
  ctx.pushMatrix();  // COLOR stack depth 2
  CHECK(ctx.getError() == gl::STACK_OVERFLOW);
  ctx.popMatrix();
  ctx.popMatrix();
  CHECK(ctx.getError() == gl::STACK_UNDERFLOW);
  ctx.matrixMode(0x1234);
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  CHECK(ctx.matrix_mode() == gl::COLOR);
}

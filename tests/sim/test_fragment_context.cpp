// The per-fragment entry points of the Context: initial state, enables, GL errors
// (GL 1.2.1 §2.5, §4.1; EXT_blend_*; EXT_stencil_wrap), the plan cache, and the
// paper's framebuffer-arithmetic sequences through write_fragments.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "sim/context.h"

using namespace ffsim;

namespace {

Context make(int w = 4, int h = 1, const char* profile = "geforce256") { return Context(*find_builtin_profile(profile), w, h); }

FragmentSpan row(int y, std::initializer_list<std::array<std::uint16_t, 4>> rgba, std::uint32_t z = 0) {
  FragmentSpan sp;
  sp.y = y;
  sp.count = static_cast<int>(rgba.size());
  for (const auto& c : rgba)
    for (std::uint16_t v : c) sp.codes.push_back(v);
  sp.depth.assign(rgba.size(), z);
  return sp;
}

// One colour for the whole row of a w-pixel framebuffer.
FragmentSpan fill(int w, std::array<std::uint16_t, 4> c) {
  FragmentSpan sp;
  sp.count = w;
  for (int i = 0; i < w; ++i)
    for (std::uint16_t v : c) sp.codes.push_back(v);
  sp.depth.assign(static_cast<std::size_t>(w), 0);
  return sp;
}

std::uint16_t px(const Context& ctx, int x, int c) { return ctx.framebuffer().codes()[4 * static_cast<std::size_t>(x) + c]; }

void expect_error(Context& ctx, const char* function) {
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  REQUIRE(!ctx.error_log().empty());
  CHECK(ctx.error_log().back().function == function);
  CHECK(ctx.getError() == gl::NO_ERROR);
}

}  // namespace

TEST_CASE("fragment state: GL 1.2.1 initial values and enables") {
  Context ctx = make();
  CHECK(ctx.isEnabled(gl::DITHER));  // §4.1.7: dithering is enabled initially
  for (GLenum cap : {gl::ALPHA_TEST, gl::STENCIL_TEST, gl::DEPTH_TEST, gl::BLEND, gl::COLOR_LOGIC_OP}) {
    CHECK(!ctx.isEnabled(cap));
    ctx.enable(cap);
    CHECK(ctx.isEnabled(cap));
    ctx.disable(cap);
    CHECK(!ctx.isEnabled(cap));
  }
  ctx.disable(gl::DITHER);
  CHECK(!ctx.isEnabled(gl::DITHER));
  CHECK(ctx.getError() == gl::NO_ERROR);
  const FragmentOpsState s = make().fragment_ops_state();
  CHECK(s.alpha.func == gl::ALWAYS);
  CHECK(s.alpha.ref == 0.0);
  CHECK(s.stencil.func == gl::ALWAYS);
  CHECK(s.stencil.ref == 0);
  CHECK(s.stencil.value_mask == 0xFFFFFFFFu);
  CHECK(s.stencil.sfail == gl::KEEP);
  CHECK(s.stencil.dpfail == gl::KEEP);
  CHECK(s.stencil.dppass == gl::KEEP);
  CHECK(s.depth.func == gl::LESS);
  CHECK(s.blend.src == gl::ONE);
  CHECK(s.blend.dst == gl::ZERO);
  CHECK(s.blend.equation == gl::FUNC_ADD);
  CHECK(s.blend.color == std::array<double, 4>{0, 0, 0, 0});
  CHECK(s.logic.op == gl::COPY);
}

TEST_CASE("fragment state: values are clamped when specified, stencil ref kept as given") {
  Context ctx = make();
  ctx.alphaFunc(gl::GREATER, 1.5);
  CHECK(ctx.fragment_ops_state().alpha.ref == 1.0);
  ctx.alphaFunc(gl::LESS, -2.0);
  CHECK(ctx.fragment_ops_state().alpha.ref == 0.0);
  ctx.blendColor(-1.0, 2.0, 0.5, 0.25);
  CHECK(ctx.fragment_ops_state().blend.color == std::array<double, 4>{0.0, 1.0, 0.5, 0.25});
  ctx.stencilFunc(gl::EQUAL, 300, 0x0F);
  CHECK(ctx.fragment_ops_state().stencil.ref == 300);  // clamped to 2^s - 1 only when used
  CHECK(ctx.fragment_ops_state().stencil.value_mask == 0x0Fu);
  CHECK(ctx.fragment_plan_constants().stencil_ref == 255);
  ctx.stencilOp(gl::INCR_WRAP, gl::DECR_WRAP, gl::INVERT);  // EXT_stencil_wrap tokens accepted
  CHECK(ctx.fragment_ops_state().stencil.sfail == gl::INCR_WRAP);
  CHECK(ctx.getError() == gl::NO_ERROR);
}

TEST_CASE("fragment GL errors: INVALID_ENUM and no state change") {
  Context ctx = make();
  const FragmentOpsState before = ctx.fragment_ops_state();
  ctx.alphaFunc(gl::BLEND, 0.5);
  expect_error(ctx, "glAlphaFunc");
  ctx.stencilFunc(gl::NEVER - 1, 1, 1);
  expect_error(ctx, "glStencilFunc");
  ctx.stencilOp(gl::KEEP, gl::KEEP, gl::NEVER);
  expect_error(ctx, "glStencilOp");
  ctx.stencilOp(gl::XOR, gl::KEEP, gl::KEEP);
  expect_error(ctx, "glStencilOp");
  ctx.depthFunc(gl::ALWAYS + 1);
  expect_error(ctx, "glDepthFunc");
  ctx.blendFunc(gl::SRC_COLOR, gl::ZERO);  // SRC_COLOR is a destination factor only
  expect_error(ctx, "glBlendFunc");
  ctx.blendFunc(gl::ONE, gl::SRC_ALPHA_SATURATE);  // a source factor only in GL 1.2.1
  expect_error(ctx, "glBlendFunc");
  CHECK(ctx.error_log().back().message.find("source factor only") != std::string::npos);
  ctx.blendFunc(gl::ONE, gl::DST_COLOR);  // DST_COLOR is a source factor only
  expect_error(ctx, "glBlendFunc");
  ctx.blendFunc(gl::FUNC_ADD, gl::ONE);
  expect_error(ctx, "glBlendFunc");
  ctx.blendEquation(gl::ONE);
  expect_error(ctx, "glBlendEquation");
  ctx.blendEquation(gl::BLEND_EQUATION);
  expect_error(ctx, "glBlendEquation");
  ctx.logicOp(gl::SET + 1);
  expect_error(ctx, "glLogicOp");
  ctx.enable(gl::BLEND_COLOR);  // a state token, not a capability
  expect_error(ctx, "glEnable");
  CHECK(ctx.fragment_ops_state() == before);
  // Valid calls with every token raise nothing.
  for (GLenum f : {gl::NEVER, gl::LESS, gl::EQUAL, gl::LEQUAL, gl::GREATER, gl::NOTEQUAL, gl::GEQUAL, gl::ALWAYS}) {
    ctx.alphaFunc(f, 0.5);
    ctx.stencilFunc(f, 1, 1);
    ctx.depthFunc(f);
  }
  for (GLenum e : {gl::FUNC_ADD, gl::FUNC_SUBTRACT, gl::FUNC_REVERSE_SUBTRACT, gl::MIN, gl::MAX}) ctx.blendEquation(e);
  ctx.blendFunc(gl::SRC_ALPHA_SATURATE, gl::ONE_MINUS_CONSTANT_ALPHA);
  for (GLenum op = gl::CLEAR; op <= gl::SET; ++op) ctx.logicOp(op);
  CHECK(ctx.getError() == gl::NO_ERROR);
}

TEST_CASE("plan cache: keyed by the canonical state, constants do not add plans") {
  Context ctx = make();
  ctx.enable(gl::ALPHA_TEST);
  ctx.alphaFunc(gl::GREATER, 0.1);
  FragmentSpan sp = fill(4, {1, 2, 3, 250});
  ctx.write_fragments(sp);
  CHECK(ctx.fragment_plan_cache_size() == 1);
  ctx.alphaFunc(gl::GREATER, 0.9);  // a constant: same plan (ref code 230 < 250)
  ctx.write_fragments(sp);
  CHECK(ctx.fragment_plan_cache_size() == 1);
  CHECK(px(ctx, 0, 0) == 1);
  ctx.enable(gl::BLEND);  // (ONE, ZERO, ADD): still a copy, same plan
  ctx.write_fragments(sp);
  CHECK(ctx.fragment_plan_cache_size() == 1);
  ctx.blendFunc(gl::ONE, gl::ONE);
  ctx.write_fragments(sp);
  CHECK(ctx.fragment_plan_cache_size() == 2);
  CHECK(px(ctx, 0, 0) == 2);  // 1 + 1
  ctx.blendFunc(gl::ONE, gl::ZERO);
  ctx.write_fragments(sp);
  CHECK(ctx.fragment_plan_cache_size() == 2);
  // Masks and scissor set through context_clear.cpp take effect on the next span.
  ctx.colorMask(false, true, true, true);
  FragmentSpan sp2 = fill(4, {9, 9, 9, 250});
  ctx.write_fragments(sp2);
  CHECK(px(ctx, 0, 0) == 1);
  CHECK(px(ctx, 0, 1) == 9);
  ctx.colorMask(true, true, true, true);
  ctx.scissor(1, 0, 1, 1);
  ctx.enable(gl::SCISSOR_TEST);
  FragmentSpan sp3 = fill(4, {7, 7, 7, 250});
  ctx.write_fragments(sp3);
  CHECK(px(ctx, 0, 0) == 1);
  CHECK(px(ctx, 1, 0) == 7);
  CHECK(px(ctx, 2, 0) == 1);
}

TEST_CASE("explain: the current plan as text") {
  Context ctx = make();
  ctx.colorMask(false, false, false, true);
  ctx.enable(gl::BLEND);
  ctx.blendFunc(gl::ONE, gl::ONE);
  ctx.blendEquation(gl::FUNC_SUBTRACT);
  const std::string t = ctx.explain_fragment_ops();
  CHECK(t.find("  colour: A = max(0, A_s - A_d)\n") != std::string::npos);
  CHECK(t.find("  scissor: x 0..3, y 0..0\n") != std::string::npos);
}

TEST_CASE("explain: a colour stage that keeps every destination for the current colour says so") {
  // The paper's third penumbra pass at penumbra 2 (section 4.2): DST_ALPHA, ONE on
  // alpha with A_s = 0 stores A_d back; with A_s = 1/255 it does not; a texture
  // shades the fragments, so their colour is not the current colour.
  Context ctx = make();
  ctx.colorMask(false, false, false, true);
  ctx.enable(gl::BLEND);
  ctx.blendFunc(gl::DST_ALPHA, gl::ONE);
  ctx.color4(0, 0, 0, 0);
  CHECK(ctx.explain_constant_source() ==
        "  colour: with the colour codes (0, 0, 0, 0) at every vertex, each written channel stores back its "
        "destination: the span path leaves out the groups whose depth and stencil tests write nothing too\n");
  ctx.color4(0, 0, 0, 1.0 / 255);
  CHECK(ctx.explain_constant_source().empty());
  ctx.color4(0, 0, 0, 0);
  const std::uint8_t texel[4] = {1, 2, 3, 4};
  ctx.texImage2D(gl::TEXTURE_2D, 0, gl::RGBA8, 1, 1, 0, gl::RGBA, gl::UNSIGNED_BYTE, texel);
  ctx.enable(gl::TEXTURE_2D);
  CHECK(ctx.explain_constant_source().empty());
  ctx.disable(gl::TEXTURE_2D);
  ctx.colorMask(false, false, false, false);  // nothing written: nothing to say
  CHECK(ctx.explain_constant_source().empty());
}

TEST_CASE("paper antialiased shadows (§4.2 steps 6-21) through write_fragments") {
  Context ctx = make(3, 1);
  // Steps 6-10: alpha := T1 + T2 with FUNC_ADD (ONE, ONE), then T3 - (T1 + T2) with FUNC_SUBTRACT.
  FragmentSpan t1 = row(0, {{0, 0, 0, 30}, {0, 0, 0, 50}, {0, 0, 0, 10}});
  FragmentSpan t2 = row(0, {{0, 0, 0, 40}, {0, 0, 0, 60}, {0, 0, 0, 10}});
  FragmentSpan t3 = row(0, {{0, 0, 0, 100}, {0, 0, 0, 100}, {0, 0, 0, 70}});
  ctx.write_fragments(t1);
  ctx.enable(gl::BLEND);
  ctx.blendFunc(gl::ONE, gl::ONE);
  ctx.write_fragments(t2);
  CHECK(px(ctx, 0, 3) == 70);
  ctx.blendEquation(gl::FUNC_SUBTRACT);
  ctx.write_fragments(t3);
  // Source minus destination: 100 - 70 = 30, 100 - 110 -> 0 (clamped), 70 - 20 = 50.
  CHECK(px(ctx, 0, 3) == 30);
  CHECK(px(ctx, 1, 3) == 0);
  CHECK(px(ctx, 2, 3) == 50);
  // Steps 12-14: (DST_ALPHA, ONE) with colour (0,0,0,1) doubles alpha twice. The paper
  // leaves the equation implicit; doubling needs FUNC_ADD (with FUNC_SUBTRACT the result
  // would be A_d - A_d = 0), so the trace sets it back.
  ctx.blendEquation(gl::FUNC_ADD);
  ctx.blendFunc(gl::DST_ALPHA, gl::ONE);
  FragmentSpan black = fill(3, {0, 0, 0, 255});
  ctx.write_fragments(black);
  CHECK(px(ctx, 0, 3) == 60);
  CHECK(px(ctx, 2, 3) == 100);
  ctx.write_fragments(black);
  CHECK(px(ctx, 0, 3) == 120);
  CHECK(px(ctx, 1, 3) == 0);
  CHECK(px(ctx, 2, 3) == 200);
  // Steps 15-17: reset blending, disable alpha writes, draw the bump map.
  ctx.disable(gl::BLEND);
  ctx.colorMask(true, true, true, false);
  FragmentSpan bump = fill(3, {200, 100, 50, 7});
  ctx.write_fragments(bump);
  CHECK(px(ctx, 0, 0) == 200);
  CHECK(px(ctx, 0, 3) == 120);  // alpha kept
  // Steps 18-20: alpha writes on, (DST_ALPHA, DST_ALPHA), colour (1,1,1,1):
  // C = C_s*A_d + C_d*A_d = (1 + C_d)*A_d (GL121 §4.1.6; note: not C_d*A_d).
  ctx.colorMask(true, true, true, true);
  ctx.enable(gl::BLEND);
  ctx.blendFunc(gl::DST_ALPHA, gl::DST_ALPHA);
  FragmentSpan white = fill(3, {255, 255, 255, 255});
  ctx.write_fragments(white);
  // Pixel 0, A_d = 120: R = (255 + 200)*120/255^2 = 214.12 -> 214; G = 355*120/255 = 167.06 -> 167;
  // B = 305*120/255 = 143.53 -> 144; A = 375*120/255 = 176.47 -> 176.
  CHECK(px(ctx, 0, 0) == 214);
  CHECK(px(ctx, 0, 1) == 167);
  CHECK(px(ctx, 0, 2) == 144);
  CHECK(px(ctx, 0, 3) == 176);
  // Pixel 1, A_d = 0: everything 0. Pixel 2, A_d = 200: R = 455*200/255 = 356.9 -> clamp 255.
  CHECK(px(ctx, 1, 0) == 0);
  CHECK(px(ctx, 1, 3) == 0);
  // B = (255 + 50)*200/255 = 239.2 -> 239.
  CHECK(px(ctx, 2, 0) == 255);
  CHECK(px(ctx, 2, 2) == 239);
}

TEST_CASE("float profiles: blending in binary64 and binary32 with the [0,1] clamp only") {
  for (const char* name : {"ideal", "float32"}) {
    Context ctx = make(2, 1, name);
    FragmentSpan a;
    a.count = 2;
    a.values = {0.75, 0.1, 0.3, 1.0, 0.2, 0.2, 0.2, 0.2};
    ctx.write_fragments(a);
    ctx.enable(gl::BLEND);
    ctx.blendFunc(gl::ONE, gl::ONE);
    FragmentSpan b = a;
    b.values = {0.5, 0.2, 0.1, 1.0, 0.1, 0.1, 0.1, 0.1};
    ctx.blendEquation(gl::FUNC_ADD);
    ctx.write_fragments(b);
    const auto& v = ctx.framebuffer().values();
    CHECK(v[0] == 1.0);  // 0.75 + 0.5 = 1.25 -> 1
    // 0.1 + 0.2: binary64 sum for ideal, binary32 sum of the binary32 operands for float32.
    if (std::string(name) == "ideal") CHECK(v[1] == 0.1 + 0.2);
    else CHECK(v[1] == static_cast<double>(0.1f + 0.2f));
    ctx.blendEquation(gl::FUNC_SUBTRACT);
    FragmentSpan c = a;
    c.values = {0.25, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    ctx.write_fragments(c);
    CHECK(v[0] == 0.0);  // 0.25 - 1 -> 0, the destination exceeds the source
    CHECK(!std::signbit(v[0]));
  }
}

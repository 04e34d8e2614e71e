#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <random>
#include <vector>

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

// The clears fill rectangles row by row; this checks them pixel by pixel against
// the rule of §4.2.3 (every pixel of the rectangle clipped to the window takes the
// clear value through the masks, §4.2.2; nothing else changes), over random
// rectangles (partly or wholly outside), masks and colour formats.
TEST_CASE("framebuffer: clears change exactly the masked components of the clipped rectangle") {
  std::mt19937 rng(20261124);
  auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  for (int round = 0; round < 300; ++round) {
    FramebufferFormat f;
    f.width = pick(1, 23);
    f.height = pick(1, 9);
    f.color_arith = std::array{Arithmetic::Fixed, Arithmetic::Float32, Arithmetic::Float64}[pick(0, 2)];
    f.color_bits = pick(1, 12);
    f.stencil_bits = pick(0, 8);
    f.depth_bits = std::array{0, 16, 24}[pick(0, 2)];
    Framebuffer fb(f);
    // Distinct starting contents, so an unchanged pixel is seen as one.
    for (std::size_t i = 0; i < fb.codes().size(); ++i)
      fb.codes()[i] = static_cast<std::uint16_t>(i % (fb.color_max() + 1));
    for (std::size_t i = 0; i < fb.values().size(); ++i) fb.values()[i] = static_cast<double>(i % 7) / 8;
    for (std::size_t i = 0; i < fb.stencil().size(); ++i)
      fb.stencil()[i] = static_cast<std::uint8_t>(i % (fb.stencil_max() + 1));
    for (std::size_t i = 0; i < fb.depth().size(); ++i) fb.depth()[i] = static_cast<std::uint32_t>(i);
    const Framebuffer before = fb;
    const Rect r{pick(-30, 30), pick(-12, 12), pick(0, 40), pick(0, 20)};
    const std::array<bool, 4> mask{pick(0, 1) == 1, pick(0, 1) == 1, pick(0, 1) == 1, pick(0, 1) == 1};
    const std::array<double, 4> rgba{pick(0, 8) / 8.0, pick(0, 8) / 8.0, 0.3, 1.0};
    const auto stencil_value = static_cast<std::uint32_t>(pick(0, 1023));
    const auto stencil_mask = static_cast<std::uint32_t>(pick(0, 255));
    const double depth = pick(0, 4) / 4.0;
    CAPTURE(round);
    fb.clear_color(r, rgba, mask);
    fb.clear_stencil(r, stencil_value, stencil_mask);
    fb.clear_depth(r, depth);
    // The cleared values, as a one-pixel buffer stores them.
    FramebufferFormat one = f;
    one.width = one.height = 1;
    Framebuffer ref(one);
    for (int c = 0; c < 4; ++c) ref.store_color_value(0, 0, c, rgba[c]);
    const std::uint32_t sm = stencil_mask & fb.stencil_max();
    for (int y = 0; y < f.height; ++y)
      for (int x = 0; x < f.width; ++x) {
        const bool inside = x >= r.x && x < r.x + r.width && y >= r.y && y < r.y + r.height;
        const std::size_t i = fb.index(x, y);
        for (int c = 0; c < 4; ++c) {
          const std::size_t k = 4 * i + static_cast<std::size_t>(c);
          const bool cleared = inside && mask[static_cast<std::size_t>(c)];
          if (f.float_color())
            CHECK(fb.values()[k] == (cleared ? ref.values()[static_cast<std::size_t>(c)] : before.values()[k]));
          else
            CHECK(fb.codes()[k] == (cleared ? ref.codes()[static_cast<std::size_t>(c)] : before.codes()[k]));
        }
        if (fb.has_stencil())
          CHECK(fb.stencil()[i] == (inside ? (before.stencil()[i] & ~sm) | (stencil_value & sm) : before.stencil()[i]));
        if (fb.has_depth())
          CHECK(fb.depth()[i] == (inside ? unorm_from_double(depth, f.depth_bits) : before.depth()[i]));
      }
  }
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

TEST_CASE("framebuffer: a new buffer reads as zero, whichever clears or readers come first") {
  // Framebuffer owes its zero fill until a clear covers a whole buffer (every
  // pixel; every channel, every stencil bit). Random sequences of clears (whole
  // or partial rectangles, masks) and reads on a fresh framebuffer must leave
  // what the same sequence leaves on one filled at once (`model`: every buffer
  // taken, so filled, before anything else). Before each, a freed block of the
  // same sizes full of 0xA5 makes it likely that owed memory is not zero already.
  std::mt19937 rng(20261202);
  auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  int whole = 0, partial = 0;
  for (int round = 0; round < 400; ++round) {
    FramebufferFormat f;
    f.width = pick(1, 40);
    f.height = pick(1, 20);
    f.color_arith = std::array{Arithmetic::Fixed, Arithmetic::Fixed, Arithmetic::Float32, Arithmetic::Float64}[pick(0, 3)];
    f.color_bits = pick(1, 12);
    f.stencil_bits = pick(0, 8);
    f.depth_bits = std::array{0, 16, 24}[pick(0, 2)];
    {
      Framebuffer dirty(f);
      std::fill(dirty.codes().begin(), dirty.codes().end(), std::uint16_t{0xA5A5});
      std::fill(dirty.values().begin(), dirty.values().end(), 0.625);
      std::fill(dirty.stencil().begin(), dirty.stencil().end(), std::uint8_t{0xA5});
      std::fill(dirty.depth().begin(), dirty.depth().end(), 0xA5A5A5u);
    }
    Framebuffer fb(f);
    Framebuffer model(f);
    (void)model.codes(), (void)model.values(), (void)model.stencil(), (void)model.depth();
    CAPTURE(round);
    const int steps = pick(0, 3);
    for (int s = 0; s < steps; ++s) {
      const bool full = pick(0, 1) == 1;
      const Rect r = full ? Rect{pick(-3, 0), pick(-3, 0), f.width + 3, f.height + 3}
                          : Rect{pick(-5, f.width), pick(-5, f.height), pick(0, f.width), pick(0, f.height)};
      std::array<bool, 4> mask{true, true, true, true};
      if (pick(0, 2) == 0) mask[static_cast<std::size_t>(pick(0, 3))] = false;
      const std::array<double, 4> rgba{pick(0, 8) / 8.0, pick(0, 8) / 8.0, 0.3, 1.0};
      const auto smask = pick(0, 1) == 1 ? 0xFFu : static_cast<std::uint32_t>(pick(0, 255));
      const auto svalue = static_cast<std::uint32_t>(pick(0, 255));
      const double depth = pick(0, 4) / 4.0;
      const int which = pick(0, 4);  // 0-2: one clear; 3: all three; 4: a read of every buffer
      for (Framebuffer* b : {&fb, &model}) {
        if (which == 0 || which == 3) b->clear_color(r, rgba, mask);
        if (which == 1 || which == 3) b->clear_stencil(r, svalue, smask);
        if (which == 2 || which == 3) b->clear_depth(r, depth);
        if (which == 4) CHECK(b->color_value(0, 0, 0) >= 0);
      }
      (full && mask == std::array<bool, 4>{true, true, true, true} ? whole : partial)++;
    }
    CHECK(fb.codes() == model.codes());
    CHECK(fb.values() == model.values());
    CHECK(fb.stencil() == model.stencil());
    CHECK(fb.depth() == model.depth());
  }
  CHECK(whole > 100);
  CHECK(partial > 100);
}

TEST_CASE("framebuffer: a planned clear written in row ranges, in any order, equals the clear at once") {
  // plan_clear + clear_rows (what Context::clear splits over threads) against
  // clear() on a copy: random formats, rectangles (clipped or not), masks,
  // fresh buffers (owed fills) or written ones; the rows cut into 1-6 ranges
  // written in a random order, some ranges reaching past the rectangle.
  std::mt19937 rng(20261205);
  auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  int cut = 0;
  for (int round = 0; round < 400; ++round) {
    FramebufferFormat f;
    f.width = pick(1, 30);
    f.height = pick(1, 24);
    f.color_arith = std::array{Arithmetic::Fixed, Arithmetic::Fixed, Arithmetic::Float32, Arithmetic::Float64}[pick(0, 3)];
    f.color_bits = pick(1, 12);
    f.stencil_bits = pick(0, 8);
    f.depth_bits = std::array{0, 16, 24}[pick(0, 2)];
    Framebuffer whole(f);
    if (pick(0, 1) == 1) {  // written contents (else the zero fills are owed)
      for (std::size_t i = 0; i < whole.codes().size(); ++i)
        whole.codes()[i] = static_cast<std::uint16_t>((i * 7) % (whole.color_max() + 1));
      for (std::size_t i = 0; i < whole.values().size(); ++i) whole.values()[i] = static_cast<double>(i % 5) / 8;
      for (std::size_t i = 0; i < whole.stencil().size(); ++i)
        whole.stencil()[i] = static_cast<std::uint8_t>((i * 3) % (whole.stencil_max() + 1));
      for (std::size_t i = 0; i < whole.depth().size(); ++i) whole.depth()[i] = static_cast<std::uint32_t>(i * 11);
    }
    Framebuffer rows = whole;
    const bool full = pick(0, 2) == 0;
    const Rect r = full ? Rect{pick(-2, 0), pick(-2, 0), f.width + 2, f.height + 2}
                        : Rect{pick(-6, f.width), pick(-6, f.height), pick(0, f.width + 4), pick(0, f.height + 4)};
    ClearValues v;
    v.color = pick(0, 3) > 0;
    v.stencil = pick(0, 3) > 0;
    v.depth = pick(0, 3) > 0;
    v.rgba = {pick(0, 8) / 8.0, pick(0, 8) / 8.0, 0.3, pick(0, 1) * 1.0};
    v.color_mask = {pick(0, 3) > 0, pick(0, 3) > 0, pick(0, 3) > 0, pick(0, 3) > 0};
    v.stencil_value = static_cast<std::uint32_t>(pick(0, 1023));
    v.stencil_mask = pick(0, 1) == 1 ? ~0u : static_cast<std::uint32_t>(pick(0, 255));
    v.depth01 = pick(0, 4) / 4.0;
    CAPTURE(round);
    whole.clear(r, v);
    const ClearPlan p = rows.plan_clear(r, v);
    std::vector<int> cuts{p.r.y - pick(0, 2), p.r.y + p.r.height + pick(0, 2)};
    for (int k = pick(0, 5); k > 0; --k) cuts.push_back(p.r.y + pick(0, std::max(0, p.r.height)));
    std::sort(cuts.begin(), cuts.end());
    std::vector<std::array<int, 2>> ranges;
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) ranges.push_back({cuts[i], cuts[i + 1]});
    std::shuffle(ranges.begin(), ranges.end(), rng);
    for (const auto& [y0, y1] : ranges) rows.clear_rows(p, y0, y1);
    cut += ranges.size() > 2;
    CHECK(rows.codes() == whole.codes());
    CHECK(rows.values() == whole.values());
    CHECK(rows.stencil() == whole.stencil());
    CHECK(rows.depth() == whole.depth());
  }
  CHECK(cut > 150);
}

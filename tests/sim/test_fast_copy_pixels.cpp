// CopyPixels COLOR with an empty transfer plan (sim/context_pixel_rect.cpp): the
// fast path tabulates each component's final code over the framebuffer codes
// and lays the rows out without the float image. Against the reference path
// (set_fast_paths(false): read_color_rect, transfer, emit_color_rect) on random
// framebuffers, source rectangles partly outside the window (read as 0),
// overlapping the destination, raster positions, pixel zooms (fractional,
// negative), fragment operations, texturing of the copied fragments (which
// rewrites a span's colours in place), and sometimes a transfer operation (both
// paths then take the reference). Buffers must be identical.
#include <doctest/doctest.h>

#include "fast_scene.h"

using namespace ffsim;
using namespace ffsim::test;

TEST_CASE("fast copy pixels: identity-transfer CopyPixels COLOR == the reference path, every profile") {
#ifdef FFSIM_SANITIZE
  constexpr int kCases = 15;
#else
  constexpr int kCases = 40;
#endif
  int copies = 0;
  for (const char* profile : kFastProfiles) {
    for (int k = 0; k < kCases; ++k) {
      const auto seed = static_cast<std::uint32_t>(7000 + k);
      Context fast(profile_named(profile), 37, 29), slow(profile_named(profile), 37, 29);
      slow.set_fast_paths(false);
      SceneOptions opt;
      opt.copy_pixels = false;
      for (Context* c : {&fast, &slow}) {
        draw_random_scene(*c, seed, opt);
        SceneRng r(seed + 1);
        for (int copy = 0; copy < 3; ++copy) {
          for (int u = 0; u < 2; ++u) random_texture_or_off(*c, r, u, static_cast<std::uint32_t>(10 + u), 30);
          c->disable(gl::REGISTER_COMBINERS_NV);
          random_fragment_ops(*c, r);
          static const double kZoom[] = {1, 1, 1, 2, 0.5, 1.5, -1, -2, 3};
          c->pixelZoom(r.pick(kZoom), r.pick(kZoom));
          c->pixelTransferf(gl::RED_SCALE, r.b(20) ? 0.5 : 1.0);  // 0.5: a transfer stage (both take the reference)
          c->matrixMode(gl::PROJECTION);
          c->loadIdentity();
          c->ortho(0, 37, 0, 29, -1, 1);
          c->matrixMode(gl::MODELVIEW);
          c->loadIdentity();
          c->rasterPos2(r.d(-3, 36), r.d(-3, 28));  // outside the window: an invalid raster position, nothing drawn
          c->copyPixels(r.i(-10, 30), r.i(-10, 25), r.i(0, 50), r.i(0, 40), gl::COLOR);
        }
      }
      INFO("profile ", profile, " seed ", seed);
      REQUIRE(buffer_hashes(fast) == buffer_hashes(slow));
      copies += 3;
    }
  }
  CHECK(copies == 3 * kCases * 5);
}

TEST_CASE("fast copy pixels: a source rectangle anywhere in int range reads as outside the window, without overflow") {
  // x or y near INT_MIN / INT_MAX: the whole source is outside and reads as 0,
  // as a rectangle just beside the window does.
  const int kFar[][2] = {{-2147483647 - 1, 3}, {2147483647 - 5, 3}, {3, -2147483647 - 1}, {3, 2147483647 - 5}};
  for (const auto& far : kFar) {
    Context a(profile_named("geforce256"), 16, 16), b(profile_named("geforce256"), 16, 16);
    for (Context* c : {&a, &b}) {
      c->clearColor(0.25, 0.5, 0.75, 1);
      c->clear(gl::COLOR_BUFFER_BIT);
      c->rasterPos2(0, 0);
    }
    a.copyPixels(far[0], far[1], 6, 6, gl::COLOR);
    b.copyPixels(-100, -100, 6, 6, gl::COLOR);
    CHECK(a.getError() == gl::NO_ERROR);
    CHECK(buffer_hashes(a) == buffer_hashes(b));
  }
}

TEST_CASE("fast copy pixels: rows copied whole where each column lands on one pixel, and where leading columns land on none") {
  // emit_color_code_rows copies a row's codes at once when the image columns
  // that reach the window land one per pixel, in order; with a zoom below 1 the
  // first columns may land on no pixel (the copy then starts at the first that
  // does) or several columns on one pixel (no single copy). Every raster
  // position's fraction, zooms near 1 and below, widths 1..6, against the
  // reference path.
  int compared = 0;
  for (const double zoom : {1.0, 0.5, 0.25, 0.75, 1.5})
    for (const double fx : {0.0, 0.25, 0.5, 0.75, 0.9})
      for (int width = 1; width <= 6; ++width) {
        Context fast(profile_named("geforce256"), 16, 8), slow(profile_named("geforce256"), 16, 8);
        slow.set_fast_paths(false);
        for (Context* c : {&fast, &slow}) {
          ortho_window(*c);
          for (int y = 0; y < 8; ++y)  // a different colour in every pixel of the source rows
            for (int x = 0; x < 16; ++x)
              for (int k = 0; k < 4; ++k)
                c->framebuffer().codes()[4 * c->framebuffer().index(x, y) + static_cast<std::size_t>(k)] =
                    static_cast<std::uint16_t>((x * 16 + y * 4 + k * 67) % 256);
          c->pixelZoom(zoom, 1);
          c->rasterPos2(3 + fx, 4);
          c->copyPixels(0, 0, width, 3, gl::COLOR);
        }
        INFO("zoom ", zoom, " raster x fraction ", fx, " width ", width);
        REQUIRE(buffer_hashes(fast) == buffer_hashes(slow));
        ++compared;
      }
  CHECK(compared == 5 * 5 * 6);
}

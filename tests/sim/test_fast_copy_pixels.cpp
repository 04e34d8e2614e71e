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

TEST_CASE("fast copy pixels: rows in bands on 2 and 3 threads == one thread == the reference path") {
  // CopyPixels COLOR of large rectangles (docs/performance.md 19.6): when every
  // image row lands on one window row of its own and nothing shades the
  // fragments, the rows go through the fragment operations in bands on the pool.
  // Random scenes on a 128 x 96 window, random fragment operations (blending,
  // alpha, stencil, depth, masks), zooms that split (y = 1, -1, x = 1) and that
  // do not (y = 2 or 0.5: a row on two window rows or two rows on one; x = 0.5:
  // no row copy; texturing on: shaded per fragment), sources overlapping the
  // destination. Buffers and fragment counts must equal one thread's and the
  // reference's.
#ifdef FFSIM_SANITIZE
  constexpr int kCases = 6;
#else
  constexpr int kCases = 24;
#endif
  constexpr int W = 128, H = 96;
  std::uint64_t split = 0;
  for (const char* profile : {"geforce256", "rgba12"})
    for (int k = 0; k < kCases; ++k) {
      const auto seed = static_cast<std::uint32_t>(7400 + k);
      Context one(profile_named(profile), W, H), two(profile_named(profile), W, H), three(profile_named(profile), W, H),
          slow(profile_named(profile), W, H);
      two.set_threads(2);
      three.set_threads(3);
      slow.set_fast_paths(false);
      SceneOptions opt;
      opt.copy_pixels = false;
      for (Context* c : {&one, &two, &three, &slow}) {
        draw_random_scene(*c, seed, opt);
        SceneRng r(seed + 1);
        for (int copy = 0; copy < 3; ++copy) {
          for (int u = 0; u < 2; ++u) random_texture_or_off(*c, r, u, static_cast<std::uint32_t>(10 + u), 10);
          c->disable(gl::REGISTER_COMBINERS_NV);
          if (r.b(80)) c->disable(gl::COLOR_SUM);
          random_fragment_ops(*c, r);
          static const double kZoomX[] = {1, 1, 1, 1, 0.5, 2};
          static const double kZoomY[] = {1, 1, 1, -1, -1, 2, 0.5};
          const double zy = r.pick(kZoomY);
          c->pixelZoom(r.pick(kZoomX), zy);
          c->matrixMode(gl::PROJECTION);
          c->loadIdentity();
          c->ortho(0, W, 0, H, -1, 1);
          c->matrixMode(gl::MODELVIEW);
          c->loadIdentity();
          c->rasterPos2(r.d(0, 8), zy < 0 ? r.d(H - 8, H) : r.d(0, 8));  // (rows going down from the top)
          c->copyPixels(r.i(-10, 20), r.i(-10, 20), r.i(100, 140), r.i(70, 110), gl::COLOR);
        }
      }
      INFO("profile ", profile, " seed ", seed);
      REQUIRE(buffer_hashes(two) == buffer_hashes(one));
      REQUIRE(buffer_hashes(three) == buffer_hashes(one));
      REQUIRE(buffer_hashes(one) == buffer_hashes(slow));
      CHECK(two.fragments_written() == one.fragments_written());
      CHECK(three.fragments_written() == one.fragments_written());
      CHECK(one.split_pixel_rects() == 0);
      CHECK(two.split_pixel_rects() == three.split_pixel_rects());
      split += two.split_pixel_rects();
    }
  MESSAGE("copies split into bands: " << split << " of " << 2 * kCases * 3);
  CHECK(split >= static_cast<std::uint64_t>(kCases));
}

TEST_CASE("fast copy pixels: rows read from the framebuffer itself (in place, or colour masked) == snapshot == reference") {
  // With identity codes the fast path reads each row straight from the
  // framebuffer, without a snapshot, when no fragment can write a source pixel
  // before it is read: every image pixel lands on the pixel it was read from
  // (zoom 1, the raster position rounding to the source corner; the paper's
  // "CopyPixels the window onto itself"), or the colour mask keeps every channel.
  // Random scenes, random fragment operations with blending forced on (a copy in
  // place then changes every pixel it writes from the value it read), sources
  // partly outside the window, at 1 and 2 threads (rows in bands), against the
  // reference path. The in-place raster positions are the corner plus a fraction
  // below 1/2 (which rounds to the corner); the masked ones are anywhere.
#ifdef FFSIM_SANITIZE
  constexpr int kCases = 6;
#else
  constexpr int kCases = 20;
#endif
  constexpr int W = 96, H = 72;
  for (const char* profile : {"geforce256", "rgba12"})
    for (int k = 0; k < kCases; ++k) {
      const auto seed = static_cast<std::uint32_t>(7700 + k);
      Context one(profile_named(profile), W, H), two(profile_named(profile), W, H), slow(profile_named(profile), W, H);
      two.set_threads(2);
      two.set_split_fragments(256);  // rows in bands however small the rectangle
      slow.set_fast_paths(false);
      SceneOptions opt;
      opt.copy_pixels = false;
      for (Context* c : {&one, &two, &slow}) {
        draw_random_scene(*c, seed, opt);
        SceneRng r(seed + 1);
        for (int copy = 0; copy < 4; ++copy) {
          c->disable(gl::TEXTURE_2D);
          c->disable(gl::REGISTER_COMBINERS_NV);
          random_fragment_ops(*c, r);
          c->enable(gl::BLEND);
          c->blendFunc(gl::ONE, gl::ONE);
          c->blendEquation(copy % 2 ? gl::FUNC_ADD : gl::FUNC_REVERSE_SUBTRACT);
          const bool masked = copy >= 2;
          if (masked) c->colorMask(false, false, false, false);
          else c->colorMask(true, true, true, r.b(50));
          c->pixelZoom(1, masked && r.b(50) ? -1 : 1);
          c->matrixMode(gl::PROJECTION);
          c->loadIdentity();
          c->ortho(0, W, 0, H, -1, 1);
          c->matrixMode(gl::MODELVIEW);
          c->loadIdentity();
          const int x = r.i(-8, 20), y = r.i(-8, 20);
          if (masked) c->rasterPos2(r.d(0, 30), r.d(0, 30));
          else c->rasterPos2(std::max(x, 0) + r.d(0, 0.45), std::max(y, 0) + r.d(0, 0.45));
          // (a raster position is valid inside the window only: a corner left of or
          // below it is moved in, and the copy is then not in place: the snapshot)
          c->copyPixels(x, y, r.i(40, 110), r.i(30, 90), gl::COLOR);
        }
      }
      INFO("profile ", profile, " seed ", seed);
      REQUIRE(buffer_hashes(one) == buffer_hashes(slow));
      REQUIRE(buffer_hashes(two) == buffer_hashes(slow));
      CHECK(two.fragments_written() == one.fragments_written());
    }
}

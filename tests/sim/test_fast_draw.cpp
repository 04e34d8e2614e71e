// The span path of the draw (sim/draw_span.cpp) against the per-fragment path:
// random scenes (seeded) drawn with set_fast_paths(true) and (false) must leave
// identical colour, stencil and depth buffers, in every built-in profile.
#include <doctest/doctest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>

#include "fast_scene.h"
#include "pipeline/raster/triangle.h"
#include "sim/draw_span.h"

using namespace ffsim;
using namespace ffsim::test;

namespace {

#ifdef FFSIM_SANITIZE
constexpr int kCases = 20;  // per profile; keeps each test case well under 10 s under ASan
#else
constexpr int kCases = 40;
#endif

struct Pair {
  Context fast, slow;
  explicit Pair(const char* profile, int w = 37, int h = 29)
      : fast(profile_named(profile), w, h), slow(profile_named(profile), w, h) {
    slow.set_fast_paths(false);
  }
};

// Draws `cases` scenes per profile both ways; returns the span-path runs taken.
std::uint64_t compare_scenes(const SceneOptions& opt, std::uint32_t seed0, int cases) {
  std::uint64_t runs = 0;
  for (const char* profile : kFastProfiles) {
    for (int k = 0; k < cases; ++k) {
      Pair p(profile);
      const auto seed = seed0 + static_cast<std::uint32_t>(k);
      draw_random_scene(p.fast, seed, opt);
      draw_random_scene(p.slow, seed, opt);
      INFO("profile ", profile, " seed ", seed);
      REQUIRE(buffer_hashes(p.fast) == buffer_hashes(p.slow));
      CHECK(p.slow.fast_runs() == 0);
      runs += p.fast.fast_runs();
    }
  }
  return runs;
}

}  // namespace

TEST_CASE("fast draw: texture environments, colour sum and fragment ops, span path == per-fragment path") {
  SceneOptions opt;
  opt.combiners = false;
  CHECK(compare_scenes(opt, 1000, kCases) > 500);  // the span path did run
}

TEST_CASE("fast draw: register combiners, span path == per-fragment path") {
  SceneOptions opt;
  CHECK(compare_scenes(opt, 5000, kCases) > 500);
}

TEST_CASE("fast draw: a planted difference is detected") {
  // The comparison is sensitive: the same scenes with one texture-environment
  // colour code changed in one context differ somewhere.
  int differing = 0;
  for (std::uint32_t seed = 1000; seed < 1040; ++seed) {
    Pair p("geforce256");
    SceneOptions opt;
    opt.combiners = false;
    draw_random_scene(p.fast, seed, opt);
    draw_random_scene(p.slow, seed, opt);
    // Plant: one more textured, blended quad in one context only.
    p.fast.enable(gl::BLEND);
    p.fast.blendFunc(gl::ONE, gl::ONE);
    p.fast.disable(gl::DEPTH_TEST);
    p.fast.disable(gl::STENCIL_TEST);
    p.fast.disable(gl::ALPHA_TEST);
    p.fast.disable(gl::SCISSOR_TEST);
    p.fast.colorMask(true, true, true, true);
    p.fast.color4(0.01, 0.01, 0.01, 0.01);
    quad(p.fast, 3, 3, 4, 4);
    differing += buffer_hashes(p.fast) != buffer_hashes(p.slow);
  }
  CHECK(differing > 0);
}

TEST_CASE("fast draw: interpolate_code_run equals interpolate_code on random runs") {
  // Both forms of the DDA: int64 (A·max code <= 2^59: every small or medium
  // triangle) and 128-bit (every third triangle: vertices up to 2^27 grid units
  // and codes up to 2^32 − 1).
  SceneRng r(77);
  int wide = 0;
  for (int k = 0; k < 3000; ++k) {
    // A random triangle, and the run of one of its rows.
    std::array<SnappedVertex, 3> v;
    const bool huge = k % 3 == 2;
    for (auto& p : v) p = {r.i(-400, 4000), r.i(-400, 4000)};
    if (huge)
      for (auto& p : v) p = {std::int64_t{r.i(-(1 << 19), 1 << 19)} << 8, std::int64_t{r.i(-(1 << 19), 1 << 19)} << 8};
    const int S = 4;
    std::vector<CoverageRun> runs;
    const TriangleCoverage cov = rasterize_triangle(v, S, -100, -100, 400, 400, [&](const TriangleCoverage&, const CoverageRun& run) {
      if (runs.size() < 8) runs.push_back(run);
    });
    std::uint32_t k0 = static_cast<std::uint32_t>(r.i(0, 65535)), k1 = static_cast<std::uint32_t>(r.i(0, 65535)),
                  k2 = static_cast<std::uint32_t>(r.i(0, 16777215));
    if (huge) k2 = 0xFFFFFFFFu - static_cast<std::uint32_t>(r.i(0, 3));
    if (k % 4 == 0) k1 = k2 = k0;  // equal codes: the run is filled without a division
    if (k % 8 == 4) k1 = k0;       // two equal: still the DDA
    const std::uint32_t kmax = std::max({k0, k1, k2});
    if (!runs.empty() && kmax > 0 && cov.area > (std::int64_t{1} << 59) / kmax) ++wide;
    std::vector<std::array<std::int64_t, 3>> first;
    std::vector<int> length;
    std::vector<std::uint32_t> expected;
    for (const CoverageRun& run : runs) {
      std::vector<std::uint32_t> out(run.weight.size());
      interpolate_code_run(run.weight[0], cov.dwdx, cov.area, k0, k1, k2, static_cast<int>(out.size()), out.data());
      for (std::size_t i = 0; i < out.size(); ++i) {
        REQUIRE(out[i] == interpolate_code(run.weight[i], cov.area, k0, k1, k2));
        expected.push_back(out[i]);
      }
      first.push_back(run.weight[0]);
      length.push_back(static_cast<int>(run.weight.size()));
    }
    // All runs of the triangle at once (one step division per triangle).
    std::vector<std::uint32_t> all(expected.size());
    interpolate_code_runs(first.data(), length.data(), static_cast<int>(first.size()), cov.dwdx, cov.area, k0, k1, k2,
                          all.data());
    REQUIRE(all == expected);
  }
  CHECK(wide > 150);  // (236 with this seed: the 128-bit form is exercised)
}

TEST_CASE("fast draw: interpolate_code_runs on slivers (one-fragment runs with huge gradients) and mixed runs") {
  // A long thin triangle covers one fragment per row: its x gradient is far above
  // A, which only a run of two or more fragments bounds; the step must not be
  // formed from such runs alone (int64 overflow). Then a wider row appears.
  SceneRng r(78);
  int slivers = 0;
  for (int k = 0; k < 2000; ++k) {
    const std::int64_t S = 8, len = std::int64_t{r.i(200, 1 << 14)} << S;
    const std::int64_t x = std::int64_t{r.i(0, 50)} << S, y = std::int64_t{r.i(0, 50)} << S;
    // (x, y), (x + 1.3 px, y + len), (x + 0.4 px + w, y + len/2): nearly vertical and thin.
    std::array<SnappedVertex, 3> v{{{x, y}, {x + 333, y + len}, {x + 100 + r.i(0, k % 2 ? 600 : 40), y + len / 2}}};
    std::vector<std::array<std::int64_t, 3>> first;
    std::vector<int> length;
    std::vector<std::uint32_t> expected;
    const TriangleCoverage cov = rasterize_triangle(v, static_cast<int>(S), -10, -10, 1 << 20, 1 << 20,
                                                    [&](const TriangleCoverage& c, const CoverageRun& run) {
                                                      first.push_back(run.weight[0]);
                                                      length.push_back(static_cast<int>(run.weight.size()));
                                                      for (const auto& w : run.weight) expected.push_back(interpolate_code(w, c.area, 0, 0, 0));
                                                    });
    if (first.empty()) continue;
    const std::uint32_t k0 = static_cast<std::uint32_t>(r.i(0, 16777215)), k1 = static_cast<std::uint32_t>(r.i(0, 255)),
                        k2 = k % 3 == 0 ? 0xFFFFFFFFu : static_cast<std::uint32_t>(r.i(0, 65535));
    std::size_t at = 0;
    for (std::size_t i = 0; i < first.size(); ++i)
      for (int j = 0; j < length[i]; ++j, ++at) {
        std::array<std::int64_t, 3> w = first[i];
        for (int q = 0; q < 3; ++q) w[static_cast<std::size_t>(q)] += j * cov.dwdx[static_cast<std::size_t>(q)];
        expected[at] = interpolate_code(w, cov.area, k0, k1, k2);
      }
    slivers += std::all_of(length.begin(), length.end(), [](int n) { return n == 1; });
    std::vector<std::uint32_t> all(expected.size());
    interpolate_code_runs(first.data(), length.data(), static_cast<int>(first.size()), cov.dwdx, cov.area, k0, k1, k2,
                          all.data());
    REQUIRE(all == expected);
  }
  CHECK(slivers > 100);  // triangles made only of one-fragment runs were drawn
}

TEST_CASE("fast draw: vertices shared by a glEnd's polygons (window form once), every mode, 1 and 2 threads") {
  // Smooth shading with every vertex inside the view volume: the span path puts
  // each vertex in window form once and indexes it from every polygon. Scenes of
  // one mode at a time, vertices in the window, fast == reference, and the shared
  // form must have been taken.
  const GLenum modes[] = {gl::TRIANGLES, gl::TRIANGLE_STRIP, gl::TRIANGLE_FAN, gl::QUADS, gl::QUAD_STRIP, gl::POLYGON};
  for (const GLenum mode : modes)
    for (int threads : {1, 2}) {
      std::uint64_t shared = 0;
      for (std::uint32_t seed = 90; seed < 96; ++seed) {
        Pair p("geforce256", 64, 48);
        for (Context* c : {&p.fast, &p.slow}) {
          SceneRng r(seed);
          c->set_threads(threads);
          random_clear_and_projection(*c, r, 0);
          c->shadeModel(gl::SMOOTH);
          c->enable(gl::DEPTH_TEST);
          c->enable(gl::BLEND);
          c->blendFunc(gl::SRC_ALPHA, gl::ONE_MINUS_SRC_ALPHA);
          c->begin(mode);
          for (int k = 0; k < 24; ++k) {
            c->color4(r.d(0, 1), r.d(0, 1), r.d(0, 1), r.d(0, 1));
            c->vertex3(r.d(0, 64), r.d(0, 48), r.d(-0.9, 0.9));
          }
          c->end();
        }
        INFO("mode ", mode, " threads ", threads, " seed ", seed);
        REQUIRE(buffer_hashes(p.fast) == buffer_hashes(p.slow));
        CHECK(p.slow.shared_vertex_draws() == 0);
        shared += p.fast.shared_vertex_draws();
      }
      CHECK(shared > 0);
    }
}

namespace {

// Right triangles with legs of 2^a and 2^b pixels (a, b <= max_log_leg) at integer
// corners in [0, max_corner] of a 64x64 window, two random textures, (ONE, ONE)
// blending, drawn both ways in geforce256 and rgba12 for kCases seeds from
// seed0; `texcoord(c, unit, rv, projective)` gives each vertex's coordinates
// (projective: drawn per triangle with projective_percent % chance, 0: never
// drawn). Returns the span-path runs taken.
std::uint64_t compare_pow2_triangles(std::uint32_t seed0, std::uint32_t vertex_seed_offset, int triangles,
                                     int max_corner, int max_log_leg, int projective_percent,
                                     const std::function<void(Context&, GLenum, SceneRng&, bool)>& texcoord) {
  std::uint64_t fast_runs = 0;
  for (const char* profile : {"geforce256", "rgba12"}) {
    for (std::uint32_t seed = seed0; seed < seed0 + kCases; ++seed) {
      Pair p(profile, 64, 64);
      for (Context* c : {&p.fast, &p.slow}) {
        SceneRng rc(seed);
        for (int u = 0; u < 2; ++u) random_texture(*c, rc, u, static_cast<std::uint32_t>(1 + u));
        c->matrixMode(gl::PROJECTION);
        c->loadIdentity();
        c->ortho(0, 64, 0, 64, -1, 1);
        c->matrixMode(gl::MODELVIEW);
        c->loadIdentity();
        c->enable(gl::BLEND);
        c->blendFunc(gl::ONE, gl::ONE);
        c->begin(gl::TRIANGLES);
        SceneRng rv(seed + vertex_seed_offset);
        for (int k = 0; k < triangles; ++k) {
          const int x = rv.i(0, max_corner), y = rv.i(0, max_corner);
          const int a = 1 << rv.i(0, max_log_leg), b = 1 << rv.i(0, max_log_leg);
          const bool flip = rv.b(50), projective = projective_percent > 0 && rv.b(projective_percent);
          const int px[3] = {x, x + a, x}, py[3] = {y, y, y + b};
          for (int v = 0; v < 3; ++v) {
            const int i = flip ? 2 - v : v;
            for (GLenum u = 0; u < 2; ++u) texcoord(*c, gl::TEXTURE0 + u, rv, projective);
            c->color4(rv.d(0, 1), rv.d(0, 1), rv.d(0, 1), rv.d(0, 1));
            c->vertex3(px[i], py[i], rv.d(-0.9, 0.9));
          }
        }
        c->end();
      }
      INFO("profile ", std::string(profile), " seed ", seed);
      REQUIRE(buffer_hashes(p.fast) == buffer_hashes(p.slow));
      fast_runs += p.fast.fast_runs();  // (textures whose result depends on λ take the reference path)
    }
  }
  return fast_runs;
}

}  // namespace

TEST_CASE("fast draw: triangles of power-of-two area (divisions by A as multiplications), span == per-fragment") {
  // Right triangles with legs of 2^a and 2^b pixels at integer corners: twice the
  // area in grid units is 2^(a + b + 2S), the case where the span path multiplies
  // by 1/A instead of dividing. Affine (q = 1) and projective texture coordinates.
  const std::uint64_t fast_runs =
      compare_pow2_triangles(300, 7, 6, 40, 4, 40, [](Context& c, GLenum unit, SceneRng& rv, bool projective) {
        c.multiTexCoord4(unit, rv.d(-2, 2), rv.d(-2, 2), 0, projective ? rv.d(0.5, 2) : 1.0);
      });
  CHECK(fast_runs > 500);
}

TEST_CASE("fast draw: dyadic texture coordinates on power-of-two areas (the exact progression V_0 + i·D), span == per-fragment") {
  // Right triangles of power-of-two area with affine (q = 1) coordinates that
  // are integer multiples of a power of two: the span path steps them as
  // V_0 + i·D when every product and partial sum of the reference's formula is
  // exact (draw_span.cpp's bound 2·W·Σ|m| < 2^53), and falls back to the formula
  // otherwise. The multiples range from a few bits (texel-aligned quads) to 50
  // bits (over the bound), with exponents from 2^-40 to 2^20, zeros and
  // negatives, so both sides of the bound and exact cancellations to +0 occur.
  auto dyadic = [](SceneRng& rv) {
    if (rv.b(10)) return 0.0;
    const int bits = rv.b(70) ? rv.i(1, 12) : rv.b(50) ? rv.i(13, 30) : rv.i(31, 50);
    const double m = std::floor(rv.d(-1, 1) * std::ldexp(1.0, bits));
    return std::ldexp(m, -rv.i(0, 40) + (rv.b(10) ? 60 : 0));
  };
  const std::uint64_t fast_runs =
      compare_pow2_triangles(500, 11, 8, 30, 5, 0, [&](Context& c, GLenum unit, SceneRng& rv, bool) {
        c.multiTexCoord4(unit, dyadic(rv), dyadic(rv), 0, 1.0);
      });
  CHECK(fast_runs > 500);
}

TEST_CASE("fast draw: one REPLACE unit (texels straight to the fragment colours), every base format, span == per-fragment") {
  // The span path samples a lone REPLACE unit of an RGBA texture at the colour
  // width straight into the fragment colours; every other base format (RGB keeps
  // the primary alpha, ALPHA the primary colour...) or width takes the texture
  // environment. Scenes of one REPLACE unit, the colour sum on or off.
  std::uint64_t fast_runs = 0;
  for (const char* profile : {"geforce256", "rgba12"}) {
    for (std::uint32_t seed = 600; seed < 600 + 2 * kCases; ++seed) {
      Pair p(profile);
      for (Context* c : {&p.fast, &p.slow}) {
        SceneRng r(seed);
        random_clear_and_projection(*c, r, 0);
        random_texture(*c, r, 0, 1);
        c->texEnvi(gl::TEXTURE_ENV, gl::TEXTURE_ENV_MODE, gl::REPLACE);
        c->activeTexture(gl::TEXTURE1);
        c->disable(gl::TEXTURE_2D);
        c->activeTexture(gl::TEXTURE0);
        c->disable(gl::REGISTER_COMBINERS_NV);
        if (r.b(20)) c->enable(gl::COLOR_SUM);
        else c->disable(gl::COLOR_SUM);
        c->shadeModel(r.b(80) ? gl::SMOOTH : gl::FLAT);
        random_fragment_ops(*c, r);
        const bool aligned = r.b(40);
        c->begin(gl::TRIANGLES);
        for (int k = 0; k < 18; ++k) random_vertex(*c, r, aligned);
        c->end();
      }
      INFO("profile ", std::string(profile), " seed ", seed);
      REQUIRE(buffer_hashes(p.fast) == buffer_hashes(p.slow));
      fast_runs += p.fast.fast_runs();
    }
  }
  CHECK(fast_runs > 500);
}

TEST_CASE("fast draw: vertex colours converted once per run of equal colours, span == per-fragment") {
  // The fast path keeps the last vertex colour conversion; colours here repeat,
  // or differ from the previous vertex's in one channel only (primary or
  // secondary), so a memo that compared too little would show.
  for (const char* profile : {"geforce256", "rgba10"}) {
    for (std::uint32_t seed = 900; seed < 900 + kCases; ++seed) {
      Pair p(profile);
      for (Context* c : {&p.fast, &p.slow}) {
        SceneRng r(seed);
        random_clear_and_projection(*c, r, 0);
        c->disable(gl::TEXTURE_2D);
        c->enable(gl::COLOR_SUM);
        c->shadeModel(gl::SMOOTH);
        double col[4] = {0.25, 0.5, 0.75, 1.0}, sec[3] = {0.1, 0.2, 0.3};
        c->begin(gl::TRIANGLE_STRIP);
        for (int k = 0; k < 24; ++k) {
          if (r.b(50)) col[r.i(0, 3)] = r.d(0, 1);  // one channel changes, or none
          if (r.b(30)) sec[r.i(0, 2)] = r.d(0, 1);
          c->color4(col[0], col[1], col[2], col[3]);
          c->secondaryColor3(sec[0], sec[1], sec[2]);
          const double W = c->framebuffer().width(), H = c->framebuffer().height();
          c->vertex3(r.d(0, W), r.d(0, H), r.d(-0.9, 0.9));
        }
        c->end();
      }
      INFO("profile ", std::string(profile), " seed ", seed);
      REQUIRE(buffer_hashes(p.fast) == buffer_hashes(p.slow));
    }
  }
}

namespace {

// A strip of small triangles wandering over part of the window (so later
// triangles land on pixels of earlier ones), with order-dependent fragment
// operations, and two units whose coordinates are the same at some vertices and
// not at others (the sharing of coordinates changes from triangle to triangle).
void draw_folded_strip(Context& c, std::uint32_t seed, int vertices) {
  SceneRng r(seed);
  random_clear_and_projection(c, r, 0.5);
  c.matrixMode(gl::PROJECTION);  // window coordinates
  c.loadIdentity();
  c.ortho(0, c.framebuffer().width(), 0, c.framebuffer().height(), -1, 1);
  c.matrixMode(gl::MODELVIEW);
  c.loadIdentity();
  for (int u = 0; u < 2; ++u) random_texture(c, r, u, static_cast<std::uint32_t>(1 + u));
  if (r.b(40)) random_combiners(c, r);
  else c.disable(gl::REGISTER_COMBINERS_NV);
  c.shadeModel(gl::SMOOTH);
  switch (seed % 3) {
    case 0:  // blending: every fragment reads what the one before it on its pixel wrote
      c.enable(gl::BLEND);
      c.blendFunc(gl::ONE, r.b(50) ? gl::ONE : gl::ONE_MINUS_SRC_ALPHA);
      c.blendEquation(r.b(50) ? gl::FUNC_ADD : gl::FUNC_REVERSE_SUBTRACT);
      break;
    case 1:  // stencil counts the fragments per pixel; the alpha test drops some
      c.enable(gl::STENCIL_TEST);
      c.stencilFunc(gl::GEQUAL, 3, 0xFF);
      c.stencilOp(gl::INCR, gl::DECR, gl::INCR);
      c.enable(gl::ALPHA_TEST);
      c.alphaFunc(gl::GREATER, 0.2);
      break;
    default:  // depth test with writes: the nearer fragment wins whatever the order of stages
      c.enable(gl::DEPTH_TEST);
      c.depthFunc(r.b(50) ? gl::LESS : gl::GEQUAL);
      c.enable(gl::BLEND);
      c.blendFunc(gl::SRC_ALPHA, gl::ONE_MINUS_SRC_ALPHA);
      break;
  }
  const double W = c.framebuffer().width(), H = c.framebuffer().height();
  double x = r.d(0.3 * W, 0.7 * W), y = r.d(0.3 * H, 0.7 * H);
  c.begin(r.b(70) ? gl::TRIANGLE_STRIP : gl::TRIANGLES);
  for (int k = 0; k < vertices; ++k) {
    x = std::clamp(x + r.d(-7, 7), 0.0, W);
    y = std::clamp(y + r.d(-7, 7), 0.0, H);
    c.color4(r.d(0, 1), r.d(0, 1), r.d(0, 1), r.d(0, 1));
    const double s = r.d(-2, 2), t = r.d(-2, 2), q = r.b(70) ? 1.0 : r.d(0.5, 2);
    c.multiTexCoord4(gl::TEXTURE0, s, t, 0, q);
    if (r.b(70)) c.multiTexCoord4(gl::TEXTURE1, s, t, 0, q);
    else c.multiTexCoord4(gl::TEXTURE1, r.d(-2, 2), r.d(-2, 2), 0, q);
    c.vertex3(x, y, r.d(-0.9, 0.9));
  }
  c.end();
}

}  // namespace

TEST_CASE("fast draw: runs of several triangles shaded as one group (strips that meet their own pixels), span == per-fragment, 1 and 2 threads") {
  // The span path gathers the runs of consecutive triangles into one group while
  // their pixels are distinct; a run on a pixel of the group closes it first.
  std::uint64_t joined = 0, met = 0;
  for (const char* profile : {"geforce256", "rgba12"})
    for (int threads : {1, 2})
      for (std::uint32_t seed = 1200; seed < 1200 + kCases / 2; ++seed) {
        Pair p(profile, 96, 80);
        for (Context* c : {&p.fast, &p.slow}) {
          c->set_threads(threads);
          draw_folded_strip(*c, seed, 240);
        }
        INFO("profile ", std::string(profile), " threads ", threads, " seed ", seed);
        REQUIRE(buffer_hashes(p.fast) == buffer_hashes(p.slow));
        CHECK(p.slow.span_group_stats().joined == 0);
        joined += p.fast.span_group_stats().joined;
        met += p.fast.span_group_stats().met;
      }
  CHECK(joined > 1000);
  CHECK(met > 100);
}

TEST_CASE("fast draw: a window over the group bitmap's size (a group per triangle), span == per-fragment") {
  // 4096 x 2050 pixels need 64 x 2050 > 2^17 words of one bit per pixel: groups
  // end with their triangle there.
  Pair p("geforce256", 4096, 2050);
  for (Context* c : {&p.fast, &p.slow}) draw_folded_strip(*c, 1300, 120);
  REQUIRE(buffer_hashes(p.fast) == buffer_hashes(p.slow));
  CHECK(p.fast.fast_runs() > 100);
  CHECK(p.fast.span_group_stats().joined == 0);
}

namespace {
// texture_coordinates of unit 0 for a triangle's runs (as the span path hands
// them over: first weights and lengths), into s and t (with their 3 spare slots).
void span_coordinates(const std::array<WindowVertex, 3>& wv, const TriangleCoverage& cov,
                      const std::vector<CoverageRun>& runs, std::vector<float>& s, std::vector<float>& t) {
  const std::array<const WindowVertex*, 3> tv{&wv[0], &wv[1], &wv[2]};
  std::vector<std::array<std::int64_t, 3>> first;
  std::vector<int> length;
  int count = 0;
  for (const CoverageRun& run : runs) {
    first.push_back(run.weight[0]);
    length.push_back(static_cast<int>(run.weight.size()));
    count += length.back();
  }
  s.assign(static_cast<std::size_t>(count) + 3, 0.0f);
  t.assign(s.size(), 0.0f);
  texture_coordinates(tv, 0, cov, FastRuns{first.data(), length.data(), static_cast<int>(runs.size()), count},
                      s.data(), t.data());
}

}  // namespace

TEST_CASE("fast draw: texture_coordinates bit for bit against the reference's formula, dyadic coordinates on power-of-two areas") {
  // The exact progression V_0 + i·D (draw_span.cpp) is taken when every product
  // and partial sum is exact; over the bound (coordinates of up to 52 bits on
  // triangles of up to 2^11 pixels a side) it must fall back to the formula.
  // Compared as bits (±0 included), without the texture sampling that hides an
  // ulp.
  SceneRng r(91);
  const int S = 4;
  int compared = 0;
  for (int k = 0; k < 100 * kCases; ++k) {
    const int la = r.i(0, k % 4 == 0 ? 11 : 6), lb = r.i(0, k % 4 == 0 ? 11 : 6);
    const std::int64_t x = r.i(-50, 50) << S, y = r.i(-50, 50) << S;
    const std::int64_t a = std::int64_t{1} << (la + S), b = std::int64_t{1} << (lb + S);
    std::array<SnappedVertex, 3> v{SnappedVertex{x, y}, SnappedVertex{x + a, y}, SnappedVertex{x, y + b}};
    if (r.b(50)) std::swap(v[1], v[2]);
    std::vector<CoverageRun> runs;
    const TriangleCoverage cov = rasterize_triangle(v, S, -60, -60, 2200, 2200, [&](const TriangleCoverage&, const CoverageRun& run) {
      if (runs.size() < 6) runs.push_back(run);
    });
    if (runs.empty()) continue;
    REQUIRE((cov.area & (cov.area - 1)) == 0);  // a power of two
    auto dyadic = [&] {
      if (r.b(10)) return r.b(50) ? 0.0 : -0.0;
      const int bits = r.b(60) ? r.i(1, 12) : r.i(13, 52);
      const double m = std::floor(r.d(-1, 1) * std::ldexp(1.0, bits));
      return std::ldexp(m, r.i(-45, 5));
    };
    std::array<WindowVertex, 3> wv{};
    for (auto& w : wv) w.tcw[0] = {dyadic(), dyadic(), 1.0};
    std::vector<float> s, t;
    span_coordinates(wv, cov, runs, s, t);
    std::size_t f = 0;
    const double A = static_cast<double>(cov.area);
    for (const CoverageRun& run : runs)
      for (const auto& w : run.weight) {
        double ref[2] = {0.0, 0.0};  // sim/draw.cpp's per-fragment sums, then / A (q = 1: / 1)
        for (int j = 0; j < 2; ++j) {
          for (int q = 0; q < 3; ++q) ref[j] += static_cast<double>(w[static_cast<std::size_t>(q)]) * wv[static_cast<std::size_t>(q)].tcw[0][static_cast<std::size_t>(j)];
          ref[j] = ref[j] / A / 1.0;
        }
        INFO("triangle ", k, " fragment ", f);
        // The binary32 values the sampler rounds the reference's s/q, t/q to.
        REQUIRE(std::bit_cast<std::uint32_t>(s[f]) == std::bit_cast<std::uint32_t>(static_cast<float>(ref[0])));
        REQUIRE(std::bit_cast<std::uint32_t>(t[f]) == std::bit_cast<std::uint32_t>(static_cast<float>(ref[1])));
        ++f;
        ++compared;
      }
  }
  CHECK(compared > 25 * kCases * 100);
}

TEST_CASE("fast draw: texture_coordinates are the reference's binary64 s/q, t/q rounded to binary32, perspective and near rounding boundaries") {
  // texture_coordinates approximates each quotient with one reciprocal and takes
  // the reference's divisions only when the approximation cannot decide the
  // binary32 value (draw_span.cpp, coordinates_rounded). Compared with the
  // reference's formula as bits (±0 included): random perspective triangles
  // (q/w varying), q = 1 on areas that are not powers of two, values out of the
  // tested range (tiny, huge, zero, infinite, NaN; every vertex's q/w scaled by
  // 2^±(195..240)), and coordinates built to put
  // the quotient on or next to a binary32 rounding boundary (a 25-bit midpoint
  // m times q), where only the fallback gives the right value.
  SceneRng r(92);
  const int S = 4;
  int compared = 0, boundary = 0;
  for (int k = 0; k < 72 * kCases; ++k) {
    std::array<SnappedVertex, 3> v{};
    for (auto& p : v) p = SnappedVertex{r.i(-40 << S, 200 << S), r.i(-40 << S, 200 << S)};
    std::vector<CoverageRun> runs;
    const TriangleCoverage cov = rasterize_triangle(v, S, -60, -60, 400, 400, [&](const TriangleCoverage&, const CoverageRun& run) {
      if (runs.size() < 12) runs.push_back(run);
    });
    if (runs.empty()) continue;
    const int kind = k % 6;
    const bool unit_q = kind == 1;
    // An odd integer in [2^24, 2^25) (binary32 holds the even ones there: it is a
    // midpoint between two), scaled by a power of two.
    const double m = (2 * std::floor(r.d(0x1p23, 0x1p24)) + 1) * std::ldexp(1.0, r.i(-30, 0));
    auto special = [&]() -> double {
      switch (r.i(0, 6)) {
        case 0: return 0.0;
        case 1: return -0.0;
        case 2: return r.d(-1, 1) * 0x1p-230;
        case 3: return r.d(-1, 1) * 0x1p230;
        case 4: return INFINITY;
        case 5: return NAN;
        default: return r.d(-3, 3);
      }
    };
    std::array<WindowVertex, 3> wv{};
    for (auto& w : wv) {
      const double q = unit_q ? 1.0 : kind == 2 ? static_cast<double>(r.i(1, 9)) : r.d(0.05, 20.0);
      switch (kind) {
        case 2:  // s = m·q, t = −m·q at every vertex: s/q lands on (or next to) the midpoint m
          w.tcw[0] = {m * q, -m * q, q};
          break;
        case 3:  // special values mixed in
          w.tcw[0] = {r.b(30) ? special() : r.d(-4, 4) * q, r.b(30) ? special() : r.d(-4, 4) * q, r.b(20) ? special() : q};
          break;
        case 4: {  // every value scaled far out: 1/v_2 outside [2^-190, 2^190], the reference's divisions
          const double e = std::ldexp(1.0, r.b(50) ? r.i(195, 240) : -r.i(195, 240));
          w.tcw[0] = {r.d(-4, 4) * q * e, r.d(-4, 4) * q * e, q * e};
          break;
        }
        default: w.tcw[0] = {r.d(-4, 4) * q, r.d(-4, 4) * q, q}; break;
      }
    }
    if (kind == 1 && r.b(50))  // q = 1 with s on the midpoint: v_0 / A = m exactly
      for (auto& w : wv) w.tcw[0] = {m, m, 1.0};
    std::vector<float> s, t;
    span_coordinates(wv, cov, runs, s, t);
    std::size_t f = 0;
    const double A = static_cast<double>(cov.area);
    for (const CoverageRun& run : runs)
      for (const auto& w : run.weight) {
        double sum[3] = {0.0, 0.0, 0.0};  // sim/draw.cpp's per-fragment sums, each / A, then s/q, t/q
        for (int j = 0; j < 3; ++j) {
          for (int q = 0; q < 3; ++q)
            sum[j] += static_cast<double>(w[static_cast<std::size_t>(q)]) * wv[static_cast<std::size_t>(q)].tcw[0][static_cast<std::size_t>(j)];
          sum[j] = sum[j] / A;
        }
        const double ref_s = sum[0] / sum[2], ref_t = sum[1] / sum[2];  // (q = 1: / (A / A) = / 1)
        const auto want_s = static_cast<float>(ref_s), want_t = static_cast<float>(ref_t);
        if (kind == 2 || kind == 1) boundary += std::fabs(static_cast<double>(want_s) - m) < 1e-6 * std::fabs(m);
        INFO("triangle ", k, " kind ", kind, " fragment ", f, " reference s ", ref_s, " t ", ref_t);
        REQUIRE(std::bit_cast<std::uint32_t>(s[f]) == std::bit_cast<std::uint32_t>(want_s));
        REQUIRE(std::bit_cast<std::uint32_t>(t[f]) == std::bit_cast<std::uint32_t>(want_t));
        ++f;
        ++compared;
      }
  }
  CHECK(compared > 20 * kCases * 60);
  CHECK(boundary > kCases * 100);  // the boundary cases did occur
}

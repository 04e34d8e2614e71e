// The raster cache (sim/raster_cache.h, sim/draw_replay.cpp): a multipass scene
// draws the same mesh again and again with new state each pass, as the paper's
// traces do. With the cache on, every pass after the first replays the
// rasterizer's groups, long runs and depth codes; the buffers must be exactly
// those of the same scene with the cache off and of the per-fragment reference.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <array>
#include <utility>
#include <vector>

#include "draw_test_util.h"
#include "fast_scene.h"
#include "sim/raster_cache.h"

using namespace ffsim;
using namespace ffsim::test;

namespace {

constexpr int kW = 192, kH = 128;

struct MeshVertex {
  double x, y, z;
  std::array<double, 4> color, tc0, tc1;
};

// A jittered grid of `cx` x `cy` cells over the window (some vertices outside it),
// per-vertex colours, texture coordinates and depths.
std::vector<MeshVertex> jittered_grid(SceneRng& r, int cx, int cy) {
  std::vector<MeshVertex> g;
  for (int j = 0; j <= cy; ++j)
    for (int i = 0; i <= cx; ++i) {
      MeshVertex v;
      v.x = (i - 0.1) * (kW * 1.2 / cx) + r.d(-3, 3);
      v.y = (j - 0.1) * (kH * 1.2 / cy) + r.d(-3, 3);
      v.z = r.d(-0.5, 0.5);
      v.color = {r.d(0, 1), r.d(0, 1), r.d(0, 1), r.d(0, 1)};
      v.tc0 = {v.x / kW * 2, v.y / kH * 2, 0, 1};
      v.tc1 = r.b(50) ? v.tc0 : std::array<double, 4>{r.d(-1, 2), r.d(-1, 2), 0, r.b(80) ? 1.0 : r.d(0.5, 2)};
      g.push_back(v);
    }
  return g;
}

// jittered_grid with every vertex moved inside the window (at least one pixel
// from its edges): with an orthographic window projection, every vertex is
// inside the view volume.
std::vector<MeshVertex> jittered_grid_inside(SceneRng& r, int cx, int cy) {
  std::vector<MeshVertex> mesh = jittered_grid(r, cx, cy);
  for (MeshVertex& v : mesh) {
    v.x = std::clamp(v.x, 1.0, kW - 1.0);
    v.y = std::clamp(v.y, 1.0, kH - 1.0);
  }
  return mesh;
}

// `passes` passes over the same geometry: a grid of small cells as triangle
// strips (one glEnd per row), a grid of large cells as GL_TRIANGLES (runs of 64
// fragments and more), each pass with new textures, combiners, fragment
// operations and vertex colours. Sometimes a pass moves the mesh in depth, or
// changes unit 1's texture coordinates (other coords_reuse_mask): those must
// not replay an earlier pass's recording.
void draw_multipass(Context& c, std::uint32_t seed, int passes) {
  SceneRng r(seed);
  random_clear_and_projection(c, r, 0.3);
  const int cx = r.i(8, 20), cy = r.i(6, 14);
  const std::vector<MeshVertex> small = jittered_grid(r, cx, cy), large = jittered_grid(r, 2, 2);
  for (int pass = 0; pass < passes; ++pass) {
    c.flush_deferred();  // (set_defer_draws: before any state change)
    for (int u = 0; u < 2; ++u) random_texture_or_off(c, r, u, static_cast<std::uint32_t>(1 + u + 2 * pass), 75);
    if (r.b(35)) random_combiners(c, r);
    else c.disable(gl::REGISTER_COMBINERS_NV);
    if (r.b(30)) c.enable(gl::COLOR_SUM); else c.disable(gl::COLOR_SUM);
    random_fragment_ops(c, r);
    if (r.b(50)) {  // the depth test on (a replay's depth codes decide it)
      c.enable(gl::DEPTH_TEST);
      c.depthFunc(r.b(50) ? gl::LEQUAL : gl::GEQUAL);
    }
    const double dz = r.b(80) ? 0.0 : r.d(-0.3, 0.3);
    const bool other_tc1 = r.b(15);
    const double tint = r.d(0, 1);
    auto vertex = [&](const MeshVertex& v) {
      c.color4(v.color[0] * tint, v.color[1], v.color[2], v.color[3]);
      c.multiTexCoord4(gl::TEXTURE0, v.tc0[0], v.tc0[1], v.tc0[2], v.tc0[3]);
      if (other_tc1) c.multiTexCoord4(gl::TEXTURE1, v.tc0[1], v.tc0[0], 0, 1);
      else c.multiTexCoord4(gl::TEXTURE1, v.tc1[0], v.tc1[1], v.tc1[2], v.tc1[3]);
      c.vertex3(v.x, v.y, v.z + dz);
    };
    auto at = [](const std::vector<MeshVertex>& g, int cols, int i, int j) -> const MeshVertex& {
      return g[static_cast<std::size_t>(j * (cols + 1) + i)];
    };
    for (int j = 0; j < cy; ++j) {
      c.begin(gl::TRIANGLE_STRIP);
      for (int i = 0; i <= cx; ++i) {
        vertex(at(small, cx, i, j + 1));
        vertex(at(small, cx, i, j));
      }
      c.end();
    }
    c.begin(gl::TRIANGLES);
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        vertex(at(large, 2, i, j)), vertex(at(large, 2, i + 1, j)), vertex(at(large, 2, i + 1, j + 1));
        vertex(at(large, 2, i, j)), vertex(at(large, 2, i + 1, j + 1)), vertex(at(large, 2, i, j + 1));
      }
    c.end();
  }
  c.flush_deferred();
}

}  // namespace

TEST_CASE("raster cache: multipass meshes replayed == rasterized again == per-fragment path, 1 and 2 threads") {
  std::uint64_t hits = 0, misses = 0, scenes = 0;
  for (const char* profile : {"geforce256", "rgba12"})
    for (int threads : {1, 2})
#ifdef FFSIM_SANITIZE
      for (std::uint32_t seed = 900; seed < 903; ++seed) {
#else
      for (std::uint32_t seed = 900; seed < 910; ++seed) {
#endif
        INFO("profile ", std::string(profile), " threads ", threads, " seed ", seed);
        Context cached(profile_named(profile), kW, kH), uncached(profile_named(profile), kW, kH),
            reference(profile_named(profile), kW, kH);
        for (Context* c : {&cached, &uncached, &reference}) c->set_threads(threads);
        for (Context* c : {&cached, &uncached}) c->set_defer_draws(seed % 2 == 0);  // (a batch of several glEnds)
        uncached.set_raster_cache(false);
        reference.set_fast_paths(false);
        for (Context* c : {&cached, &uncached, &reference}) draw_multipass(*c, seed, 4);
        REQUIRE(buffer_hashes(cached) == buffer_hashes(uncached));
        REQUIRE(buffer_hashes(cached) == buffer_hashes(reference));
        CHECK(cached.fragments_written() == uncached.fragments_written());
        CHECK(cached.span_group_stats().joined == uncached.span_group_stats().joined);
        CHECK(cached.span_group_stats().met == uncached.span_group_stats().met);
        CHECK(uncached.raster_cache().hits() == 0);
        ++scenes;
        hits += cached.raster_cache().hits();
        misses += cached.raster_cache().misses();
      }
  // Replays happened, and first sightings, depth moves, new coordinates (about
  // 3 and 2 per scene with these seeds: passes whose textures take the
  // per-fragment path, e.g. mipmaps, do not use the cache).
  MESSAGE("scenes " << scenes << ", hits " << hits << ", misses " << misses);
  CHECK(hits >= 2 * scenes);
  CHECK(misses >= scenes);
}

TEST_CASE("raster cache: a replay needs the same positions, depths and pattern of coordinate sharing") {
  // One strip drawn again unchanged (a hit), moved in depth (a miss), with unit
  // 1's coordinates other than unit 0's at every vertex (every triangle's
  // coords_reuse_mask changes alike: the same groups, a hit), at some vertices
  // only (triangles of different masks: a miss), at some more (the same masks,
  // one run longer: a miss), then as the first time (a hit).
  // The same calls with the cache off leave the same buffers.
  Context c(profile_named("geforce256"), 64, 64), off(profile_named("geforce256"), 64, 64);
  off.set_raster_cache(false);
  for (Context* x : {&c, &off}) {
    ortho_window(*x);
    std::vector<std::uint8_t> texels(4 * 4 * 4);
    for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = static_cast<std::uint8_t>(37 * i);
    for (int u = 0; u < 2; ++u) {
      x->activeTexture(gl::TEXTURE0 + static_cast<GLenum>(u));
      x->bindTexture(gl::TEXTURE_2D, static_cast<std::uint32_t>(1 + u));
      x->texImage2D(gl::TEXTURE_2D, 0, gl::RGBA8, 4, 4, 0, gl::RGBA, gl::UNSIGNED_BYTE, texels.data());
      x->texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MIN_FILTER, gl::LINEAR);
      x->texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MAG_FILTER, gl::LINEAR);
      x->texEnvi(gl::TEXTURE_ENV, gl::TEXTURE_ENV_MODE, gl::ADD);
      x->enable(gl::TEXTURE_2D);
    }
    x->enable(gl::BLEND);
    x->blendFunc(gl::ONE, gl::ONE);
  }
  enum Coords { kSame, kOther, kMixed, kMixedEarlier };  // unit 1's against unit 0's
  auto strip = [&](double z, Coords coords) {
    for (Context* x : {&c, &off}) {
      x->begin(gl::TRIANGLE_STRIP);
      for (int i = 0; i <= 4; ++i)
        for (int j : {1, 0}) {
          const bool other = coords == kOther || (coords == kMixed && i >= 3) || (coords == kMixedEarlier && i >= 2);
          x->multiTexCoord2(gl::TEXTURE0, i / 4.0, j);
          x->multiTexCoord2(gl::TEXTURE1, other ? j : i / 4.0, other ? i / 4.0 : j);
          x->vertex3(3 + 14.5 * i, 5 + 40.0 * j, z);
        }
      x->end();
    }
  };
  strip(0.25, kSame);
  CHECK(c.raster_cache().misses() == 1);
  strip(0.25, kSame);
  CHECK(c.raster_cache().hits() == 1);
  strip(0.5, kSame);
  CHECK(c.raster_cache().misses() == 2);
  strip(0.25, kOther);
  CHECK(c.raster_cache().hits() == 2);
  strip(0.25, kMixed);
  CHECK(c.raster_cache().misses() == 3);
  // The same two masks in the same order, the change two triangles earlier: the
  // key's runs of labels differ in length (a miss); kMixed again is a hit.
  strip(0.25, kMixedEarlier);
  CHECK(c.raster_cache().misses() == 4);
  strip(0.25, kMixed);
  CHECK(c.raster_cache().hits() == 3);
  strip(0.25, kSame);
  CHECK(c.raster_cache().hits() == 4);
  CHECK(buffer_hashes(c) == buffer_hashes(off));
  CHECK(off.raster_cache().hits() + off.raster_cache().misses() == 0);
  CHECK(c.raster_cache().bytes() > 0);
  c.set_raster_cache(false);
  CHECK(c.raster_cache().bytes() == 0);
  strip(0.25, kSame);
  CHECK(c.raster_cache().hits() == 4);
  CHECK(buffer_hashes(c) == buffer_hashes(off));
}

TEST_CASE("raster cache: a replay takes the recorded texture coordinates only where every triangle's match") {
  // A recording keeps the first texture coordinates its groups computed, with
  // each triangle's s/w, t/w, q/w (docs/performance.md 16.6). Passes over one
  // mesh (the same positions and depths: every pass after the first a replay)
  // with the texture coordinates of the recording, shifted at every vertex,
  // shifted at a few vertices only (groups whose triangles partly match), or
  // moved by the texture matrix; each pass is added to the colour buffer, so every
  // pass's texels show. Against the same passes with the cache off, and the
  // per-fragment reference, 1 and 2 threads.
  std::uint64_t taken = 0;
  for (int threads : {1, 2})
    for (std::uint32_t seed = 40; seed < 46; ++seed) {
      INFO("threads ", threads, " seed ", seed);
      Context cached(profile_named("geforce256"), kW, kH), uncached(profile_named("geforce256"), kW, kH),
          reference(profile_named("geforce256"), kW, kH);
      uncached.set_raster_cache(false);
      reference.set_fast_paths(false);
      for (Context* x : {&cached, &uncached, &reference}) {
        x->set_threads(threads);
        SceneRng r(seed);
        random_clear_and_projection(*x, r, 0.3);
        ortho_window(*x);  // every vertex inside the view volume (one thread draws shared vertices by the cache)
        const int cx = r.i(8, 20), cy = r.i(6, 14);
        const std::vector<MeshVertex> mesh = jittered_grid_inside(r, cx, cy);
        for (int u = 0; u < 2; ++u) {
          random_texture(*x, r, u, static_cast<std::uint32_t>(1 + u));
          for (GLenum f : {gl::TEXTURE_MIN_FILTER, gl::TEXTURE_MAG_FILTER}) x->texParameteri(gl::TEXTURE_2D, f, gl::LINEAR);
        }
        x->activeTexture(gl::TEXTURE0);
        x->enable(gl::BLEND);
        x->blendFunc(gl::ONE, gl::ONE);
        x->disable(gl::DEPTH_TEST);
        for (int pass = 0; pass < 6; ++pass) {
          enum { kRecorded, kAllShifted, kSomeShifted, kTextureMatrix };
          const int mode = pass == 0 ? kRecorded : r.i(0, 3);
          x->matrixMode(gl::TEXTURE);
          for (int u = 0; u < 2; ++u) {
            x->activeTexture(gl::TEXTURE0 + static_cast<GLenum>(u));
            x->loadIdentity();
            if (mode == kTextureMatrix) x->translate(0.31, -0.17, 0);
          }
          x->matrixMode(gl::MODELVIEW);
          x->activeTexture(gl::TEXTURE0);
          std::size_t index = 0;
          auto vertex = [&](const MeshVertex& v) {
            const bool shift = mode == kAllShifted || (mode == kSomeShifted && index++ % 7 == 3);
            const double ds = shift ? 0.37 : 0.0;
            x->color4(v.color[0], v.color[1], v.color[2], 0.25);
            x->multiTexCoord4(gl::TEXTURE0, v.tc0[0] + ds, v.tc0[1], v.tc0[2], v.tc0[3]);
            x->multiTexCoord4(gl::TEXTURE1, v.tc1[0] + ds, v.tc1[1], v.tc1[2], v.tc1[3]);
            x->vertex3(v.x, v.y, v.z);
          };
          for (int j = 0; j < cy; ++j) {
            x->begin(gl::TRIANGLE_STRIP);
            for (int i = 0; i <= cx; ++i) {
              vertex(mesh[static_cast<std::size_t>((j + 1) * (cx + 1) + i)]);
              vertex(mesh[static_cast<std::size_t>(j * (cx + 1) + i)]);
            }
            x->end();
          }
        }
      }
      REQUIRE(buffer_hashes(cached) == buffer_hashes(uncached));
      REQUIRE(buffer_hashes(cached) == buffer_hashes(reference));
      CHECK(cached.raster_cache().hits() > 0);
      CHECK(uncached.span_group_stats().coords_recorded == 0);
      taken += cached.span_group_stats().coords_recorded;
    }
  MESSAGE("groups that took recorded coordinates: " << taken);
  CHECK(taken > 100);
}

TEST_CASE("raster cache: a replay reuses the depth test's comparisons only while the depth buffer holds the same values") {
  // Passes over one mesh with the depth test on (every pass after the first a
  // replay; docs/performance.md 17.1), each pass's surviving fragments added to
  // the colour buffer, so the result of every pass's depth test shows. Between
  // passes, now and then, something else changes depths or the test: a
  // scissored depth clear, an occluding quad, DrawPixels and CopyPixels of
  // depth, a code written through framebuffer().depth(), another depth
  // function, the depth mask off or on. Against the same calls with the cache off, and the
  // per-fragment reference, 1 and 2 threads.
  std::uint64_t reused = 0;
  for (int threads : {1, 2})
    for (std::uint32_t seed = 60; seed < 72; ++seed) {
      INFO("threads ", threads, " seed ", seed);
      Context cached(profile_named("geforce256"), kW, kH), uncached(profile_named("geforce256"), kW, kH),
          reference(profile_named("geforce256"), kW, kH);
      uncached.set_raster_cache(false);
      reference.set_fast_paths(false);
      for (Context* x : {&cached, &uncached, &reference}) {
        x->set_threads(threads);
        SceneRng r(seed);
        random_clear_and_projection(*x, r, 0.3);
        ortho_window(*x);  // every vertex inside the view volume
        const int cx = r.i(8, 20), cy = r.i(6, 14);
        const std::vector<MeshVertex> mesh = jittered_grid_inside(r, cx, cy);
        x->enable(gl::BLEND);
        x->blendFunc(gl::ONE, gl::ONE);
        x->enable(gl::DEPTH_TEST);
        x->depthFunc(gl::LEQUAL);
        auto rect = [&](int& x0, int& y0, int& w, int& h) {
          x0 = r.i(0, kW - 8), y0 = r.i(0, kH - 8), w = r.i(4, kW - x0), h = r.i(4, kH - y0);
        };
        for (int pass = 0; pass < 14; ++pass) {
          // A schedule, then random events: the mask off in pass 4 and on again
          // in pass 6 (comparisons made where a fragment would store but the
          // mask kept it from storing); a strict function in pass 7 and depths
          // changed in pass 8 (a pass that stores where its own comparisons then
          // change: z < z is false), passes 9 and 10 unchanged.
          static const int kSchedule[] = {0, 0, 0, -1, 7, -2, 8, 10, -1, 0, 0};
          const int planned = pass < 11 ? kSchedule[pass] : -2;
          const int event = planned == -1 ? r.i(1, 5) : planned == -2 ? r.i(0, 9) : planned;
          int x0 = 0, y0 = 0, w = 0, h = 0;
          rect(x0, y0, w, h);
          switch (event) {
            case 1:  // a depth clear of part of the window
              x->enable(gl::SCISSOR_TEST);
              x->scissor(x0, y0, w, h);
              x->clearDepth(r.d(0, 1));
              x->clear(gl::DEPTH_BUFFER_BIT);
              x->disable(gl::SCISSOR_TEST);
              break;
            case 2:  // an occluder, by the current depth test and mask
              x->color4(0.01, 0.02, 0.03, 0.04);
              x->begin(gl::QUADS);
              for (const auto& [qx, qy] : {std::pair{x0, y0}, {x0 + w, y0}, {x0 + w, y0 + h}, {x0, y0 + h}})
                x->vertex3(qx, qy, r.d(-0.5, 0.5));
              x->end();
              break;
            case 3: {  // DrawPixels of depth
              std::vector<float> z(static_cast<std::size_t>(w * h));
              for (float& v : z) v = static_cast<float>(r.d(0, 1));
              x->rasterPos2(x0, y0);
              x->drawPixels(w, h, gl::DEPTH_COMPONENT, gl::FLOAT, z.data());
              break;
            }
            case 4:  // CopyPixels of depth
              x->rasterPos2(r.i(0, kW / 2), r.i(0, kH / 2));
              x->copyPixels(x0, y0, std::min(w, kW / 2), std::min(h, kH / 2), gl::DEPTH);
              break;
            case 5: {  // codes written straight into the buffer
              const std::uint32_t code = static_cast<std::uint32_t>(r.i(0, 0xFFFFFF));
              for (int k = 0; k < 20; ++k)
                x->framebuffer().depth()[x->framebuffer().index(r.i(0, kW - 1), r.i(0, kH - 1))] = code;
              break;
            }
            case 6: {
              static const GLenum kFuncs[] = {gl::LESS, gl::LEQUAL, gl::EQUAL, gl::GEQUAL, gl::GREATER, gl::NOTEQUAL,
                                              gl::ALWAYS, gl::NEVER};
              x->depthFunc(r.pick(kFuncs));
              break;
            }
            case 10: {
              static const GLenum kStrict[] = {gl::LESS, gl::GREATER, gl::NOTEQUAL};
              x->depthFunc(r.pick(kStrict));
              break;
            }
            case 7: x->depthMask(false); break;
            case 8: x->depthMask(true); break;
            default: break;
          }
          const double tint = r.d(0.01, 0.1);
          for (int j = 0; j < cy; ++j) {
            x->begin(gl::TRIANGLE_STRIP);
            for (int i = 0; i <= cx; ++i)
              for (int row : {j + 1, j}) {
                const MeshVertex& v = mesh[static_cast<std::size_t>(row * (cx + 1) + i)];
                x->color4(tint * v.color[0], tint * v.color[1], tint, tint * v.color[3]);
                x->vertex3(v.x, v.y, v.z);
              }
            x->end();
          }
        }
      }
      REQUIRE(buffer_hashes(cached) == buffer_hashes(uncached));
      REQUIRE(buffer_hashes(cached) == buffer_hashes(reference));
      CHECK(cached.raster_cache().hits() > 0);
      CHECK(uncached.span_group_stats().depth_reused == 0);
      reused += cached.span_group_stats().depth_reused;
    }
  MESSAGE("groups whose depth test took a replay's comparisons: " << reused);
  CHECK(reused > 100);
}

TEST_CASE("raster cache: keys are compared whole, and the cache stays within its byte bound") {
  RasterCache cache;
  auto recording = [](std::size_t depth_codes) {
    std::vector<RasterRecording> r(1);
    RecordedGroup& g = r[0].groups.emplace_back();
    g.depth = r[0].arena.make<std::uint32_t>(depth_codes);
    std::fill(g.depth.begin(), g.depth.end(), 7u);
    r[0].steps.push_back({false, 0});
    return r;
  };
  const std::vector<std::int64_t> a{1, 2, 3}, b{1, 2, 4}, c{1, 2, 3, 0};
  cache.insert(a, recording(10));
  REQUIRE(cache.find(a) != nullptr);
  CHECK(cache.find(a)->front().groups.front().depth.size() == 10);
  CHECK(cache.find(b) == nullptr);  // one word differs
  CHECK(cache.find(c) == nullptr);  // a prefix of another key
  CHECK(cache.hits() == 2);
  CHECK(cache.misses() == 2);
  // A quarter of the bound each: the fifth insertion empties the cache first.
  const std::size_t quarter = RasterCache::kMaxBytes / 4 / sizeof(std::uint32_t);
  for (std::int64_t k = 0; k < 5; ++k) {
    cache.insert({100 + k}, recording(quarter - 1000));
    CHECK(cache.bytes() <= RasterCache::kMaxBytes);
    CHECK(cache.find({100 + k}) != nullptr);
  }
  CHECK(cache.find({100}) == nullptr);  // emptied to make room
  CHECK(cache.find(a) == nullptr);
  // A recording over the bound is never kept (and evicts nothing).
  const std::size_t before = cache.bytes();
  cache.insert({999}, recording(RasterCache::kMaxBytes / sizeof(std::uint32_t) + 1));
  CHECK(cache.find({999}) == nullptr);
  CHECK(cache.bytes() == before);
  cache.clear();
  CHECK(cache.bytes() == 0);
  CHECK(cache.find({104}) == nullptr);
}

TEST_CASE("raster cache: with threads a batch is keyed by its glEnds' memo serials, in order, or by positions") {
  // Two threads with deferred draws: each pass's three strips are one batch, split
  // in bands. A batch whose glEnds all have geometry memo serials is keyed by
  // them (docs/performance.md 19.4): the same strips again hit; a strip moved by
  // one ulp, or the strips in another order, miss. A flat-shaded pass (no shared
  // vertices, so no serial) is keyed by positions: a miss, then a hit when
  // repeated. Every pass's buffers equal the cache off and the per-fragment path.
  constexpr int W = 128, H = 96;
  Context c(profile_named("geforce256"), W, H), off(profile_named("geforce256"), W, H),
      reference(profile_named("geforce256"), W, H);
  off.set_raster_cache(false);
  reference.set_fast_paths(false);
  for (Context* x : {&c, &off, &reference}) {
    x->set_threads(2);
    x->set_defer_draws(true);
    ortho_window(*x);
    x->enable(gl::BLEND);
    x->blendFunc(gl::ONE, gl::ONE);
  }
  auto pass = [&](std::array<int, 3> order, double nudge, bool flat) {
    for (Context* x : {&c, &off, &reference}) {
      x->flush_deferred();
      x->shadeModel(flat ? gl::FLAT : gl::SMOOTH);
      for (const int s : order) {
        x->begin(gl::TRIANGLE_STRIP);
        for (int i = 0; i <= 8; ++i)
          for (int j : {1, 0}) {
            x->color4(0.05 * i, 0.03 * (s + 1), 0.02 * j + 0.01, 0.1);
            const double px = 2.5 + 15.5 * i;
            x->vertex3(s == 1 && nudge != 0 ? std::nextafter(px, 1e9) : px, 1.5 + 31.0 * (s + j), 0);
          }
        x->end();
      }
      x->flush_deferred();
    }
    REQUIRE(buffer_hashes(c) == buffer_hashes(off));
    REQUIRE(buffer_hashes(c) == buffer_hashes(reference));
  };
  pass({0, 1, 2}, 0, false);
  CHECK(c.split_batches() >= 1);
  CHECK(c.raster_cache().misses() == 1);
  pass({0, 1, 2}, 0, false);
  CHECK(c.raster_cache().hits() == 1);
  pass({0, 1, 2}, 1, false);  // strip 1 one ulp to the right: a new serial
  CHECK(c.raster_cache().misses() == 2);
  pass({0, 2, 1}, 0, false);  // the same glEnds (memo hits) in another order
  CHECK(c.raster_cache().misses() == 3);
  pass({0, 1, 2}, 0, false);
  CHECK(c.raster_cache().hits() == 2);
  pass({0, 1, 2}, 0, true);  // flat: keyed by positions
  CHECK(c.raster_cache().misses() == 4);
  pass({0, 1, 2}, 0, true);
  CHECK(c.raster_cache().hits() == 3);
  CHECK(off.raster_cache().hits() + off.raster_cache().misses() == 0);
}

TEST_CASE("raster cache: a group that can change no buffer is left out, and only such a group") {
  // Passes over one mesh, each in one colour (glColor once: every vertex the
  // same codes). Most passes take a colour stage that keeps the destination for
  // their colour (the paper's GL_DST_ALPHA, GL_ONE with A_s = 0; ONE, ONE with
  // 0; MIN with 1; MAX with 0; SRC_ALPHA, ONE_MINUS_SRC_ALPHA with A_s = 0),
  // the others a random one; then, each now and then, what must keep a group
  // in: one vertex of another colour, a texture, a stencil test that writes (or
  // one that does not), the depth mask on after a scissored depth clear to 1
  // (fragments that store), and flat shading. The buffers must be exactly those
  // of the same calls with the cache off and of the per-fragment reference, on
  // 1 and 2 threads (docs/performance.md 34.1).
  std::uint64_t unwritten = 0, reference_unwritten = 0;
  for (int threads : {1, 2})
    for (std::uint32_t seed = 80; seed < 92; ++seed) {
      INFO("threads ", threads, " seed ", seed);
      Context cached(profile_named("geforce256"), kW, kH), uncached(profile_named("geforce256"), kW, kH),
          reference(profile_named("geforce256"), kW, kH);
      uncached.set_raster_cache(false);
      reference.set_fast_paths(false);
      for (Context* x : {&cached, &uncached, &reference}) {
        x->set_threads(threads);
        SceneRng r(seed);
        random_clear_and_projection(*x, r, 0.3);
        ortho_window(*x);
        const int cx = r.i(8, 20), cy = r.i(6, 14);
        const std::vector<MeshVertex> mesh = jittered_grid_inside(r, cx, cy);
        x->enable(gl::BLEND);
        x->enable(gl::DEPTH_TEST);
        x->depthFunc(gl::LEQUAL);
        x->stencilFunc(gl::ALWAYS, 0, 0xFF);
        random_texture(*x, r, 0, 1);
        x->texEnvi(gl::TEXTURE_ENV, gl::TEXTURE_ENV_MODE, gl::REPLACE);
        x->texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MIN_FILTER, gl::NEAREST);  // (the span path's textures)
        x->texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MAG_FILTER, gl::NEAREST);
        x->disable(gl::TEXTURE_2D);
        struct Keeping {
          GLenum eq, sf, df;
          std::array<double, 4> color;  // -1: any code
          std::array<bool, 4> mask;
        };
        static const Keeping kKeeping[] = {
            {gl::FUNC_ADD, gl::DST_ALPHA, gl::ONE, {0, 0, 0, 0}, {false, false, false, true}},  // the paper's
            {gl::FUNC_ADD, gl::ONE, gl::ONE, {0, 0, 0, 0}, {true, true, true, true}},
            {gl::FUNC_REVERSE_SUBTRACT, gl::ONE, gl::ONE, {0, 0, 0, 0}, {true, true, true, true}},
            {gl::MIN, gl::ONE, gl::ONE, {1, 1, 1, 1}, {true, true, true, true}},
            {gl::MAX, gl::ONE, gl::ONE, {0, 0, 0, 0}, {true, true, true, true}},
            {gl::FUNC_ADD, gl::SRC_ALPHA, gl::ONE_MINUS_SRC_ALPHA, {-1, -1, -1, 0}, {true, true, true, true}}};
        struct Mode {
          GLenum eq, sf, df;
        };
        static const Mode kOthers[] = {{gl::FUNC_SUBTRACT, gl::ONE, gl::ONE},
                                       {gl::FUNC_ADD, gl::DST_ALPHA, gl::DST_ALPHA},
                                       {gl::FUNC_ADD, gl::ONE, gl::ONE},
                                       {gl::FUNC_ADD, gl::ONE, gl::ZERO}};
        static const double kCodes[] = {0.0, 1.0 / 255, 254.0 / 255, 1.0};
        for (int pass = 0; pass < 20; ++pass) {
          std::array<double, 4> color{r.pick(kCodes), r.pick(kCodes), r.pick(kCodes), r.pick(kCodes)};
          if (pass == 0) {  // colour and depth written
            x->blendEquation(gl::FUNC_ADD);
            x->blendFunc(gl::ONE, gl::ZERO);
          } else if (r.b(70)) {
            const Keeping& k = r.pick(kKeeping);
            x->blendEquation(k.eq);
            x->blendFunc(k.sf, k.df);
            x->colorMask(k.mask[0], k.mask[1], k.mask[2], k.mask[3]);
            for (int c = 0; c < 4; ++c)
              if (k.color[static_cast<std::size_t>(c)] >= 0) color[static_cast<std::size_t>(c)] = k.color[static_cast<std::size_t>(c)];
          } else {
            const Mode& m = r.pick(kOthers);
            x->blendEquation(m.eq);
            x->blendFunc(m.sf, m.df);
            x->colorMask(r.b(60), r.b(60), r.b(60), r.b(80));
          }
          x->shadeModel(r.b(70) ? gl::SMOOTH : gl::FLAT);
          x->depthMask(pass == 0 || r.b(70));
          if (pass > 0 && r.b(20)) {  // a stencil test: writing (INCR) or not (KEEP)
            x->enable(gl::STENCIL_TEST);
            x->stencilOp(gl::KEEP, gl::KEEP, r.b(50) ? gl::INCR : gl::KEEP);
          } else {
            x->disable(gl::STENCIL_TEST);
          }
          if (pass > 0 && r.b(20)) x->enable(gl::TEXTURE_2D);
          else x->disable(gl::TEXTURE_2D);
          if (pass > 0 && r.b(20)) {  // far depths under part of the mesh: its fragments there store
            x->enable(gl::SCISSOR_TEST);
            x->scissor(r.i(0, kW / 2), r.i(0, kH / 2), kW / 2, kH / 2);
            x->clearDepth(1);
            x->clear(gl::DEPTH_BUFFER_BIT);
            x->disable(gl::SCISSOR_TEST);
          }
          const int odd = r.b(20) ? r.i(0, (cx + 1) * 2 - 1) : -1;  // a vertex of another colour in every strip
          for (int j = 0; j < cy; ++j) {
            x->begin(gl::TRIANGLE_STRIP);
            int k = 0;
            for (int i = 0; i <= cx; ++i)
              for (int row : {j + 1, j}) {
                const MeshVertex& v = mesh[static_cast<std::size_t>(row * (cx + 1) + i)];
                if (k++ == odd) x->color4(0.5, 0.25, 0.75, 0.5);
                else x->color4(color[0], color[1], color[2], color[3]);
                x->texCoord2(v.tc0[0], v.tc0[1]);
                x->vertex3(v.x, v.y, v.z);
              }
            x->end();
          }
        }
      }
      REQUIRE(buffer_hashes(cached) == buffer_hashes(uncached));
      REQUIRE(buffer_hashes(cached) == buffer_hashes(reference));
      unwritten += cached.span_group_stats().unwritten;
      reference_unwritten += reference.span_group_stats().unwritten;
    }
  MESSAGE("groups left out: " << unwritten);
  CHECK(unwritten > 1000);
  CHECK(reference_unwritten == 0);  // (the per-fragment path writes every fragment)
}

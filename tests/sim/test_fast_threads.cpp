// Row bands on worker threads (sim/draw.cpp, sim/worker_pool.*): the polygons of
// a glEnd are rasterized in bands of rows, every band walking all of them in
// order. Random scenes with large triangles, meshes of small triangles, and
// overlapping triangles whose order matters, drawn with 1 and with 2, 3 or 4
// threads (span path on and off), must leave identical buffers in every profile;
// the split must happen. The terrain trace likewise.
#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>
#include <sstream>

#include "fast_scene.h"
#include "sim/trace/executor.h"
#include "sim/trace/trace.h"
#include "sim/worker_pool.h"

using namespace ffsim;
using namespace ffsim::test;

namespace {

// A 10 x 6 grid of 16 x 20-pixel cells over a 160 x 120 window (jittered, per
// vertex colours, texture coordinates and depth): 120 triangles, each far below
// kSplitFragments, drawn twice over: as triangle strips (one glEnd per row of
// cells, 20 triangles) and as one GL_TRIANGLES batch of all 120. Random
// textures, sometimes combiners, random fragment operations, then the depth
// test and blending forced on for the second pass. `defer`: with deferred draws
// (Context::set_defer_draws), flush_deferred() before each pass's state changes
// and at the end, as the trace executor calls it.
constexpr int kMeshW = 160, kMeshH = 120, kCellsX = 10, kCellsY = 6;

void draw_mesh_scene(Context& c, std::uint32_t seed, bool defer = false) {
  SceneRng r(seed);
  random_clear_and_projection(c, r, 0.5);
  struct V {
    double x, y, z;
    std::array<double, 4> color, secondary;
    std::array<double, 4> tc0, tc1;
  };
  std::vector<V> grid;
  for (int j = 0; j <= kCellsY; ++j)
    for (int i = 0; i <= kCellsX; ++i) {
      V v;
      const double jx = i == 0 || i == kCellsX ? 0 : r.d(-5, 5), jy = j == 0 || j == kCellsY ? 0 : r.d(-6, 6);
      v.x = i * (kMeshW / kCellsX) + jx;
      v.y = j * (kMeshH / kCellsY) + jy;
      v.z = r.d(-0.3, 0.3);
      v.color = {r.d(0, 1), r.d(0, 1), r.d(0, 1), r.d(0, 1)};
      v.secondary = {r.d(0, 1), r.d(0, 1), r.d(0, 1), 0};
      v.tc0 = {v.x / kMeshW * 2, v.y / kMeshH * 2, 0, 1};
      v.tc1 = {r.d(-1, 2), r.d(-1, 2), 0, r.b(80) ? 1.0 : r.d(0.5, 2)};
      grid.push_back(v);
    }
  auto vertex = [&](int i, int j, double dz) {
    const V& v = grid[static_cast<std::size_t>(j * (kCellsX + 1) + i)];
    c.color4(v.color[0], v.color[1], v.color[2], v.color[3]);
    c.secondaryColor3(v.secondary[0], v.secondary[1], v.secondary[2]);
    c.multiTexCoord4(gl::TEXTURE0, v.tc0[0], v.tc0[1], v.tc0[2], v.tc0[3]);
    c.multiTexCoord4(gl::TEXTURE1, v.tc1[0], v.tc1[1], v.tc1[2], v.tc1[3]);
    c.vertex3(v.x, v.y, v.z + dz);
  };
  for (int pass = 0; pass < 2; ++pass) {
    if (defer) c.flush_deferred();
    for (int u = 0; u < 2; ++u) random_texture_or_off(c, r, u, static_cast<std::uint32_t>(1 + u + 2 * pass), 75);
    if (r.b(40)) random_combiners(c, r);
    else c.disable(gl::REGISTER_COMBINERS_NV);
    if (r.b(30)) c.enable(gl::COLOR_SUM); else c.disable(gl::COLOR_SUM);
    c.shadeModel(r.b(80) ? gl::SMOOTH : gl::FLAT);
    random_fragment_ops(c, r);
    if (pass == 1) {
      c.enable(gl::DEPTH_TEST);
      c.depthFunc(gl::LEQUAL);
      c.enable(gl::BLEND);
      c.blendFunc(gl::SRC_ALPHA, gl::ONE_MINUS_SRC_ALPHA);
      c.blendEquation(gl::FUNC_ADD);
    }
    const double dz = pass == 0 ? 0 : r.d(-0.2, 0.2);
    if (pass == 0)
      for (int j = 0; j < kCellsY; ++j) {
        c.begin(gl::TRIANGLE_STRIP);
        for (int i = 0; i <= kCellsX; ++i) {
          vertex(i, j + 1, dz);
          vertex(i, j, dz);
        }
        c.end();
      }
    else {
      c.begin(gl::TRIANGLES);
      for (int j = 0; j < kCellsY; ++j)
        for (int i = 0; i < kCellsX; ++i) {
          vertex(i, j, dz), vertex(i + 1, j, dz), vertex(i + 1, j + 1, dz);
          vertex(i, j, dz), vertex(i + 1, j + 1, dz), vertex(i, j + 1, dz);
        }
      c.end();
    }
  }
  if (defer) c.flush_deferred();
}

// 300 small triangles (sides up to 24 pixels) piled on the middle of a 128 x 96
// window in one GL_TRIANGLES batch, blended (SRC_ALPHA, ONE_MINUS_SRC_ALPHA) with
// FUNC_ADD and counted by stencil INCR: each pixel's result depends on the order
// of its fragments. `reverse` draws them in the opposite order.
void draw_overlap_scene(Context& c, std::uint32_t seed, bool reverse) {
  SceneRng r(seed);
  ortho_window(c);
  c.clearColor(0.2, 0.3, 0.4, 0.5);
  c.clearStencil(0);
  c.clear(gl::COLOR_BUFFER_BIT | gl::STENCIL_BUFFER_BIT | gl::DEPTH_BUFFER_BIT);
  c.enable(gl::BLEND);
  c.blendFunc(gl::SRC_ALPHA, gl::ONE_MINUS_SRC_ALPHA);
  c.blendEquation(gl::FUNC_ADD);
  c.enable(gl::STENCIL_TEST);
  c.stencilFunc(gl::ALWAYS, 0, 0xFF);
  c.stencilOp(gl::KEEP, gl::KEEP, gl::INCR);
  struct V {
    double x, y;
    std::array<double, 4> color;
  };
  std::vector<V> v;
  for (int k = 0; k < 300; ++k) {
    const double cx = r.d(40, 88), cy = r.d(28, 68);
    for (int j = 0; j < 3; ++j)
      v.push_back({cx + r.d(-12, 12), cy + r.d(-12, 12), {r.d(0, 1), r.d(0, 1), r.d(0, 1), r.d(0.2, 0.9)}});
  }
  if (reverse)
    for (std::size_t k = 0; k < v.size() / 2; k += 3)  // whole triangles, each kept as it is
      for (std::size_t j = 0; j < 3; ++j) std::swap(v[k + j], v[v.size() - 3 - k + j]);
  c.begin(gl::TRIANGLES);
  for (const V& p : v) {
    c.color4(p.color[0], p.color[1], p.color[2], p.color[3]);
    c.vertex2(p.x, p.y);
  }
  c.end();
}

// Yields until cond() holds or 20 s have passed; whether it holds. The pool
// tests' waits, so that a wrong schedule fails instead of hanging.
template <class Cond>
bool wait_for(Cond cond) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!cond() && std::chrono::steady_clock::now() < end) std::this_thread::yield();
  return cond();
}

}  // namespace

TEST_CASE("fast threads: row bands on 2 and 3 threads == one thread, random scenes, all profiles") {
  std::uint64_t splits = 0;
  SceneOptions opt;
  opt.triangles = 3;
  for (const char* profile : kFastProfiles)
#ifdef FFSIM_SANITIZE
    for (std::uint32_t seed = 300; seed < 303; ++seed) {
#else
    for (std::uint32_t seed = 300; seed < 306; ++seed) {
#endif
      Context one(profile_named(profile), 128, 96);
      draw_random_scene(one, seed, opt);
      for (int threads : {2, 3})
        for (bool fast : {true, false}) {
          Context many(profile_named(profile), 128, 96);
          many.set_threads(threads);
          many.set_fast_paths(fast);
          draw_random_scene(many, seed, opt);
          INFO("profile ", profile, " seed ", seed, " threads ", threads, " fast ", fast);
          REQUIRE(buffer_hashes(many) == buffer_hashes(one));
          CHECK(many.fragments_written() == one.fragments_written());
          splits += many.split_triangles();
        }
      CHECK(one.split_triangles() == 0);
    }
  CHECK(splits > 25);
}

TEST_CASE("fast threads: the probe keeps one thread") {
  Context ctx(profile_named("geforce256"), 128, 96);
  ctx.set_threads(3);
  ctx.probe().set_target(5, 5);
  draw_random_scene(ctx, 301);
  CHECK(ctx.split_triangles() == 0);
  draw_mesh_scene(ctx, 700);  // glEnd batches worth splitting
  CHECK(ctx.split_batches() == 0);
}

TEST_CASE("fast threads: the pool runs every task once and rethrows a task's exception") {
  WorkerPool pool(3);
  for (int round = 0; round < 50; ++round) {
    std::vector<std::atomic<int>> hits(37);
    pool.run(37, [&](int i) { ++hits[static_cast<std::size_t>(i)]; });
    for (auto& h : hits) REQUIRE(h.load() == 1);
  }
  CHECK_THROWS_AS(pool.run(5, [](int i) { if (i == 3) throw std::runtime_error("task 3"); }), std::runtime_error);
  int sum = 0;
  pool.run(1, [&](int) { sum = 1; });  // usable after an exception
  CHECK(sum == 1);
}

TEST_CASE("fast threads: the pool runs a task on its home thread first, and steals from the back") {
  // Two participants, eight tasks: the caller's home is 0..3, the worker's 4..7.
  // Task 0 holds the caller until the worker has started a task (so the worker
  // can only have taken its own first, 4); task 4 holds the worker until 5, 6
  // and 7 have ended, which only the caller can do, by stealing them from the
  // back. Every wait has a time-out, so a wrong schedule fails instead of hanging.
  WorkerPool pool(2);
  for (int round = 0; round < 20; ++round) {
    const std::thread::id caller = std::this_thread::get_id();
    std::mutex m;
    std::vector<int> on_caller, on_worker;
    std::atomic<int> worker_started{0}, tail_done{0};
    std::atomic<bool> timed_out{false};
    pool.run(8, [&](int i) {
      const bool here = std::this_thread::get_id() == caller;
      {
        std::lock_guard<std::mutex> g(m);
        (here ? on_caller : on_worker).push_back(i);
      }
      if (!here) ++worker_started;
      if (i == 0 && !wait_for([&] { return worker_started.load() > 0; })) timed_out = true;
      if (i == 4 && !wait_for([&] { return tail_done.load() == 3; })) timed_out = true;
      if (i >= 5) ++tail_done;
    });
    REQUIRE_FALSE(timed_out.load());
    CHECK(on_caller == std::vector<int>{0, 1, 2, 3, 7, 6, 5});
    CHECK(on_worker == std::vector<int>{4});
    CHECK(pool.stolen() == 3);
  }
  // One participant: its home is every task, in order; nothing is stolen.
  WorkerPool alone(1);
  std::vector<int> order;
  alone.run(5, [&](int i) { order.push_back(i); });
  CHECK(order == std::vector<int>{0, 1, 2, 3, 4});
  CHECK(alone.stolen() == 0);
}

TEST_CASE("fast threads: on_caller runs every task on the calling thread, in order, and waits for nobody") {
  WorkerPool pool(3);
  const std::thread::id caller = std::this_thread::get_id();
  std::vector<int> order;
  std::atomic<int> elsewhere{0};
  pool.run(11, [&](int i) {
    if (std::this_thread::get_id() != caller) ++elsewhere;
    order.push_back(i);  // (one thread: no lock needed)
  }, true);
  CHECK(elsewhere.load() == 0);
  CHECK(order == std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10});
  CHECK(pool.stolen() == 0);
  CHECK(pool.last_wait() == std::chrono::steady_clock::duration{0});
  // Every task still runs when one throws; the first exception is rethrown.
  std::vector<int> ran;
  CHECK_THROWS_WITH_AS(pool.run(4, [&](int i) {
    ran.push_back(i);
    if (i == 1 || i == 2) throw std::runtime_error("task " + std::to_string(i));
  }, true), "task 1", std::runtime_error);
  CHECK(ran == std::vector<int>{0, 1, 2, 3});
  // The workers were left alone: the next ordinary run uses them again.
  std::atomic<int> hits{0};
  pool.run(30, [&](int) { ++hits; });
  CHECK(hits.load() == 30);
}

TEST_CASE("fast threads: last_wait is how long the caller waited after its own tasks for a worker's") {
  // Two participants, two tasks: the caller's home is task 0, the worker's task 1.
  // Task 0 holds the caller until the worker has started task 1 (so the caller
  // cannot steal it), which then sleeps 30 ms: the caller, done, waits for it.
  // So last_wait is at least about 30 ms, and at most the run's wall time. Every
  // wait has a time-out, so a wrong schedule fails instead of hanging.
  using Clock = std::chrono::steady_clock;
  WorkerPool pool(2);
  const std::thread::id caller = std::this_thread::get_id();
  for (int round = 0; round < 3; ++round) {
    std::atomic<bool> started{false}, timed_out{false};
    const auto t0 = Clock::now();
    pool.run(2, [&](int i) {
      if (i == 0) {
        if (!wait_for([&] { return started.load(); })) timed_out = true;
      } else if (std::this_thread::get_id() != caller) {
        started = true;
        std::this_thread::sleep_for(std::chrono::milliseconds(30));
      }
    });
    const auto wall = Clock::now() - t0;
    REQUIRE_FALSE(timed_out.load());
    CHECK(pool.last_wait() >= std::chrono::milliseconds(20));
    CHECK(pool.last_wait() <= wall);
    CHECK(pool.stolen() == 0);
  }
  // One participant waits for nobody.
  WorkerPool alone(1);
  alone.run(3, [](int) { std::this_thread::sleep_for(std::chrono::milliseconds(1)); });
  CHECK(alone.last_wait() == Clock::duration{0});
}

TEST_CASE("fast threads: last_start is how long after the run began another thread took its first task") {
  // The run begins after t0; the worker takes its task before the task's body
  // starts (t1), so last_start <= t1 - t0. Task 0 (the caller's home) holds the
  // caller until the worker has started task 1 and then 30 ms more, so a
  // last_start measured to the caller's end instead would exceed t1 - t0.
  using Clock = std::chrono::steady_clock;
  WorkerPool pool(2);
  const std::thread::id caller = std::this_thread::get_id();
  for (int round = 0; round < 3; ++round) {
    std::atomic<bool> started{false}, timed_out{false};
    Clock::time_point t1{};
    const auto t0 = Clock::now();
    pool.run(2, [&](int i) {
      if (i == 0) {
        if (!wait_for([&] { return started.load(); })) timed_out = true;
        std::this_thread::sleep_for(std::chrono::milliseconds(30));
      } else if (std::this_thread::get_id() != caller) {
        t1 = Clock::now();
        started = true;
      }
    });
    REQUIRE_FALSE(timed_out.load());
    CHECK(pool.last_start() >= Clock::duration{0});
    CHECK(pool.last_start() <= t1 - t0);
  }
  // One task, the worker's home: whichever thread runs it (the caller steals
  // it when the worker is late), last_start says which. On the worker: at
  // most until the task began. On the caller, no other thread took a task:
  // the time until the caller had run it, at least its 20 ms.
  for (int round = 0; round < 3; ++round) {
    std::atomic<bool> on_caller{false};
    Clock::time_point begun{};
    const auto t0 = Clock::now();
    pool.run(1, [&](int) {
      begun = Clock::now();
      on_caller = std::this_thread::get_id() == caller;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    });
    if (on_caller.load()) CHECK(pool.last_start() >= std::chrono::milliseconds(20));
    else CHECK(pool.last_start() <= begun - t0);
  }
  // Nobody else to start: one participant, or every task on the caller.
  pool.run(2, [](int) {}, true);
  CHECK(pool.last_start() == Clock::duration{0});
  WorkerPool alone(1);
  alone.run(3, [](int) {});
  CHECK(alone.last_start() == Clock::duration{0});
}

TEST_CASE("fast threads: a mesh of small triangles is split by rows as whole batches, identical at 1 to 4 threads") {
  std::uint64_t batches = 0;
  for (const char* profile : kFastProfiles)
#ifdef FFSIM_SANITIZE
    for (std::uint32_t seed = 700; seed < 702; ++seed) {
#else
    for (std::uint32_t seed = 700; seed < 706; ++seed) {
#endif
      Context one(profile_named(profile), kMeshW, kMeshH);
      draw_mesh_scene(one, seed);
      CHECK(one.split_batches() == 0);
      for (int threads : {2, 3, 4})
        for (bool fast : {true, false}) {
          if (!fast && threads != 3) continue;  // the per-fragment path once is enough
          Context many(profile_named(profile), kMeshW, kMeshH);
          many.set_threads(threads);
          many.set_split_fragments(1024);  // (a strip covers about 3200 pixels)
          many.set_fast_paths(fast);
          draw_mesh_scene(many, seed);
          INFO("profile ", std::string(profile), " seed ", seed, " threads ", threads, " fast ", fast);
          REQUIRE(buffer_hashes(many) == buffer_hashes(one));
          CHECK(many.fragments_written() == one.fragments_written());
          // Every glEnd of the scene is worth splitting: 6 strips and one batch of
          // all cells (the view volume may clip a few cells away, or cut some into
          // polygons of more triangles).
          CHECK(many.split_batches() == 7);
          CHECK(many.split_triangles() > kCellsX * kCellsY * 2);
          batches += many.split_batches();
        }
    }
  CHECK(batches > 0);
}

TEST_CASE("fast threads: deferred glEnds reuse the pending batch's set-up, and the next pass's state is seen") {
  // The mesh scene with deferred draws: pass 0's six strips join one batch, the
  // five after the first reusing its shading state, plan and set-up
  // (Context::end); pass 1 changes textures, combiners, fragment operations,
  // depth test and blending after a flush and must be drawn with them. A reuse
  // after the flush (a stale set-up) would draw pass 1 with pass 0's state.
  std::uint64_t reuses = 0;
  for (const char* profile : kFastProfiles)
    for (std::uint32_t seed = 700; seed < 703; ++seed) {
      INFO("profile ", std::string(profile), " seed ", seed);
      Context one(profile_named(profile), kMeshW, kMeshH);
      draw_mesh_scene(one, seed);
      Context many(profile_named(profile), kMeshW, kMeshH);
      many.set_threads(2);
      many.set_split_fragments(1024);
      many.set_defer_draws(true);
      draw_mesh_scene(many, seed, true);
      REQUIRE(buffer_hashes(many) == buffer_hashes(one));
      CHECK(many.fragments_written() == one.fragments_written());
      CHECK(one.deferred_setup_reuses() == 0);
      // Flat shading in pass 0 (a fifth of the seeds) keeps the polygons apart
      // (no shared vertices) but not the batch: five reuses either way.
      CHECK(many.deferred_setup_reuses() == 5);
      CHECK(many.split_batches() == 2);  // (pass 0's strips as one batch, pass 1's glEnd)
      reuses += many.deferred_setup_reuses();
    }
  CHECK(reuses > 0);
}

TEST_CASE("fast threads: overlapping triangles of one batch keep their order in every pixel at 1 to 4 threads") {
  for (const char* profile : {"geforce256", "float32"})
    for (std::uint32_t seed = 40; seed < 43; ++seed) {
      INFO("profile ", std::string(profile), " seed ", seed);
      Context one(profile_named(profile), 128, 96);
      draw_overlap_scene(one, seed, false);
      Context reversed(profile_named(profile), 128, 96);
      draw_overlap_scene(reversed, seed, true);
      // The order shows: the test would see a band that reordered fragments.
      REQUIRE(buffer_hashes(reversed) != buffer_hashes(one));
      for (int threads : {2, 3, 4}) {
        Context many(profile_named(profile), 128, 96);
        many.set_threads(threads);
        draw_overlap_scene(many, seed, false);
        INFO("threads ", threads);
        CHECK(buffer_hashes(many) == buffer_hashes(one));
        CHECK(many.fragments_written() == one.fragments_written());
        CHECK(many.split_batches() == 1);
      }
    }
}

namespace {

// Blended triangles (order matters where they overlap) from a list of corners.
void draw_triangles(Context& c, const std::vector<std::array<double, 2>>& corners) {
  ortho_window(c);
  c.clearColor(0.2, 0.3, 0.4, 0.5);
  c.clear(gl::COLOR_BUFFER_BIT);
  c.enable(gl::BLEND);
  c.blendFunc(gl::SRC_ALPHA, gl::ONE_MINUS_SRC_ALPHA);
  c.begin(gl::TRIANGLES);
  for (std::size_t k = 0; k < corners.size(); ++k) {
    c.color4(0.1 * static_cast<double>(k % 7), 0.5, 1.0 - 0.1 * static_cast<double>(k % 9), 0.4);
    c.vertex2(corners[k][0], corners[k][1]);
  }
  c.end();
}

}  // namespace

TEST_CASE("fast threads: a batch is split by its triangles' areas, not their boxes, and a small window stays on one thread") {
  // Hand count: a sliver (0,0) (160,120) (159,120) covers |160*120 - 120*159|/2
  // = 60 pixels in a box of 160 x 120; twenty sum to 1200 pixels, below
  // kSplitFragments (4096) though their boxes sum to 384000. A half-window
  // triangle (0,0) (160,0) (0,120) covers 9600 pixels, above it.
  static_assert(Context::kSplitFragments == 4096);
  std::vector<std::array<double, 2>> slivers, halves;
  for (int k = 0; k < 20; ++k) {
    slivers.insert(slivers.end(), {{0, 0}, {160, 120}, {159, 120}});
    halves.insert(halves.end(), {{0, 0}, {160, 0}, {0, 120}});
  }
  for (const auto* corners : {&slivers, &halves}) {
    const bool big = corners == &halves;
    Context one(profile_named("geforce256"), 160, 120);
    draw_triangles(one, *corners);
    Context two(profile_named("geforce256"), 160, 120);
    two.set_threads(2);
    draw_triangles(two, *corners);
    INFO("halves ", big);
    CHECK(buffer_hashes(two) == buffer_hashes(one));
    CHECK(two.split_batches() == (big ? 1u : 0u));
  }
  // The estimate is exact for these: the slivers' 1200 pixels split at a
  // threshold of 1200 and not at 1201 (the cross product's scale to pixels,
  // 2^-(2S+1), is DrawSetup::area_scale; 2^-(2S) would count 2400).
  for (const std::int64_t threshold : {std::int64_t{1200}, std::int64_t{1201}}) {
    Context two(profile_named("geforce256"), 160, 120);
    two.set_threads(2);
    two.set_split_fragments(threshold);
    draw_triangles(two, slivers);
    INFO("threshold ", threshold);
    CHECK(two.split_batches() == (threshold == 1200 ? 1u : 0u));
  }
  // A 64 x 36 window holds 2304 pixels, below kSplitFragments: however many
  // triangles a glEnd holds, its draw stays on the calling thread, unless the
  // threshold is lowered below the window.
  std::vector<std::array<double, 2>> quads;
  for (int k = 0; k < 40; ++k) quads.insert(quads.end(), {{0, 0}, {64, 0}, {64, 36}, {0, 0}, {64, 36}, {0, 36}});
  Context one(profile_named("geforce256"), 64, 36);
  draw_triangles(one, quads);
  for (std::int64_t threshold : {Context::kSplitFragments, std::int64_t{1024}}) {
    Context two(profile_named("geforce256"), 64, 36);
    two.set_threads(2);
    two.set_split_fragments(threshold);
    CHECK(two.split_fragments() == threshold);
    draw_triangles(two, quads);
    INFO("threshold ", threshold);
    CHECK(buffer_hashes(two) == buffer_hashes(one));
    CHECK(two.split_batches() == (threshold < 64 * 36 ? 1u : 0u));
  }
}

TEST_CASE("fast threads: pool_seconds is the calling thread's time in the pool's runs, 0 without a split") {
  // The bench's serial part is a frame's time minus pool_seconds (docs/performance.md
  // 31): it must grow with each split (the clear's rows and the batch), stay 0 when
  // nothing is split, and never exceed the wall time around the draws.
  std::vector<std::array<double, 2>> halves;
  for (int k = 0; k < 20; ++k) halves.insert(halves.end(), {{0, 0}, {160, 0}, {0, 120}});
  Context one(profile_named("geforce256"), 160, 120);
  draw_triangles(one, halves);
  CHECK(one.pool_seconds() == 0);
  Context two(profile_named("geforce256"), 160, 120);
  two.set_threads(2);
  two.set_split_fragments(std::int64_t{1} << 40);  // nothing worth splitting
  draw_triangles(two, halves);
  CHECK(two.split_batches() + two.split_clears() == 0);
  CHECK(two.pool_seconds() == 0);
  two.set_split_fragments(Context::kSplitFragments);
  const auto t0 = std::chrono::steady_clock::now();
  draw_triangles(two, halves);
  const double after_one = two.pool_seconds();
  draw_triangles(two, halves);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  REQUIRE(two.split_batches() == 2);
  REQUIRE(two.split_clears() == 2);
  CHECK(after_one > 0);
  CHECK(two.pool_seconds() > after_one);
  CHECK(two.pool_seconds() <= wall);
}

TEST_CASE("fast threads: a borrowed pool goes back to the idle pools and is borrowed again") {
  // 7 threads: a size no other test borrows. Returned pools join the idle pools
  // (the oldest is evicted beyond four); a borrow takes the most recent of its size.
  WorkerPool* first = nullptr;
  {
    std::shared_ptr<WorkerPool> b = WorkerPool::borrow(7);
    std::shared_ptr<WorkerPool> a = WorkerPool::borrow(7);
    REQUIRE(a->threads() == 7);
    CHECK(b.get() != a.get());  // borrowed twice at once: two pools, one user each
    first = b.get();
    std::shared_ptr<WorkerPool> c = WorkerPool::borrow(2);
    CHECK(c->threads() == 2);
    std::atomic<int> sum{0};
    b->run(9, [&](int i) { sum += i; });
    CHECK(sum.load() == 36);
  }
  // Dropped in the order c, a, b: b came back last, so it is borrowed again (no
  // new pool), and still runs tasks.
  std::shared_ptr<WorkerPool> again = WorkerPool::borrow(7);
  CHECK(again.get() == first);
  std::atomic<int> hits{0};
  again->run(30, [&](int) { ++hits; });
  CHECK(hits.load() == 30);
  // Fewer than one thread: a pool of one participant (no worker threads).
  CHECK(WorkerPool::borrow(0)->threads() == 1);
}

TEST_CASE("fast threads: the terrain trace is identical at 1 and 2 threads and its strips are split") {
  // kautz-geforce-aa's terrain (scene 1): 30 triangle strips of 60 small
  // triangles per pass, combiners, blending, depth test. With threads the
  // executor defers draws (Context::set_defer_draws): the strips of one pass join
  // one batch, so a pass is split once, not once per strip.
  trace::LoadOptions lo;
#ifdef FFSIM_SANITIZE
  lo.sets = {{"scene", "1"}, {"tw", "256"}, {"th", "192"}, {"rays", "16"}};
#else
  lo.sets = {{"scene", "1"}, {"tw", "320"}, {"th", "240"}, {"rays", "16"}};
#endif
  const trace::Program prog = trace::load_trace_file(std::string(FFSIM_SOURCE_DIR) + "/traces/kautz-geforce-aa.trace", lo);
  // [2]: two threads with every split task on the calling thread (the bench's
  // frame taken apart, performance.md 38): the same batches, the same bits.
  std::string hashes[3];
  std::uint64_t fragments[3] = {0, 0, 0}, batches[3] = {0, 0, 0}, triangles[3] = {0, 0, 0}, clears[3] = {0, 0, 0};
  double pool_s[3] = {0, 0, 0}, wait_s[3] = {0, 0, 0};
  for (int k : {0, 1, 2}) {
    Context ctx(prog.profile, prog.width, prog.height);
    ctx.set_split_on_caller(k == 2);
    trace::RunOptions ro;
    ro.threads = k == 0 ? 1 : 2;
    std::ostringstream sink;
    const trace::RunResult r = trace::run_program_on(ctx, prog, ro, sink);
    REQUIRE(r.ok);
    CHECK(r.gl_errors.empty());
    CHECK_FALSE(r.hashes.empty());
    std::string& h = hashes[k];
    for (const auto& l : r.hashes) h.append(l.hex).append(" ");
    for (const auto& [b, v] : r.final_hashes) h.append(b).append("=").append(v).append(" ");
    fragments[k] = ctx.fragments_written();
    batches[k] = ctx.split_batches();
    triangles[k] = ctx.split_triangles();
    clears[k] = ctx.split_clears();
    pool_s[k] = ctx.pool_seconds();
    wait_s[k] = ctx.pool_wait_seconds();
  }
  CHECK(hashes[1] == hashes[0]);
  CHECK(fragments[1] == fragments[0]);
  CHECK(hashes[2] == hashes[0]);
  CHECK(fragments[2] == fragments[0]);
  CHECK(batches[2] == batches[1]);
  CHECK(triangles[2] == triangles[1]);
  // The caller's waits are part of its time in the pool; on the caller it waits for nobody.
  CHECK(wait_s[0] == 0);
  CHECK(wait_s[1] <= pool_s[1]);
  CHECK(pool_s[2] > 0);
  CHECK(wait_s[2] == 0);
  CHECK(batches[0] == 0);
  MESSAGE("terrain ", prog.width, "x", prog.height, ": ", batches[1], " batches split at 2 threads, ", fragments[0],
          " fragments");
  CHECK(batches[1] > 0);
  // Merged strips: a strip alone is 60 triangles; the deferred batches of a pass
  // hold all 30 strips (1800 triangles, under the 2048 cap).
  CHECK(triangles[1] > 1000 * batches[1]);
  // Its one glClear (of every buffer) is written in bands at 2 threads.
  CHECK(clears[0] == 0);
  CHECK(clears[1] == 1);
}

TEST_CASE("fast threads: glClear in row bands on 2 and 3 threads == one thread, between draws, all profiles") {
  // Context::clear's rows split over the pool (docs/performance.md 27.1): random
  // scenes, then clears of random buffers, values, colour/stencil/depth masks
  // and scissor boxes (the whole window, a part, or none of it), each followed
  // by a draw, on fresh framebuffers (owed zero fills) and written ones. Every
  // clear is compared; the split must happen, and never on one thread.
  std::uint64_t splits = 0;
  SceneOptions opt;
  opt.triangles = 2;
  for (const char* profile : kFastProfiles)
    for (std::uint32_t seed = 700; seed < 703; ++seed) {
      Context one(profile_named(profile), 96, 64);
      std::vector<std::unique_ptr<Context>> many;
      for (int threads : {2, 3}) {
        many.push_back(std::make_unique<Context>(profile_named(profile), 96, 64));
        many.back()->set_threads(threads);
        many.back()->set_split_fragments(256);
      }
      const bool fresh = seed == 700;  // first clear on owed buffers
      SceneRng r(seed);
      for (int step = 0; step < 8; ++step) {
        const bool scene = step > 0 || !fresh;
        const std::uint32_t scene_seed = seed * 100 + static_cast<std::uint32_t>(step);
        const int which = r.i(0, 7);  // bits: colour, stencil, depth
        const bool scissor = r.b(50);
        const int sx = r.i(-10, 90), sy = r.i(-10, 60), sw = r.i(0, 100), sh = r.i(0, 70);
        const std::array<bool, 4> cm{r.b(80), r.b(80), r.b(80), r.b(80)};
        const std::uint32_t sm = r.b(50) ? 0xFFu : static_cast<std::uint32_t>(r.i(0, 255));
        const bool dm = r.b(80);
        const double cr = r.d(0, 1), cg = r.d(0, 1), ca = r.d(0, 1), cd = r.d(0, 1);
        const int cs = r.i(0, 255);
        auto apply = [&](Context& c) {
          if (scene) draw_random_scene(c, scene_seed, opt);
          c.disable(gl::SCISSOR_TEST);
          if (scissor) c.enable(gl::SCISSOR_TEST), c.scissor(sx, sy, sw, sh);
          c.colorMask(cm[0], cm[1], cm[2], cm[3]);
          c.stencilMask(sm);
          c.depthMask(dm);
          c.clearColor(cr, cg, 0.25, ca);
          c.clearStencil(cs);
          c.clearDepth(cd);
          c.clear(((which & 1) ? gl::COLOR_BUFFER_BIT : 0u) | ((which & 2) ? gl::STENCIL_BUFFER_BIT : 0u) |
                  ((which & 4) ? gl::DEPTH_BUFFER_BIT : 0u));
          c.colorMask(true, true, true, true);
          c.stencilMask(0xFF);
          c.depthMask(true);
          c.disable(gl::SCISSOR_TEST);
        };
        apply(one);
        for (const auto& c : many) {
          apply(*c);
          INFO("profile ", profile, " seed ", seed, " step ", step, " threads ", c->threads());
          REQUIRE(buffer_hashes(*c) == buffer_hashes(one));
        }
      }
      CHECK(one.split_clears() == 0);
      for (const auto& c : many) splits += c->split_clears();
    }
  CHECK(splits > 50);
}

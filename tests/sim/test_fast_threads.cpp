// Row bands on worker threads (sim/draw.cpp, sim/worker_pool.*): random scenes
// with large triangles drawn with 1 and with 2 or 3 threads, span path on and
// off, must leave identical buffers in every profile; the split must happen.
#include <doctest/doctest.h>

#include <atomic>

#include "fast_scene.h"
#include "sim/worker_pool.h"

using namespace ffsim;
using namespace ffsim::test;

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

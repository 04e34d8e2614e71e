// The raster cache (docs/performance.md 13.2): what the span path's rasterizer
// and grouping produced for a sequence of triangles, kept so that the same
// sequence drawn again (the next pass of a multipass algorithm over the same
// mesh) is not rasterized again.
//
// A recording is a pure function of its key: the triangles' snapped window
// positions and depth codes in drawing order, which of them share a
// coords_reuse_mask, the rows drawn, the window, the viewport corner and the
// sub-pixel bits (Context::raster_key). So a replay hands the rest of the span path (shading,
// fragment operations) exactly the runs, groups and depth codes that
// rasterizing would have, in the same order, and every output bit is the same;
// tests/sim/test_raster_cache.cpp draws random scenes with the cache on and off
// and compares.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <utility>
#include <unordered_map>
#include <vector>

#include "pipeline/gl/enums.h"
#include "pipeline/raster/triangle.h"
#include "sim/recording_arena.h"

namespace ffsim {

// A triangle of a recorded group: its index in the sequence (its vertices are the
// current draw's), its coverage, and where its runs start in the group.
struct RecordedTriangle {
  int index = 0;
  TriangleCoverage cov;
  int run_begin = 0, fragment_begin = 0;
};

// A group of runs as shade_group received it (Context::SpanScratch), the depth
// codes shading computed for it (empty without a depth buffer) and the pixel
// indices the fragment operations took. Its arrays live in the recording's
// arena (RasterRecording::arena), written once when recorded.
struct RecordedGroup {
  ArenaArray<std::array<std::int64_t, 3>> weight;
  ArenaArray<int> run_y, run_x0, run_length;
  ArenaArray<RecordedTriangle> triangles;
  int fragments = 0;
  ArenaArray<std::uint32_t> depth;
  ArenaArray<std::uint32_t> pixel;  // y·width + x per fragment, 7 spare (empty: not written by list)
  // The first sampled unit's s/q, t/q as the span path computed them (binary32,
  // one per fragment, 3 spare), and each triangle's s/w, t/w, q/w at its three
  // vertices for that unit; empty when the recording drew no texture. A replay
  // whose triangles have those same bits for a unit takes these values instead
  // of computing them (docs/performance.md 16.6): texture_coordinates is a
  // function of exactly those bits, the coverage and the runs.
  ArenaArray<float> s, t;
  ArenaArray<std::array<std::array<double, 3>, 3>> tcw;
  // The depth test's comparisons on this group's listed fragments (ListedDepthTest,
  // docs/performance.md 17.1), made by a replay while the framebuffer's depth
  // epoch was `epoch`, for `func`; `would_store`: some fragment passing them has
  // a depth other than the stored one. A replay under the same epoch and
  // function takes them instead of reading the depth buffer. Kept by replays of
  // a const recording (a recording is replayed by one thread at a time: its
  // band's), in its arena.
  struct DepthComparisons {
    std::uint64_t epoch = 0;  // 0: none (epochs start at 1)
    GLenum func = 0;
    bool would_store = true;
    ArenaArray<std::uint8_t> cmp;
  };
  mutable DepthComparisons depth_test;
};

// A run of kLongRun fragments or more, shaded on its own.
struct RecordedLongRun {
  int index = 0;
  TriangleCoverage cov;
  int y = 0, x0 = 0, count = 0;
  std::array<std::int64_t, 3> weight{};  // at its first fragment
};

// One sequence's groups and long runs in drawing order, and the grouping
// statistics it added (Context::span_group_stats).
struct alignas(64) RasterRecording {  // (a band's own cache lines: the bands record concurrently)
  struct Step {
    bool long_run = false;
    std::size_t index = 0;  // into groups or long_runs
  };
  std::vector<Step> steps;
  std::vector<RecordedGroup> groups;
  std::vector<RecordedLongRun> long_runs;
  // The groups' arrays (the depth comparisons are added by replays, under the
  // same one-thread-at-a-time rule as RecordedGroup::depth_test).
  mutable RecordingArena arena;
  // A band's recording (Context::flush_batch): the batch's triangles its
  // sequence held, by index in the batch, in order. The key fixes the batch's
  // triangles, their rows and the bands, so a replay's band holds these same
  // ones, and takes them from here instead of testing every triangle's rows.
  std::vector<std::uint32_t> band_triangles;
  std::uint64_t joined = 0, met = 0;
  std::size_t bytes() const;
};

class RasterCache {
 public:
  // At most this many bytes of recordings; an insertion beyond it empties the
  // cache first (a trace's passes reuse the geometry of the pass before).
  static constexpr std::size_t kMaxBytes = std::size_t{64} << 20;

  // The recordings (one per band of rows; one when not split) of `key`, or null.
  const std::vector<RasterRecording>* find(const std::vector<std::int64_t>& key);
  void insert(std::vector<std::int64_t> key, std::vector<RasterRecording> recordings);
  void clear();

  std::uint64_t hits() const { return hits_; }
  std::uint64_t misses() const { return misses_; }
  std::size_t bytes() const { return bytes_; }

 private:
  struct Entry {
    std::vector<std::int64_t> key;
    std::vector<RasterRecording> recordings;
    std::size_t bytes = 0;
  };
  static std::uint64_t hash(const std::vector<std::int64_t>& key);
  std::unordered_map<std::uint64_t, Entry> entries_;  // by hash; the key is compared
  std::size_t bytes_ = 0;
  std::uint64_t hits_ = 0, misses_ = 0;
};

}  // namespace ffsim

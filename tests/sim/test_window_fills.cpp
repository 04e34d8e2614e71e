// A deferred glEnd's window vertices filled by the batch's flush (Context::
// WindowFill, docs/performance.md 35): with threads and deferred draws, a glEnd
// whose vertices are a replayed run's record and whose geometry memo entry gives
// its window positions and batch triangles leaves its window vertices to the
// flush, which fills them over the pool. Checked here: traces of strips drawn
// again (replayed runs) whose buffers and hashes must equal one thread's and the
// per-fragment path's, the fills over the pool and on the caller both taken, and
// the memos changing while fills are pending (a run recorded again replaces the
// record a pending fill reads: the fills are made first). A glEnd of a run just
// called and recorded leaves its fill too (docs/performance.md 39); fills stay
// pending across memo insertions that drop nothing, and those at a memo's
// bound make them first.
#include <doctest/doctest.h>

#include <sstream>
#include <string>

#include "fast_scene.h"
#include "trace_test_util.h"
#include "sim/trace/executor.h"
#include "sim/trace/trace.h"

using namespace ffsim;
using namespace ffsim::test;
using namespace ffsim::trace;

namespace {

struct Outcome {
  RunResult result;
  std::uint64_t fills = 0, pooled = 0, settled = 0, splits = 0, replays = 0, recordings = 0;
};

// mode 0: fast paths, 1: per-fragment path. split: the Context's split_fragments.
Outcome run(const Program& p, int threads, int mode, int split) {
  Context c(p.profile, p.width, p.height);
  if (mode == 1) c.set_fast_paths(false);
  c.set_split_fragments(split);
  RunOptions ro;
  ro.threads = threads;
  std::ostringstream out;
  Outcome o;
  o.result = run_program_on(c, p, ro, out);
  o.fills = c.deferred_window_fills();
  o.pooled = c.split_window_fills();
  o.settled = c.settled_window_fills();
  o.splits = c.split_batches();
  o.replays = c.vertex_run_memo().hits();
  o.recordings = c.vertex_run_memo().misses();
  return o;
}

// `strips` triangle strips of `len` vertices over a 96x64 window, each vertex
// with its own unit-0 (and, with two units, unit-1) coordinates, drawn in
// `passes` passes with additive blending. Between strips of a pass the current
// colour may change (vertex data: the pass stays one deferred batch); a strip's
// run reads it first, so a strip whose colour differs from its recording's is
// called and recorded again, replacing the record an earlier strip of the same
// pass may be waiting on; at the end of each later pass one strip already
// replayed in it is drawn again that way (its record replaced while the
// earlier glEnd's fill reads it). Without `churn`, neither: every strip of a
// later pass replays, and the pass's fills wait for its flush.
std::string strips_trace(const std::string& profile, std::uint32_t seed, int strips, int len, int passes, bool churn) {
  SceneRng r(seed);
  const int units = profile_named(profile.c_str()).texture_units >= 2 && r.b(50) ? 2 : 1;
  std::string t = "ffsim-trace 1\nprofile " + profile +
                  "\nframebuffer 96 64\n"
                  "glMatrixMode GL_PROJECTION\nglOrtho 0 96 0 64 -1 1\nglMatrixMode GL_MODELVIEW\n"
                  "table tex 4 x 1-x 0.25+0.5*x 1\n";
  for (int u = units - 1; u >= 0; --u) {
    t += "glActiveTexture GL_TEXTURE" + std::to_string(u) + "\nglBindTexture GL_TEXTURE_2D " + std::to_string(u + 1) +
         "\nglTexImage2D GL_TEXTURE_2D 0 GL_RGBA 4 1 0 GL_RGBA GL_FLOAT tex\n"
         "glTexParameteri GL_TEXTURE_2D GL_TEXTURE_MIN_FILTER GL_NEAREST\n"
         "glTexParameteri GL_TEXTURE_2D GL_TEXTURE_MAG_FILTER GL_LINEAR\nglEnable GL_TEXTURE_2D\n";
  }
  t += "glEnable GL_BLEND\nglBlendFunc GL_ONE GL_ONE\n";
  // Each strip's calls, the same text in every pass (one run class).
  std::vector<std::string> calls(static_cast<std::size_t>(strips));
  for (int s = 0; s < strips; ++s) {
    std::string& c = calls[static_cast<std::size_t>(s)];
    // Inside the window (shared window vertices, the geometry memo), but the
    // first strip, which crosses its left edge (clipped: drawn polygon by
    // polygon into the same batches).
    const double y0 = r.d(1, 52), h = r.d(2, 10), x0 = s == 0 ? -8 : r.d(0, 8), x1 = r.d(80, 96);
    for (int i = 0; i < len; ++i) {  // each vertex, then the next one's coordinates
      const double x = x0 + (x1 - x0) * (i / 2) / (len / 2), y = y0 + (i % 2) * h + r.d(-0.5, 0.5);
      c += "glVertex2d " + std::to_string(x) + " " + std::to_string(y) + "\n";
      for (int u = 0; u < units; ++u)
        c += "glMultiTexCoord2d GL_TEXTURE" + std::to_string(u) + " " + std::to_string(r.d(-1, 2)) + " " +
             std::to_string(r.d(-1, 2)) + "\n";
    }
  }
  const std::string colours[] = {"0.125 0.25 0.0625 0.5", "0.0625 0.125 0.25 1", "0.25 0 0.125 0.75"};
  // A strip: the first vertex's coordinates (set before glBegin, read first by
  // the strip's run, so compared by its replay), then the run.
  auto strip = [&](int s, const char* first) {
    std::string d;
    for (int u = 0; u < units; ++u) d += "glMultiTexCoord2d GL_TEXTURE" + std::to_string(u) + " " + first + "\n";
    return d + "glBegin GL_TRIANGLE_STRIP\n" + calls[static_cast<std::size_t>(s)] + "glEnd\n";
  };
  for (int pass = 0; pass < passes; ++pass) {
    t += "glColor4d " + colours[0] + "\n";
    std::vector<int> replayed;  // strips of this pass drawn with their recording's first coordinates
    for (int s = 0; s < strips; ++s) {
      // From the second pass on, sometimes another colour (filled, not
      // compared: the run still replays), and sometimes other first
      // coordinates: the replay fails, the run is called and recorded again,
      // replacing the record that an earlier glEnd's pending fill may read.
      if (pass > 0 && r.b(25)) t += "glColor4d " + colours[r.i(0, 2)] + "\n";
      const bool other = churn && pass > 0 && r.b(30);
      t += strip(s, other ? "0.75 0.125" : "0.25 0.5");
      // Sometimes the same strip again right away (its run replayed again): the
      // second glEnd reads the record the first one's pending fill reads.
      if (pass > 0 && r.b(20)) t += strip(s, other ? "0.75 0.125" : "0.25 0.5");
      if (!other) replayed.push_back(s);
    }
    // A strip replayed earlier in this pass (its glEnd's fill pending, reading
    // its record) drawn again with other first coordinates: recorded again,
    // its record replaced while that fill is still pending.
    if (churn && pass > 0 && !replayed.empty())
      t += strip(replayed[static_cast<std::size_t>(r.i(0, static_cast<int>(replayed.size()) - 1))], "0.75 0.125");
    t += "hash color\n";
  }
  return t;
}

}  // namespace

TEST_CASE("window fills: strips drawn again on 2 and 3 threads == one thread == per-fragment path") {
  std::uint64_t fills = 0, pooled = 0, settled = 0;
#ifdef FFSIM_SANITIZE
  const std::uint32_t seeds = 3;
#else
  const std::uint32_t seeds = 8;
#endif
  for (const char* profile : {"geforce256", "rgba12"})
    for (std::uint32_t seed = 1; seed <= seeds; ++seed) {
      INFO("profile ", profile, " seed ", seed);
      // Long strips (over kSplitWindowFill vertices a pass): fills over the pool
      // (unless a recording settles them first); short ones: on the caller.
      const bool long_strips = seed % 2 == 1, churn = seed % 4 != 1;
      const Program p = load_trace_text(
          strips_trace(profile, seed, long_strips ? 12 : 4, long_strips ? 120 : 16, 3, churn), "strips.trace", {});
      const Outcome one = run(p, 1, 0, 256), ref = run(p, 1, 1, 256);
      check_same_run(one.result, ref.result);
      CHECK(one.fills == 0);  // (one thread: no batches)
      for (int threads : {2, 3}) {
        INFO("threads ", threads);
        const Outcome many = run(p, threads, 0, 256);
        check_same_run(many.result, one.result);
        CHECK(many.splits > 0);
        fills += many.fills;
        pooled += many.pooled;
        if (!long_strips) CHECK(many.pooled == 0);  // (too few vertices a flush)
        settled += many.settled;
        CHECK(many.replays > 0);
        // With the batches never split, the fills are made on the caller.
        const Outcome whole = run(p, threads, 0, 1 << 30);
        check_same_run(whole.result, one.result);
        CHECK(whole.splits == 0);
        CHECK(whole.pooled == 0);
      }
    }
  CHECK(fills > 0);
  CHECK(pooled > 0);
  CHECK(settled > 0);  // (a run recorded again while fills were pending)
}

TEST_CASE("window fills: the terrain's replayed passes leave their window vertices to the flush") {
  // kautz-imaging-aa's terrain: the first pass records the strips' runs, the
  // later passes replay them; each replayed strip's glEnd takes its triangles
  // from the memo and leaves its vertices to the flush. The buffers at 1 and 2
  // threads are compared by test_fast_threads.cpp's terrain test; here the
  // fills are counted.
  LoadOptions lo;
  lo.sets = {{"scene", "1"}, {"tw", "256"}, {"th", "192"}, {"rays", "16"}};
  const Program prog = load_trace_file(std::string(FFSIM_SOURCE_DIR) + "/traces/kautz-imaging-aa.trace", lo);
  const Outcome one = run(prog, 1, 0, Context(prog.profile, 8, 8).split_fragments());
  const Outcome two = run(prog, 2, 0, Context(prog.profile, 8, 8).split_fragments());
  check_same_run(two.result, one.result);
  CHECK(one.fills == 0);
  MESSAGE("terrain 256x192: ", two.fills, " glEnds left their window vertices to the flush");
  CHECK(two.fills > 0);
}

TEST_CASE("window fills: a recorded run's glEnd leaves its window attributes to the flush, on any thread count") {
  // One pass only: every strip's run is called and recorded (no replay), and
  // its glEnd, whose vertices are all the run's, reads them from the record as
  // a replay's would (Context::vertex_run_record): with threads, its window
  // attributes are filled by the batch's flush. The buffers must equal one
  // thread's and the per-fragment path's.
  std::uint64_t fills = 0;
  for (const char* profile : {"geforce256", "rgba12"})
    for (std::uint32_t seed = 1; seed <= 4; ++seed) {
      INFO("profile ", profile, " seed ", seed);
      const Program p = load_trace_text(strips_trace(profile, seed, 12, 120, 1, false), "strips.trace", {});
      const Outcome one = run(p, 1, 0, 256), ref = run(p, 1, 1, 256);
      check_same_run(one.result, ref.result);
      CHECK(one.fills == 0);
      CHECK(one.replays == 0);
      for (int threads : {2, 3}) {
        INFO("threads ", threads);
        const Outcome many = run(p, threads, 0, 256);
        check_same_run(many.result, one.result);
        CHECK(many.replays == 0);
        CHECK(many.recordings > 0);
        fills += many.fills;
      }
    }
  CHECK(fills > 0);
}

namespace {

// Strips of 14 vertices, each in its own batch entry when `k` differs, drawn
// as a recorded run (`id`: the run's name; 0: plain calls, no run) at about
// (10, 10 + k / 2^20) of a 96x64 window (a few fragments each).
void tiny_strip(Context& c, std::uint64_t id, std::uint64_t k) {
  const VertexRunUsage usage{texcoord_bit(0), 0, true};  // unit 0's coordinates written before any vertex reads them
  c.begin(gl::TRIANGLE_STRIP);
  const bool run = id != 0 && !c.vertex_run_replay(id, usage);  // (never recorded: called, then recorded)
  for (int i = 0; i < 14; ++i) {
    c.texCoord2(i / 13.0, i % 2);
    c.vertex3(10 + 0.5 * i, 10 + (i % 2) * 1.5 + static_cast<double>(k) * 0x1p-20, 0);
  }
  if (run) c.vertex_run_record(id);
  c.end();
}

}  // namespace

TEST_CASE("window fills: the memos emptied at their bound while fills are pending make the fills first") {
  // With threads, a glEnd of a recorded run leaves its window attributes to the
  // batch's flush, reading its record and its geometry memo entry then. A memo
  // insertion that would drop either (each memo empties itself at its vertex
  // bound) makes the pending fills first (VertexRunMemo/GeometryMemo::
  // insert_drops); others leave them pending. Phase 1: strips of new positions,
  // every other one a recorded run: the geometry memo reaches its bound first.
  // Phase 2: recorded runs of one strip's positions (the geometry memo's entry
  // found): the vertex-run memo reaches its bound. Each phase must settle fills,
  // and the buffers must equal one thread's.
  static_assert(GeometryMemo::kMaxVertices == VertexRunMemo::kMaxVertices);
  const std::uint64_t strips = GeometryMemo::kMaxVertices / 14 + 100;
  const Profile prof = profile_named("geforce256");
  Context one(prof, 96, 64), two(prof, 96, 64);
  two.set_threads(2);
  two.set_split_fragments(1);  // (every batch in bands)
  two.set_defer_draws(true);
  std::uint64_t settled_after_phase1 = 0;
  for (Context* c : {&one, &two}) {
    c->matrixMode(gl::PROJECTION);
    c->ortho(0, 96, 0, 64, -1, 1);
    c->matrixMode(gl::MODELVIEW);
    std::vector<std::uint8_t> texels(4 * 2 * 4);
    for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = static_cast<std::uint8_t>(37 * i + 5);
    c->bindTexture(gl::TEXTURE_2D, 1);
    c->texImage2D(gl::TEXTURE_2D, 0, gl::RGBA8, 4, 2, 0, gl::RGBA, gl::UNSIGNED_BYTE, texels.data());
    c->texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MIN_FILTER, gl::LINEAR);
    c->enable(gl::TEXTURE_2D);
    c->enable(gl::BLEND);
    c->blendFunc(gl::ONE, gl::ONE);
    c->color4(0.001, 0.002, 0.003, 0.004);
    for (std::uint64_t k = 0; k < strips; ++k) tiny_strip(*c, k % 2 ? 0 : (1ull << 40) + k, k);
    if (c == &two) {
      c->flush_deferred();
      settled_after_phase1 = c->settled_window_fills();
    }
    for (std::uint64_t k = 0; k < strips; ++k) tiny_strip(*c, (1ull << 41) + k, 0);
    c->flush_deferred();
  }
  CHECK(two.deferred_window_fills() > 0);
  CHECK(settled_after_phase1 > 0);                               // the geometry memo's bound
  CHECK(two.settled_window_fills() > settled_after_phase1);     // the vertex-run memo's
  CHECK(two.vertex_run_memo().size() < strips);                 // (it emptied itself)
  CHECK(buffer_hash(two.framebuffer(), BufferKind::Color) == buffer_hash(one.framebuffer(), BufferKind::Color));
  CHECK(buffer_hash(two.framebuffer(), BufferKind::Alpha) == buffer_hash(one.framebuffer(), BufferKind::Alpha));
}

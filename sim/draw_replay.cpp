// The raster cache in the draw path (sim/raster_cache.h, docs/performance.md 13.2):
// a sequence of triangles is rasterized and recorded the first time, replayed
// when the same key comes again.
//
// What raster_triangle's span path does with a sequence (sim/draw.cpp: runs
// gathered into groups, a group closed when a run meets one of its pixels, at
// kGroupFragments fragments, when coords_reuse_mask changes, or before a long
// run) depends only on the triangles' snapped positions, which of them have
// equal coords_reuse_masks, the rows and the window, and starts from an empty
// group. A group's depth codes depend on its runs and the vertices' depth codes,
// its pixel list on its runs and the window width. All of these are the key, so
// the replay's groups, long runs, depth codes and pixel lists are the rasterizer's.
#include <algorithm>
#include <array>
#include <iterator>
#include <memory>
#include <utility>

#include "sim/context.h"
#include "sim/draw_span.h"

namespace ffsim {

bool Context::raster_cache_applies(const DrawSetup& ds) const {
  return raster_cache_on_ && fast_paths_ && ds.direct_writes &&  // (threads: ds.bands implies it)
         span_path_supported(*ds.st, *ds.plan, ds.shade);
}

std::vector<std::int64_t> Context::raster_key(const DrawSetup& ds, const TriangleRef* tris, std::size_t count,
                                              std::initializer_list<std::int64_t> rows,
                                              std::span<const std::uint64_t> geometry) const {
  const bool named = !geometry.empty();
  std::vector<std::int64_t> key;
  key.reserve(17 + rows.size() + geometry.size() + (named ? 0 : 9 * count));
  // The first word tells the two forms apart: 0, every triangle's positions and
  // depth codes; 1, geometry memo serials, which name them (a serial is never
  // reused, and its entry's content never changes; the triangles are the
  // glEnd's, made from its vertices by its mode, which the entry's key holds, and
  // a batch leaves out those missing the window, which the key's window fixes).
  key.insert(key.end(), {named ? 1 : 0, profile_.subpixel_bits, fb_.width(), fb_.height(), ds.vx, ds.vy, ds.cx0,
                         ds.cx1, ds.cy0, ds.cy1, ds.has_depth ? 1 : 0, static_cast<std::int64_t>(count)});
  key.insert(key.end(), rows);
  if (named) {
    key.push_back(static_cast<std::int64_t>(geometry.size()));
    for (const std::uint64_t w : geometry) key.push_back(static_cast<std::int64_t>(w));
  } else {  // (9 words a triangle: count, in the header, says how many)
    for (std::size_t i = 0; i < count; ++i)
      for (const WindowVertex* v : tris[i]) key.insert(key.end(), {v->p.x, v->p.y, ds.has_depth ? v->depth : 0});
  }
  // coords_reuse_mask matters to the grouping only through which triangles'
  // masks are equal (a group closes when a triangle's differs from the group's):
  // each mask is keyed as the index of its first appearance in the sequence, so
  // passes sampling other units of the same mesh share the recording. The labels
  // close the key as runs, (label, length) pairs, each run as long as it goes:
  // the same label sequences give the same pairs, and other ones other pairs.
  static_assert(kShadeUnits <= 5);
  // Fewer than two sampled units: every mask is 0 (nothing to share), one run of
  // label 0.
  if (!coords_may_be_reused(*ds.plan)) {  // (tris is then read only without `geometry`)
    if (count > 0) key.insert(key.end(), {0, static_cast<std::int64_t>(count)});
    return key;
  }
  std::array<int, 32> first_seen;  // by mask; -1: not yet
  first_seen.fill(-1);
  int distinct = 0;
  std::int64_t run_label = -1, run_length = 0;
  for (std::size_t i = 0; i < count; ++i) {
    int& label = first_seen[coords_reuse_mask(*ds.plan, tris[i]) & 31u];
    if (label < 0) label = distinct++;
    if (label != run_label) {
      if (run_length > 0) key.insert(key.end(), {run_label, run_length});
      run_label = label;
      run_length = 0;
    }
    ++run_length;
  }
  if (run_length > 0) key.insert(key.end(), {run_label, run_length});
  return key;
}

void Context::draw_sequence(const DrawSetup& ds, const std::vector<TriangleRef>& all, FragmentSpan& span,
                            std::uint64_t geometry) {
  // Triangles that make no fragment (triangle_never_covers, e.g. a mesh scaled to
  // a point) are left out before the key, the recording and the walk.
  auto never = [](const TriangleRef& t) { return triangle_never_covers(t[0]->p, t[1]->p, t[2]->p); };
  const std::vector<TriangleRef>* kept = &all;
  if (std::any_of(all.begin(), all.end(), never)) {
    covering_scratch_.clear();
    std::copy_if(all.begin(), all.end(), std::back_inserter(covering_scratch_), [&](const TriangleRef& t) { return !never(t); });
    kept = &covering_scratch_;
  }
  const std::vector<TriangleRef>& tris = *kept;
  if (tris.empty()) return;
  if (!raster_cache_applies(ds)) {
    for (const TriangleRef& t : tris) raster_triangle(ds, t, ds.cy0, ds.cy1, span, -1);
    shade_group(ds, span, -1);
    return;
  }
  std::vector<std::int64_t> key = raster_key(ds, tris.data(), tris.size(), {ds.cy0, ds.cy1},
                                             geometry ? std::span<const std::uint64_t>(&geometry, 1)
                                                      : std::span<const std::uint64_t>());
  if (const std::vector<RasterRecording>* rec = raster_cache_.find(key)) {
    replay_sequence(ds, tris, rec->front(), span, -1);
    return;
  }
  std::vector<RasterRecording> rec(1);
  record_sequence(ds, tris, ds.cy0, ds.cy1, span, -1, rec.front());
  raster_cache_.insert(std::move(key), std::move(rec));
}

RecordedGroup* Context::record_group(SpanScratch& sc) {
  RasterRecording& r = *sc.recording;
  r.steps.push_back({false, r.groups.size()});
  RecordedGroup& g = r.groups.emplace_back();
  RecordingArena& a = r.arena;
  g.weight = a.copy(sc.weight.data(), sc.weight.size());
  g.run_y = a.copy(sc.run_y.data(), sc.run_y.size());
  g.run_x0 = a.copy(sc.run_x0.data(), sc.run_x0.size());
  g.run_length = a.copy(sc.run_length.data(), sc.run_length.size());
  g.fragments = sc.group_fragments;
  g.triangles = a.make<RecordedTriangle>(sc.triangles.size());
  for (std::size_t i = 0; i < sc.triangles.size(); ++i) {
    const GroupTriangle& t = sc.triangles[i];
    std::construct_at(&g.triangles[i], RecordedTriangle{sc.triangle_index[i], t.cov, t.run_begin, t.fragment_begin});
  }
  return &g;
}

void Context::record_sequence(const DrawSetup& ds, const std::vector<TriangleRef>& tris, int y0, int y1,
                              FragmentSpan& span, int band, RasterRecording& rec) {
  SpanScratch& sc = scratch_of(band);
  shade_group(ds, span, band);  // (none open: a sequence starts with an empty group)
  struct Stop {  // however this ends (the fragment operations may throw)
    SpanScratch& sc;
    ~Stop() { sc.recording = nullptr; }
  } stop{sc};
  sc.recording = &rec;
  const std::uint64_t joined = sc.joined, met = sc.met;
  for (std::size_t i = 0; i < tris.size(); ++i) {
    sc.sequence_index = static_cast<int>(i);
    raster_triangle(ds, tris[i], y0, y1, span, band);
  }
  shade_group(ds, span, band);
  rec.joined = sc.joined - joined;
  rec.met = sc.met - met;
}

void Context::replay_sequence(const DrawSetup& ds, const std::vector<TriangleRef>& tris, const RasterRecording& rec,
                              FragmentSpan& span, int band) {
  SpanScratch& sc = scratch_of(band);
  shade_group(ds, span, band);  // (none open)
  for (const RasterRecording::Step& step : rec.steps) {
    if (step.long_run) {
      const RecordedLongRun& l = rec.long_runs[step.index];
      shade_long_run(ds, tris[static_cast<std::size_t>(l.index)], l.cov, l.y, l.x0, l.count, l.weight, span, band);
      continue;
    }
    const RecordedGroup& g = rec.groups[step.index];
    sc.triangles.clear();
    for (const RecordedTriangle& t : g.triangles)
      sc.triangles.push_back({tris[static_cast<std::size_t>(t.index)], t.cov, t.run_begin, t.fragment_begin});
    sc.coords_reuse = coords_reuse_mask(*ds.plan, sc.triangles.front().tv);  // (this pass's; the same pattern)
    // The recorded arrays in place (no copy); depth codes and pixel list when
    // recorded (the first drawing had a depth buffer, or wrote by list).
    GroupRuns runs{g.weight.data(), g.run_y.data(), g.run_x0.data(), g.run_length.data(),
                   static_cast<int>(g.run_length.size()), g.fragments};
    runs.depth = g.depth.empty() ? nullptr : g.depth.data();
    runs.pixel = g.pixel.empty() ? nullptr : g.pixel.data();
    runs.from = &g;
    runs.from_recording = &rec;
    shade_group_runs(ds, span, band, runs, nullptr);
  }
  sc.joined += rec.joined;
  sc.met += rec.met;
}

}  // namespace ffsim

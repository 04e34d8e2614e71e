// Drawing a polygon (GL121 §2.11-2.13, §3.5, §3.8-3.9): clipping to the view
// volume, the viewport and depth-range transformation, snapping to the
// sub-pixel grid, rasterization with the fill rule, attribute interpolation,
// then per fragment: texture fetch, texture environments, colour sum; finished
// spans go to write_fragments (the per-fragment operations).
//
// Interpolation (docs/numerics.md §8.2): with barycentric numerators w_k (exact
// integers from the rasterizer, sum A),
//   colour codes  k = floor((2·Σ w_k·k_k + A) / 2A)   (exact, round half up once),
//   depth codes   z = floor((2·Σ w_k·z_k + A) / 2A),
//   texture coordinates perspective-correct in binary64:
//     s = Σ w_k·s_k/w_clip_k / Σ w_k·q_k/w_clip_k  (then s/q is what is sampled).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <span>
#include <utility>

#include "pipeline/combiners/register_combiners.h"
#include "pipeline/fragment/constant_source.h"
#include "pipeline/number/snorm.h"
#include "pipeline/number/unorm.h"
#include "sim/probe.h"
#include "pipeline/raster/triangle.h"
#include "sim/context.h"
#include "sim/draw_span.h"
#include "sim/worker_pool.h"

namespace ffsim {

namespace {

double to_color_value(double v, Arithmetic a) {
  return a == Arithmetic::Float32 ? static_cast<double>(static_cast<float>(v)) : v;
}

// Whether λ can change the result: only when minification and magnification
// differ (a mipmap minification filter, or different NEAREST/LINEAR choices).
bool needs_lod(const TextureParams& p) { return is_mipmap_filter(p.min_filter) || p.min_filter != p.mag_filter; }

}  // namespace

ShadingState Context::shading_state() {
  ShadingState st;
  st.color = ColorFormat::from_profile(profile_);
  st.sample = SampleFormat::from_profile(profile_);
  st.color_sum = color_sum_;
  st.unit_count = profile_.texture_units;
  for (int u = 0; u < profile_.texture_units; ++u) {
    const TextureUnitBinding& b = units_[u];
    ShadeUnit& su = st.units[u];
    su.env = texenv_[u];
    // §3.8.13: TEXTURE_2D takes precedence over TEXTURE_1D; an incomplete texture
    // disables the unit.
    const GLenum target = b.enabled_2d ? gl::TEXTURE_2D : (b.enabled_1d ? gl::TEXTURE_1D : 0);
    if (target == 0) continue;
    const TextureObject& tex = bound_texture(u, target);
    su.dims = target == gl::TEXTURE_1D ? 1 : 2;
    if (texture_complete(tex, su.dims, st.sample)) su.texture = &tex;
  }
  return st;
}

ShadingPlan Context::shading_plan(const ShadingState& st) {
  if (combiners_.enabled) {
    // RC §3.8.11: combiners replace the environments, colour sum and fog; texture
    // fetching still happens, for the units the combiners read (all enabled
    // units in the full path). A disabled unit's register is undefined -> 0.
    ShadingPlan p;
    const combiners::CombinerPlan& cp = combiner_plan();
    for (int u = 0; u < st.unit_count; ++u)
      p.sample[u] = st.units[u].texture != nullptr && (full_shading_ || cp.texture_needed[u]);
    return p;
  }
  return full_shading_ ? full_shading_plan(st) : plan_shading(st);
}

std::string Context::explain_shading() {
  const ShadingState st = shading_state();
  return ffsim::explain_shading(st, shading_plan(st));
}

Rgba Context::shade_fragment(const ShadingState& st, const ShadingPlan& plan, const Rgba& primary,
                             const Rgba& secondary, const UnitTexCoords& tc) {
  UnitTexels texels{};
  fetch_texels(st, plan, tc, texels);  // step 1
  if (shade_probe_)
    for (int u = 0; u < kShadeUnits; ++u) {
      if (!plan.sample[u]) continue;
      const Texel& t = texels[u];
      std::array<std::uint16_t, 4> k{};
      for (int c = 0; c < 4; ++c) k[c] = static_cast<std::uint16_t>(t.code[c]);
      *shade_probe_ += "\n    unit " + std::to_string(u) + ": s,t = " + std::to_string(tc[u].s) + ", " + std::to_string(tc[u].t) +
                       " lambda " + std::to_string(tc[u].lambda) + ", filtered texel (register layout) " +
                       (st.color.fixed() ? describe_codes(k.data(), t.bits) : describe_values(t.value.data()));
      // The filter footprint at the base level with the magnification filter
      // (the level and filter a magnified or pixel-rectangle fragment uses).
      const TextureObject& tex = *st.units[u].texture;
      *shade_probe_ += "\n      footprint: " + describe_footprint(tex, tex.params.base_level, st.units[u].dims,
                                                                 tex.params.mag_filter, tc[u].s, tc[u].t, st.sample);
    }
  if (!combiners_.enabled) return texture_environments(st, plan, primary, secondary, texels);  // step 2
  return combine_fragment(st, plan, primary, secondary, texels);
}

static std::string describe_rgba(const Rgba& c, const ColorFormat& fmt) {
  if (!fmt.fixed()) return describe_values(c.value.data());
  std::array<std::uint16_t, 4> k{};
  for (int i = 0; i < 4; ++i) k[i] = static_cast<std::uint16_t>(c.code[i]);
  return describe_codes(k.data(), fmt.bits);
}

void Context::probe_registers(const combiners::RegisterTrace& trace) {
  if (!shade_probe_) return;
  // The registers general stages write (spare0, spare1) and the colours, after
  // each stage, as real values.
  for (std::size_t k = 0; k < trace.after_stage.size(); ++k)
    for (int r : {combiners::kSpare0, combiners::kSpare1, combiners::kPrimaryColor, combiners::kSecondaryColor}) {
      const auto& v = trace.after_stage[k][static_cast<std::size_t>(r)];
      std::string codes;
      if (profile_.is_fixed()) {  // the register codes c (value c/M), recovered exactly from c/M
        const double M = snorm_max(profile_.combiner_bits);
        codes = "codes (";
        for (int c = 0; c < 4; ++c) codes += (c ? ", " : "") + std::to_string(std::lround(v[static_cast<std::size_t>(c)] * M));
        codes += ")/" + std::to_string(static_cast<int>(M)) + " = ";
      }
      *shade_probe_ += "\n    after stage " + std::to_string(k) + ": " + combiners::register_short_name(r) + " = " + codes +
                       describe_values(v.data());
    }
}

Rgba Context::combine_fragment(const ShadingState& st, const ShadingPlan& plan, const Rgba& primary,
                               const Rgba& secondary, const UnitTexels& texels) {
  // Register combiners in place of step 2, one fragment. Texture registers take
  // the filtered texel in the register layout of RC Table NV_register_combiners.2
  // (Texel already holds it); units not sampled are absent (undefined -> 0).
  // Fog is not modelled: FOG.rgb = 0 and FOG.a = 1 (fog disabled, RC Table .1).
  const combiners::CombinerPlan& cp = combiner_plan();
  const std::array<double, 4> fog_color{0, 0, 0, 0};
  Rgba out;
  if (st.color.fixed()) {
    std::array<std::uint16_t, 4> prim{}, sec{};
    std::array<std::array<std::uint16_t, 4>, kShadeUnits> tex{};
    combiners::CombinerInputsFixed in;
    in.count = 1;
    for (int c = 0; c < 4; ++c) {
      prim[c] = static_cast<std::uint16_t>(primary.code[c]);
      sec[c] = static_cast<std::uint16_t>(secondary.code[c]);
    }
    in.primary = prim.data();
    in.secondary = sec.data();
    for (int u = 0; u < kShadeUnits; ++u) {
      if (!plan.sample[u]) continue;
      const Texel& t = texels[u];
      for (int c = 0; c < 4; ++c)  // sized formats may differ from the profile's texture width
        tex[u][c] = static_cast<std::uint16_t>(t.bits == profile_.texture_bits ? t.code[c]
                                                   : unorm_convert(t.code[c], t.bits, profile_.texture_bits));
      in.texture[u] = tex[u].data();
    }
    std::array<std::uint16_t, 4> o{};
    combiners::RegisterTrace trace;
    combiners::shade_span(cp, in, fog_color, o.data(), shade_probe_ ? &trace : nullptr);
    probe_registers(trace);
    for (int c = 0; c < 4; ++c) out.code[c] = o[c];
  } else {
    std::array<std::array<double, 4>, kShadeUnits> tex{};
    combiners::CombinerInputsFloat in;
    in.count = 1;
    in.primary = primary.value.data();
    in.secondary = secondary.value.data();
    for (int u = 0; u < kShadeUnits; ++u) {
      if (!plan.sample[u]) continue;
      tex[u] = texels[u].value;
      in.texture[u] = tex[u].data();
    }
    std::array<double, 4> o{};
    combiners::RegisterTrace trace;
    combiners::shade_span(cp, in, fog_color, o.data(), shade_probe_ ? &trace : nullptr);
    probe_registers(trace);
    out.value = o;
  }
  return out;
}

Context::DrawSetup Context::draw_setup(const ShadingState& st, const ShadingPlan& plan) {
  DrawSetup ds;
  ds.st = &st;
  ds.plan = &plan;
  ds.flat = shade_model_ == gl::FLAT;
  ds.shade = shading_active(plan);
  ds.has_depth = fb_.has_depth();
  ds.vx = viewport_[0];
  ds.vy = viewport_[1];
  ds.hw = viewport_[2] / 2.0;
  ds.hh = viewport_[3] / 2.0;
  ds.area_scale = std::ldexp(0.5, -2 * profile_.subpixel_bits);  // (once a glEnd, not a library call a triangle)
  // Window bounds relative to the viewport corner (pixel ownership, §4.1.1), in
  // 64 bits: the viewport corner may be any int.
  auto rel = [](int a, int origin) {
    return static_cast<int>(std::clamp<std::int64_t>(std::int64_t{a} - origin, -(std::int64_t{1} << 30), std::int64_t{1} << 30));
  };
  ds.cx0 = rel(0, ds.vx);
  ds.cy0 = rel(0, ds.vy);
  ds.cx1 = rel(fb_.width(), ds.vx);
  ds.cy1 = rel(fb_.height(), ds.vy);
  // Threads (docs/performance.md): the polygons of a glEnd are rasterized in bands
  // of rows shaded concurrently, each band walking every triangle in order. Rows
  // are disjoint pixels and every per-fragment operation reads and writes only
  // its own pixel, so each pixel sees the same fragments in the same order as
  // with one thread. Shared state is made ready here (fragment plan, combiner
  // plan), then only read; the probe forces one thread (it records in order).
  ds.bands = threads_ > 1 && !probe_.enabled() &&
             std::int64_t{ds.cx1 - ds.cx0} * (ds.cy1 - ds.cy0) >= split_fragments_;
  // No span-path group is open between glEnds (each ends with shade_group, or
  // its guard on an exception); emptied again in case one was left.
  clear_group(span_scratch_);
  for (SpanScratch& b : band_scratch_) clear_group(b);
  // Without the probe, spans go straight to run_fragment_plan with the plan and
  // buffers looked up once here (no state changes inside glBegin/glEnd).
  ds.direct_writes = !probe_.enabled();
  if (ds.direct_writes) {
    update_fragment_plan();
    if (combiners_.enabled) combiner_plan();
    ds.buffers = fragment_buffers();  // (a depth change is reported: write_span, shade_group_runs)
  }
  if (ds.bands) ready_bands(0);
  return ds;
}

bool Context::prepare_polygon(std::vector<ClipVertex>& poly, std::size_t provoking, const DrawSetup& ds,
                              WindowVertices& out) {
  if (ds.flat) {  // §2.13.7: every vertex takes the provoking vertex's colours
    for (ClipVertex& v : poly) {
      v.color = poly[provoking].color;
      v.secondary = poly[provoking].secondary;
    }
  }
  poly = clip_polygon(std::move(poly));
  if (poly.size() < 3) return false;
  for (const ClipVertex& v : poly)
    if (!(v.position.w > 0)) return false;  // only a polygon through the eye point itself: no area

  const std::size_t base = out.size();
  out.resize(base + poly.size());
  for (std::size_t i = 0; i < poly.size(); ++i) window_vertex(poly[i], ds, out[base + i]);
  return true;
}

void Context::window_vertex(const ClipVertex& c, const DrawSetup& ds, WindowVertex& w) const {
  const double iw = 1.0 / c.position.w;
  window_position(c.position, iw, ds, w);
  window_attributes(c, iw, ds, w);
}

void Context::window_position(const glm::dvec4& clip, double iw, const DrawSetup& ds, WindowVertex& w) const {
  const int S = profile_.subpixel_bits;
  // §2.10.1 viewport transformation, relative to the viewport corner (vx, vy).
  w.p.x = snap_coordinate((clip.x * iw + 1) * ds.hw, S);
  w.p.y = snap_coordinate((clip.y * iw + 1) * ds.hh, S);
  const double zw = depth_near_ + (depth_far_ - depth_near_) * ((clip.z * iw + 1) / 2);
  w.depth = ds.has_depth ? unorm_from_double(zw, fb_.format().depth_bits) : 0;
}

void Context::window_attributes(const ClipVertex& c, double iw, const DrawSetup& ds, WindowVertex& w) const {
  window_attributes_n(&c, &iw, 1, ds, &w);
}

void Context::window_attributes_n(const ClipVertex* c, const double* iw, std::size_t n, const DrawSetup& ds,
                                  WindowVertex* w, const VertexRunFill* fill, ColorMemo* memo) const {
  // Vertex colours into the fragment colour format (§1.2 codes, or binary32/64).
  // A colour equal bit for bit to the previous vertex's (in the same format)
  // converts to the same codes: with the fast paths, the last conversion of each
  // is kept (a memo of another format is dropped, once for the n vertices);
  // without, every vertex converts (the reference the tests compare with).
  const ColorFormat& f = ds.st->color;
  ColorMemo* const kept = memo ? memo : color_memo_.data();
  for (ColorMemo& m : std::span<ColorMemo>(kept, 2))
    if (!fast_paths_ || m.format.arith != f.arith || m.format.bits != f.bits) m.valid = false;
  auto convert = [&](const std::array<double, 4>& v, ColorMemo& m) -> const Rgba& {
    if (!m.valid || std::memcmp(m.in.data(), v.data(), sizeof(double) * 4) != 0)
      m = {fast_paths_, f, v, rgba_from_values(v, f)};
    return m.out;
  };
  // Each attribute's source: the vertex's own, or (fill) one value for every vertex.
  const std::array<double, 4>* color = fill && !(fill->written & kAttribColor) ? &fill->color : nullptr;
  const std::array<double, 4>* secondary = fill && !(fill->written & kAttribSecondary) ? &fill->secondary : nullptr;
  // A filled colour is one value for all n vertices: converted once (the memo
  // would return the same codes for each).
  const Rgba* const color_once = color ? &convert(*color, kept[0]) : nullptr;
  const Rgba* const secondary_once = secondary ? &convert(*secondary, kept[1]) : nullptr;
  // s/w, t/w, q/w only for the units the plan samples: every reader of tcw reads
  // a sampled unit's (texture_coordinates, coords_reuse_mask, the recorded
  // groups, the per-fragment path), and a glEnd's window vertices are drawn
  // under its own plan; the others are left unwritten.
  std::array<int, kMaxTextureUnits> units{};
  int unit_count = 0;
  std::array<const glm::dvec4*, kMaxTextureUnits> texcoord{};
  for (int u = 0; u < kMaxTextureUnits; ++u) {
    if (!ds.plan->sample[static_cast<std::size_t>(u)]) continue;
    units[static_cast<std::size_t>(unit_count++)] = u;
    if (fill && fill->fills_texcoord(u, profile_.texture_units)) texcoord[u] = &fill->texcoord[static_cast<std::size_t>(u)];
  }
  for (std::size_t i = 0; i < n; ++i) {
    const ClipVertex& v = c[i];
    const Rgba &pc = color_once ? *color_once : convert(v.color, kept[0]),
               &sc = secondary_once ? *secondary_once : convert(v.secondary, kept[1]);
    WindowVertex& o = w[i];
    o.color_code = pc.code;
    o.secondary_code = sc.code;
    o.color = pc.value;
    o.secondary = sc.value;
    for (int j = 0; j < unit_count; ++j) {
      const int u = units[static_cast<std::size_t>(j)];
      const glm::dvec4& t = texcoord[u] ? *texcoord[u] : v.texcoord[u];
      o.tcw[u] = {t.x * iw[i], t.y * iw[i], t.w * iw[i]};
    }
  }
}

void Context::memo_window_vertices(const GeometryEntry& geo, const ClipVertex* c, const VertexRunFill* fill,
                                   std::size_t i0, std::size_t i1, const DrawSetup& ds, WindowVertex* w,
                                   ColorMemo* memo) const {
  for (std::size_t i = i0; i < i1; ++i) {
    w[i].p = geo.p[i];
    w[i].depth = ds.has_depth ? geo.depth[i] : 0;
  }
  window_attributes_n(c + i0, geo.iw.data() + i0, i1 - i0, ds, w + i0, fill, memo);
}

void Context::leave_window_fill(const WindowFill& f) {
  window_fills_.push_back(f);
  ++deferred_window_fills_;
}

void Context::run_window_fills(const DrawSetup& ds, bool split) {
  if (window_fills_.empty()) return;
  struct Done {  // (emptied however this ends)
    std::vector<WindowFill>& f;
    ~Done() { f.clear(); }
  } done{window_fills_};
  std::size_t total = 0;
  for (const WindowFill& f : window_fills_) total += f.n;
  // The vertices [v0, v1) of the fills laid end to end, each a pure function
  // of its own inputs (the colour memo only caches): any cut gives the same
  // bits. One task per thread; a few thousand vertices are not worth a run.
  auto fill_range = [&](std::size_t v0, std::size_t v1, ColorMemo* memo) {
    std::size_t at = 0;
    for (const WindowFill& f : window_fills_) {
      const std::size_t i0 = std::max(v0, at) - at, i1 = std::min(v1, at + f.n);
      if (i1 > at && i0 < f.n)
        memo_window_vertices(*f.geo, f.fill.pending->vertices.data(), &f.fill, i0, i1 - at, ds,
                             batch_vertices_.data() + f.base, memo);
      at += f.n;
      if (at >= v1) break;
    }
  };
  if (!split || threads_ < 2 || total < kSplitWindowFill) {
    fill_range(0, total, nullptr);
    return;
  }
  ++split_window_fills_;
  const int tasks = threads_;
  run_split(tasks, [&](int k) {
    std::array<ColorMemo, 2> memo{};  // (this task's own: color_memo_ is the caller's)
    fill_range(total * static_cast<std::size_t>(k) / static_cast<std::size_t>(tasks),
               total * static_cast<std::size_t>(k + 1) / static_cast<std::size_t>(tasks), memo.data());
  });
}

void Context::settle_window_fills() {
  if (window_fills_.empty()) return;
  if (!batch_pending_) {  // (a deferred batch that got no triangle: nothing reads them; its next glEnd clears it)
    window_fills_.clear();
    return;
  }
  ++settled_window_fills_;
  run_window_fills(deferred_ds_, false);
}

void Context::count_written(int band, std::uint64_t fragments, std::uint64_t fast_runs) {
  if (band < 0) {
    fragments_written_ += fragments;
    fast_runs_ += fast_runs;
  } else {  // this band's share, summed by flush_batch
    BandCounts& k = band_counts_[static_cast<std::size_t>(band)];
    k.fragments += fragments;
    k.fast_runs += fast_runs;
  }
}

void Context::write_span(const DrawSetup& ds, FragmentSpan& span, int band) {
  if (band < 0 && !ds.direct_writes) {
    write_fragments(span);
  } else {  // write_fragments without the plan update and the probe (done, off), here or on a worker
    count_written(band, static_cast<std::uint64_t>(span.count), 0);
    if (run_fragment_plan(*fragment_current_plan_, fragment_current_constants_, span, ds.buffers, fb_.width()))
      fb_.depth_changed();
  }
}

namespace {

// A run's framebuffer lines (colour, depth) are requested before it is shaded
// and arrive meanwhile: the fragment operations waited on these loads.
void prefetch_run(const FragmentBuffers& b, int width, int height, int y, int x0, int len) {
  if (!b.codes || y < 0 || y >= height || x0 < 0 || x0 + len > width) return;
  const std::size_t p0 = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x0);
  const std::size_t p1 = p0 + static_cast<std::size_t>(len) - 1;
  for (std::size_t p = p0; p < p1 + 8; p += 8) __builtin_prefetch(b.codes + 4 * std::min(p, p1), 1);
  if (b.depth)
    for (std::size_t p = p0; p < p1 + 16; p += 16) __builtin_prefetch(b.depth + std::min(p, p1), 1);
}

// The colour codes every fragment of a group gets when nothing shades them
// (interpolate_colors, sim/draw_span.cpp): true when each triangle's primary
// codes are constant (flat shading: the provoking vertex's, tv[0]; else three
// equal codes, whose interpolation is that code) and the same for all.
bool group_source(bool flat, const std::vector<GroupTriangle>& tris, std::array<std::uint32_t, 4>& out) {
  if (tris.empty()) return false;
  out = tris.front().tv[0]->color_code;
  for (const GroupTriangle& t : tris)
    if (t.tv[0]->color_code != out || (!flat && (t.tv[1]->color_code != out || t.tv[2]->color_code != out)))
      return false;
  return true;
}

// The bits of the pixels [x0, x0 + n) of a row (n < 64: two words at most): the
// word index and the masks of that word and the next.
struct RowBits {
  std::size_t word;
  std::uint64_t lo, hi;
};
RowBits row_bits(std::size_t row_word, int x0, int n) {
  const int b = x0 & 63;
  const std::uint64_t run = (std::uint64_t{1} << n) - 1;  // n <= 63
  return {row_word + static_cast<std::size_t>(x0 >> 6), run << b, b + n > 64 ? run >> (64 - b) : 0};
}

}  // namespace

Context::SpanGroupStats Context::span_group_stats() const {
  SpanGroupStats g;
  auto add = [&](const SpanScratch& sc) {
    g.joined += sc.joined;
    g.met += sc.met;
    g.coords_recorded += sc.coords_recorded;
    g.depth_reused += sc.depth_reused;
    g.unwritten += sc.unwritten;
  };
  add(span_scratch_);
  for (const SpanScratch& b : band_scratch_) add(b);
  return g;
}

void Context::clear_group(SpanScratch& sc) {
  if (sc.marked)  // the group's bits back to 0, run by run
    for (std::size_t r = 0; r < sc.run_length.size(); ++r) {
      const RowBits rb = row_bits(static_cast<std::size_t>(sc.run_y[r]) * sc.taken_words, sc.run_x0[r], sc.run_length[r]);
      sc.taken[rb.word] &= ~rb.lo;
      if (rb.hi) sc.taken[rb.word + 1] &= ~rb.hi;
    }
  sc.marked = false;
  sc.coords_from = nullptr;
  sc.coords_to = nullptr;
  sc.triangle_index.clear();
  sc.group_fragments = 0;
  sc.weight.clear();
  sc.run_y.clear();
  sc.run_x0.clear();
  sc.run_length.clear();
  sc.triangles.clear();
}

void Context::shade_group(const DrawSetup& ds, FragmentSpan& span, int band) {
  SpanScratch& sc = scratch_of(band);
  if (sc.run_length.empty()) return;  // (no runs: no triangles, no bits set)
  GroupRuns g{sc.weight.data(), sc.run_y.data(), sc.run_x0.data(), sc.run_length.data(),
              static_cast<int>(sc.run_length.size()), sc.group_fragments};
  shade_group_runs(ds, span, band, g, sc.recording ? record_group(sc) : nullptr);
}

void Context::shade_group_runs(const DrawSetup& ds, FragmentSpan& span, int band, const GroupRuns& g,
                               RecordedGroup* recorded) {
  SpanScratch& sc = scratch_of(band);
  struct Emptied {  // however this ends (the fragment operations may throw)
    Context& c;
    SpanScratch& sc;
    ~Emptied() { c.clear_group(sc); }
  } emptied{*this, sc};
  const FastRuns runs{g.weight, g.length, g.runs, g.fragments};
  const bool has_depth = ds.has_depth;
  sc.codes.resize(4 * static_cast<std::size_t>(runs.count));
  // The depth codes: a replay's, or interpolated here (straight into the
  // recording when one is made).
  const std::uint32_t* depth = has_depth ? g.depth : nullptr;
  std::uint32_t* depth_out = nullptr;
  if (has_depth && !depth) {
    if (recorded) {
      recorded->depth = sc.recording->arena.make<std::uint32_t>(static_cast<std::size_t>(runs.count));
      depth_out = recorded->depth.data();
    } else {
      sc.depth.resize(static_cast<std::size_t>(runs.count));
      depth_out = sc.depth.data();
    }
  }
  // A replay's depth comparisons (RecordedGroup::depth_test, used if the group is
  // written by list): taken when made under this depth epoch and function and
  // nothing would be stored; else made, and kept if this call stores nothing
  // (they then hold for the unchanged buffer).
  const FragmentPlanKey& key = fragment_current_plan_->key;
  ListedDepthTest dt;
  RecordedGroup::DepthComparisons* memo = nullptr;
  if (g.from && depth_test_alone(key) && g.depth == g.from->depth.data() && g.pixel == g.from->pixel.data()) {
    memo = &g.from->depth_test;
    if (memo->epoch == fb_.depth_epoch() && memo->func == key.depth_func && (!memo->would_store || !key.depth_write))
      dt.known = memo->cmp.data();
  }
  // A group that can change no buffer is neither shaded nor written, only
  // counted (docs/performance.md 34.1): nothing shades (the fragments' colour
  // is the primary colour's codes, one quadruple for the whole group), the
  // colour stage keeps every destination for that colour, no stencil
  // operation writes, and the depth test writes nothing (off, its mask off, or
  // the replay's comparisons just taken say no fragment would store). Not
  // while recording: a later replay reads what this group records.
  if (!recorded && !ds.shade && (!key.depth || !key.depth_write || dt.known) &&
      (!key.stencil || stencil_ops_kept(key))) {
    std::array<std::uint32_t, 4> source;
    if (group_source(ds.flat, sc.triangles, source) &&
        colour_stage_keeps(key, fragment_current_constants_, source)) {
      count_written(band, static_cast<std::uint64_t>(runs.count), static_cast<std::uint64_t>(runs.runs));
      ++sc.unwritten;
      return;
    }
  }
  FragmentBuffers ahead = ds.buffers;  // (the depth lines are not read with known comparisons)
  if (dt.known) ahead.depth = nullptr;
  for (int r = 0; r < runs.runs; ++r) prefetch_run(ahead, fb_.width(), fb_.height(), g.run_y[r], g.run_x0[r], runs.length[r]);
  sc.coords_from = g.from;
  sc.coords_to = recorded;
  shade_runs_fast(*ds.st, *ds.plan, sc.triangles.data(), static_cast<int>(sc.triangles.size()), runs, ds.flat, ds.shade,
                  sc.codes.data(), depth_out, sc);
  if (depth_out) depth = depth_out;
  // The fragment operations for the whole group in one call when every run
  // lies inside the write rectangle (window and scissor) and the colour is
  // codes: the group's fragments are distinct pixels (a triangle's are; a run
  // meeting a pixel of the group closes it first), so the buffers end the same
  // as with the runs one by one in order.
  const WriteRect& rect = fragment_current_constants_.rect;
  bool listed = ds.buffers.codes != nullptr;
  if (listed && runs.runs > 0) {
    // The runs' bounding box inside the rectangle: four reductions without a
    // branch per run (the compiler vectorises them), the same answer as every
    // run tested in turn.
    int y_lo = g.run_y[0], y_hi = g.run_y[0], x_lo = g.run_x0[0], x_hi = g.run_x0[0] + runs.length[0];
    for (int r = 1; r < runs.runs; ++r) {
      y_lo = std::min(y_lo, g.run_y[r]);
      y_hi = std::max(y_hi, g.run_y[r]);
      x_lo = std::min(x_lo, g.run_x0[r]);
      x_hi = std::max(x_hi, g.run_x0[r] + runs.length[r]);
    }
    listed = y_lo >= rect.y0 && y_hi < rect.y1 && x_lo >= rect.x0 && x_hi <= rect.x1;
  }
  if (listed) {
    const std::uint32_t* pixel = g.pixel;  // a replay's, or built here
    if (!pixel) {
      // Each run's pixel indices eight at a time (a run of a small triangle is a
      // few pixels): the last block may write past the run into the next run's
      // slots, which that run then overwrites; the list holds 7 slots more.
      std::uint32_t* px;  // (straight into the recording when one is made)
      if (recorded) {
        recorded->pixel = sc.recording->arena.make<std::uint32_t>(static_cast<std::size_t>(runs.count) + 7);
        px = recorded->pixel.data();
      } else {
        sc.pixel.resize(static_cast<std::size_t>(runs.count) + 7);
        px = sc.pixel.data();
      }
      const auto W = static_cast<std::uint32_t>(fb_.width());
      for (int r = 0, off = 0; r < runs.runs; off += runs.length[r], ++r) {
        const auto first = static_cast<std::uint32_t>(g.run_y[r]) * W + static_cast<std::uint32_t>(g.run_x0[r]);
        for (int i = 0; i < runs.length[r]; i += 8)
          for (int j = 0; j < 8; ++j) px[off + i + j] = first + static_cast<std::uint32_t>(i + j);
      }
      pixel = px;
    }
    count_written(band, static_cast<std::uint64_t>(runs.count), static_cast<std::uint64_t>(runs.runs));
    if (dt.known) ++sc.depth_reused;
    if (memo && !dt.known) {
      memo->epoch = 0;
      if (memo->cmp.size() != static_cast<std::size_t>(runs.count))  // (allocated by the first replay that records them)
        memo->cmp = g.from_recording->arena.make<std::uint8_t>(static_cast<std::size_t>(runs.count));
      dt.record = memo->cmp.data();
    }
    run_fragment_plan_pixels(*fragment_current_plan_, fragment_current_constants_, sc.codes.data(), depth, pixel,
                             runs.count, ds.buffers, &dt);
    if (dt.stored) fb_.depth_changed();
    if (memo && dt.recorded && !dt.stored) {
      memo->epoch = fb_.depth_epoch();
      memo->func = key.depth_func;
      memo->would_store = dt.would_store;
    }
    return;
  }
  for (int r = 0, off = 0; r < runs.runs; off += runs.length[r], ++r) {
    const auto o = static_cast<std::size_t>(off), len = static_cast<std::size_t>(runs.length[r]);
    span.y = g.run_y[r];
    span.x0 = g.run_x0[r];
    span.count = runs.length[r];
    span.codes.assign(sc.codes.begin() + static_cast<std::ptrdiff_t>(4 * o),
                      sc.codes.begin() + static_cast<std::ptrdiff_t>(4 * (o + len)));
    if (has_depth) span.depth.assign(depth + o, depth + o + len);
    count_written(band, 0, 1);
    write_span(ds, span, band);
  }
}

void Context::shade_long_run(const DrawSetup& ds, const TriangleRef& tv, const TriangleCoverage& cov, int y, int x0,
                             int n, const std::array<std::int64_t, 3>& first, FragmentSpan& span, int band) {
  span.y = y;
  span.x0 = x0;
  span.count = n;
  prefetch_run(ds.buffers, fb_.width(), fb_.height(), y, x0, n);
  span.codes.resize(4 * static_cast<std::size_t>(n));
  if (ds.has_depth) span.depth.resize(static_cast<std::size_t>(n));
  const FastRuns one{&first, &n, 1, n};
  const GroupTriangle g{tv, cov, 0, 0};
  shade_runs_fast(*ds.st, *ds.plan, &g, 1, one, ds.flat, ds.shade, span.codes.data(),
                  ds.has_depth ? span.depth.data() : nullptr, scratch_of(band));
  count_written(band, 0, 1);
  write_span(ds, span, band);
}

void Context::raster_triangle(const DrawSetup& ds, const std::array<const WindowVertex*, 3>& tv, int y0, int y1,
                              FragmentSpan& span, int band) {
  const ShadingState& st = *ds.st;
  const ShadingPlan& plan = *ds.plan;
  const Arithmetic arith = profile_.arithmetic;
  const int vx = ds.vx, vy = ds.vy;
  const bool has_depth = ds.has_depth, flat = ds.flat, shade = ds.shade;
  SpanScratch& sc = scratch_of(band);
  // `span` to the per-fragment operations; `band` >= 0: on a worker (no probe, plans ready).
  auto write = [&] { write_span(ds, span, band); };
  const bool span_path = fast_paths_ && span_path_supported(st, plan, shade);
  const std::array<SnappedVertex, 3> sv{tv[0]->p, tv[1]->p, tv[2]->p};
  if (span_path && (band >= 0 || ds.direct_writes)) {
    // The span path (no probe): runs' weights are gathered into a group and
    // shaded in one go (per-call costs paid once per group, not once per row or
    // per triangle), then go to the fragment operations. A group holds runs of
    // consecutive triangles of the glEnd (the caller ends it with shade_group)
    // as long as their pixels are distinct: a run that meets a pixel of the group
    // (a bit per pixel in sc.taken) closes the group first. It also closes at
    // kGroupFragments fragments so its arrays stay in cache, and when a triangle
    // shares texture coordinates between units differently (coords_reuse_mask).
    // A run of kLongRun fragments or more is shaded on its own, in place.
    // Without the bits (a window over kTakenWords words), a group ends with its
    // triangle.
    constexpr int kGroupFragments = 1024;
    constexpr std::size_t kTakenWords = std::size_t{1} << 17;  // 1 MiB: windows up to 8 Mpixels
    const std::size_t words = (static_cast<std::size_t>(fb_.width()) + 63) / 64;
    const bool across = words * static_cast<std::size_t>(fb_.height()) <= kTakenWords;
    if (across && (sc.taken_words != words || sc.taken.size() != words * static_cast<std::size_t>(fb_.height()))) {
      shade_group(ds, span, band);  // (none open: the window is the same for a whole glEnd)
      sc.taken.assign(words * static_cast<std::size_t>(fb_.height()), 0);
      sc.taken_words = words;
    }
    bool opened = false;  // this triangle is the group's last
    auto gather = [&](const TriangleCoverage& cov, const CoverageRun& run) {
      const int n = run.count, y = run.y + vy, x0 = run.x0 + vx;
      if (n >= kLongRun) {  // a long run pays its per-call costs alone: shaded in place, not copied
        shade_group(ds, span, band);
        opened = false;
        if (sc.recording) {
          sc.recording->steps.push_back({true, sc.recording->long_runs.size()});
          sc.recording->long_runs.push_back({sc.sequence_index, cov, y, x0, n, run.weight[0]});
        }
        shade_long_run(ds, tv, cov, y, x0, n, run.weight[0], span, band);
        return;
      }
      RowBits rb{};
      if (across) {
        rb = row_bits(static_cast<std::size_t>(y) * sc.taken_words, x0, n);
        if ((sc.taken[rb.word] & rb.lo) || (rb.hi && (sc.taken[rb.word + 1] & rb.hi))) {
          shade_group(ds, span, band);  // a pixel of the group: it goes first
          opened = false;
          ++sc.met;
        }
      }
      if (!opened) {
        const unsigned reuse = coords_reuse_mask(plan, tv);
        if (!sc.triangles.empty() && reuse != sc.coords_reuse) shade_group(ds, span, band);
        sc.coords_reuse = reuse;
        if (!sc.triangles.empty()) ++sc.joined;
        sc.triangles.push_back({tv, cov, static_cast<int>(sc.run_length.size()), sc.group_fragments});
        if (sc.recording) sc.triangle_index.push_back(sc.sequence_index);
        opened = true;
      }
      if (across) {
        sc.taken[rb.word] |= rb.lo;
        if (rb.hi) sc.taken[rb.word + 1] |= rb.hi;
        sc.marked = true;
      }
      sc.run_y.push_back(y);
      sc.run_x0.push_back(x0);
      sc.run_length.push_back(n);
      sc.weight.push_back(run.weight[0]);
      sc.group_fragments += n;
      if (sc.group_fragments >= kGroupFragments) {
        shade_group(ds, span, band);
        opened = false;
      }
    };
    rasterize_triangle(
        sv, profile_.subpixel_bits, ds.cx0, y0, ds.cx1, y1,  // (one capture: no allocation)
        [&gather](const TriangleCoverage& cov, const CoverageRun& run) { gather(cov, run); }, RunWeights::First,
        &sc.coverage_run);
    if (!across) shade_group(ds, span, band);
    return;
  }
  shade_group(ds, span, band);  // (none open: the span path is the same for a whole glEnd)
  // One run into `span` (the probe is on, or the span path does not apply).
  auto shade_run = [&](const TriangleCoverage& cov, const CoverageRun& run) {
    const std::int64_t A = cov.area;
    const int n = static_cast<int>(run.weight.size());
    span.y = run.y + vy;
    span.x0 = run.x0 + vx;
    span.count = n;
    if (arith == Arithmetic::Fixed) span.codes.resize(4 * static_cast<std::size_t>(n));
    else span.values.resize(4 * static_cast<std::size_t>(n));
    if (has_depth) span.depth.resize(static_cast<std::size_t>(n));
    // The span path for a run without the probed pixel (the probed one takes the
    // reference path, which records what it computes), or every fragment below.
    if (span_path && !(probe_.enabled() && probe_.y() == span.y && probe_.x() >= span.x0 && probe_.x() < span.x0 + n)) {
      const FastRuns one{run.weight.data(), &n, 1, n};
      const GroupTriangle g{tv, cov, 0, 0};
      shade_runs_fast(st, plan, &g, 1, one, flat, shade, span.codes.data(), has_depth ? span.depth.data() : nullptr, sc);
      count_written(band, 0, 1);
      write();
      return;
    }
    for (int f = 0; f < n; ++f) {
      const auto& w = run.weight[static_cast<std::size_t>(f)];
      if (has_depth) span.depth[f] = interpolate_code(w, A, tv[0]->depth, tv[1]->depth, tv[2]->depth);
      Rgba primary, secondary;
      for (int k = 0; k < 4; ++k) {
        if (arith == Arithmetic::Fixed) {
          primary.code[k] = flat ? tv[0]->color_code[k]
                                 : interpolate_code(w, A, tv[0]->color_code[k], tv[1]->color_code[k], tv[2]->color_code[k]);
          secondary.code[k] = flat ? tv[0]->secondary_code[k]
                                   : interpolate_code(w, A, tv[0]->secondary_code[k], tv[1]->secondary_code[k],
                                                      tv[2]->secondary_code[k]);
        } else {
          const double a = static_cast<double>(A);
          primary.value[k] = flat ? tv[0]->color[k]
                                  : to_color_value((static_cast<double>(w[0]) * tv[0]->color[k] +
                                                    static_cast<double>(w[1]) * tv[1]->color[k] +
                                                    static_cast<double>(w[2]) * tv[2]->color[k]) / a, arith);
          secondary.value[k] = flat ? tv[0]->secondary[k]
                                    : to_color_value((static_cast<double>(w[0]) * tv[0]->secondary[k] +
                                                      static_cast<double>(w[1]) * tv[1]->secondary[k] +
                                                      static_cast<double>(w[2]) * tv[2]->secondary[k]) / a, arith);
        }
      }
      Rgba out = primary;
      if (shade) {
        UnitTexCoords tc{};
        for (int u = 0; u < kMaxTextureUnits; ++u) {
          if (!plan.sample[u]) continue;
          const double a = static_cast<double>(A);
          std::array<double, 3> v{}, dx{}, dy{};  // s/w, t/w, q/w and their x, y derivatives
          for (int j = 0; j < 3; ++j) {
            for (int k = 0; k < 3; ++k) {
              v[j] += static_cast<double>(w[k]) * tv[k]->tcw[u][j];
              dx[j] += static_cast<double>(cov.dwdx[k]) * tv[k]->tcw[u][j];
              dy[j] += static_cast<double>(cov.dwdy[k]) * tv[k]->tcw[u][j];
            }
            v[j] /= a;
            dx[j] /= a;
            dy[j] /= a;
          }
          const double q = v[2];
          tc[u].s = v[0] / q;
          tc[u].t = v[1] / q;
          const TextureObject& tex = *st.units[u].texture;
          if (!needs_lod(tex.params)) continue;
          // ρ of GL121 eq. 3.15 from the exact derivatives of s = N/D at the centre.
          const TextureImage& base = tex.levels[static_cast<std::size_t>(tex.params.base_level)];
          const double ws = level_width(base), hs = level_height(base, st.units[u].dims);
          const double ux = (dx[0] * q - v[0] * dx[2]) / (q * q) * ws, uy = (dy[0] * q - v[0] * dy[2]) / (q * q) * ws;
          const double vxd = (dx[1] * q - v[1] * dx[2]) / (q * q) * hs, vyd = (dy[1] * q - v[1] * dy[2]) / (q * q) * hs;
          const bool one_d = st.units[u].dims == 1;
          if (arith == Arithmetic::Float64) {
            const double rx = std::sqrt(ux * ux + (one_d ? 0.0 : vxd * vxd));
            const double ry = std::sqrt(uy * uy + (one_d ? 0.0 : vyd * vyd));
            tc[u].lambda = std::log2(std::max(rx, ry));
          } else {
            const auto fux = static_cast<float>(ux), fuy = static_cast<float>(uy);
            const auto fvx = one_d ? 0.0f : static_cast<float>(vxd), fvy = one_d ? 0.0f : static_cast<float>(vyd);
            const float rx = std::sqrt(fux * fux + fvx * fvx), ry = std::sqrt(fuy * fuy + fvy * fvy);
            tc[u].lambda = static_cast<double>(std::log2(std::max(rx, ry)));
          }
        }
        const bool probed = probe_.hits(span.x0 + f, span.y);
        std::string note;
        if (probed) shade_probe_ = &note;
        out = shade_fragment(st, plan, primary, secondary, tc);
        if (probed) shade_probe_ = nullptr;  // (workers never probe: no shared write)
        if (probed) probe_.record("shading", "primary " + describe_rgba(primary, st.color) + note + "\n    fragment colour " +
                                                 describe_rgba(out, st.color));
      }
      for (int k = 0; k < 4; ++k) {
        if (arith == Arithmetic::Fixed) span.codes[4 * static_cast<std::size_t>(f) + k] = static_cast<std::uint16_t>(out.code[k]);
        else span.values[4 * static_cast<std::size_t>(f) + k] = out.value[k];
      }
    }
    write();
  };
  rasterize_triangle(sv, profile_.subpixel_bits, ds.cx0, y0, ds.cx1, y1,  // (one capture: no allocation)
                     [&shade_run](const TriangleCoverage& cov, const CoverageRun& run) { shade_run(cov, run); },
                     RunWeights::All, &sc.coverage_run);
}

void Context::draw_polygon(std::vector<ClipVertex>& poly, std::size_t provoking, const DrawSetup& ds) {
  WindowVertices& wv = window_scratch_;
  wv.clear();
  if (!prepare_polygon(poly, provoking, ds, wv)) return;
  FragmentSpan span;  // reused from run to run
  for (std::size_t i = 1; i + 1 < wv.size(); ++i) raster_triangle(ds, {&wv[0], &wv[i], &wv[i + 1]}, ds.cy0, ds.cy1, span, -1);
  shade_group(ds, span, -1);  // (the next polygon reuses window_scratch_)
}

void Context::clear_batch() {
  batch_vertices_.clear();
  batch_triangles_.clear();
  batch_r0_ = batch_r1_ = 0;
  batch_area_ = 0;
  batch_geometry_.clear();
  batch_unkeyed_ = false;
  window_fills_.clear();
}

void Context::batch_polygon(std::vector<ClipVertex>& poly, std::size_t provoking, const DrawSetup& ds) {
  const std::size_t base = batch_vertices_.size();
  if (!prepare_polygon(poly, provoking, ds, batch_vertices_)) return;
  batch_unkeyed_ = true;  // (no memo serial names these triangles)
  for (std::size_t i = base + 1; i + 1 < batch_vertices_.size(); ++i) batch_triangle(base, i, i + 1, ds);
  if (batch_triangles_.size() >= kBatchTriangles) flush_batch(ds);
}

void Context::batch_triangle(std::size_t a, std::size_t b, std::size_t c, const DrawSetup& ds) {
  const int S = profile_.subpixel_bits;
  const SnappedVertex &pa = batch_vertices_[a].p, &pb = batch_vertices_[b].p, &pc = batch_vertices_[c].p;
  // No fragment, whatever the band (e.g. a mesh scaled to a point): left out of
  // the batch, its key, its recording and every band's walk.
  if (triangle_never_covers(pa, pb, pc)) return;
  // Rows and columns the triangle's bounding box may cover (one more each way
  // than the snapped extremes), clipped to the window. A triangle that misses
  // the window produces no fragment and is left out.
  const std::int64_t lo = std::min({pa.y, pb.y, pc.y}) >> S, hi = (std::max({pa.y, pb.y, pc.y}) >> S) + 2;
  const std::int64_t le = std::min({pa.x, pb.x, pc.x}) >> S, ri = (std::max({pa.x, pb.x, pc.x}) >> S) + 2;
  const int r0 = static_cast<int>(std::max<std::int64_t>(lo, ds.cy0)), r1 = static_cast<int>(std::min<std::int64_t>(hi, ds.cy1));
  const int c0 = static_cast<int>(std::max<std::int64_t>(le, ds.cx0)), c1 = static_cast<int>(std::min<std::int64_t>(ri, ds.cx1));
  if (r1 <= r0 || c1 <= c0) return;
  batch_r0_ = batch_triangles_.empty() ? r0 : std::min(batch_r0_, r0);
  batch_r1_ = batch_triangles_.empty() ? r1 : std::max(batch_r1_, r1);
  // Its fragments, about: its area in pixels, at most its clipped box's (in
  // double: snapped coordinates reach 2^30, pipeline/raster/triangle.cpp). The
  // scale is a power of two: the product is the quotient by 2^(2S+1), exactly.
  const double cross = (static_cast<double>(pb.x - pa.x) * static_cast<double>(pc.y - pa.y) -
                        static_cast<double>(pb.y - pa.y) * static_cast<double>(pc.x - pa.x)) *
                       ds.area_scale;
  const double box = static_cast<double>(r1 - r0) * (c1 - c0);
  batch_area_ += static_cast<std::int64_t>(std::min(std::abs(cross), box));
  batch_triangles_.push_back({{static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b), static_cast<std::uint32_t>(c)}, r0, r1});
}

WorkerPool& Context::pool() {
  if (!pool_ || pool_->threads() != threads_) pool_ = WorkerPool::borrow(threads_);
  return *pool_;
}

void Context::run_split(int n, const std::function<void(int)>& fn) {
  struct Add {  // (also when a task throws: run rethrows after every task ended)
    Context& c;
    const std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
    ~Add() { c.pool_time_ += std::chrono::steady_clock::now() - t0; }
  } add{*this};
  WorkerPool& p = pool();
  p.run(n, fn, split_on_caller_);
  pool_wait_ += p.last_wait();
  pool_start_ += p.last_start();
  if (p.threads() > 1 && !split_on_caller_ && n > 0) ++pool_runs_;
}

void Context::ready_bands(int bands) {
  pool();
  if (band_scratch_.size() < static_cast<std::size_t>(bands)) {
    band_scratch_.resize(static_cast<std::size_t>(bands));
    band_spans_.resize(static_cast<std::size_t>(bands));
    band_counts_.resize(static_cast<std::size_t>(bands));
  }
}

void Context::flush_batch(const DrawSetup& ds) {
  // Emptied however this ends (a band may throw: WorkerPool::run rethrows once
  // every band has ended); the band counters are summed likewise, so the counts
  // include the fragments written before the exception.
  struct Done {
    Context& c;
    ~Done() {
      c.clear_batch();
      c.sum_band_counts();
      c.batch_pending_ = false;  // (the next glEnd makes its set-up again: Context::end)
    }
  } done{*this};
  if (batch_triangles_.empty()) return;
  auto tri = [&](const BatchTriangle& t) {
    return std::array<const WindowVertex*, 3>{&batch_vertices_[t.v[0]], &batch_vertices_[t.v[1]], &batch_vertices_[t.v[2]]};
  };
  // More bands than threads (dynamic scheduling balances rows of different cost),
  // at least one row each.
  const int rows = batch_r1_ - batch_r0_;
  const int bands = std::min(4 * threads_, rows);
  const bool split = batch_area_ >= split_fragments_ && bands >= 2;
  run_window_fills(ds, split);  // (before anything reads the vertices: the key, the bands)
  if (!split) {  // not worth the pool: in order on this thread
    FragmentSpan span;
    sequence_scratch_.clear();
    for (const BatchTriangle& t : batch_triangles_) sequence_scratch_.push_back(tri(t));
    draw_sequence(ds, sequence_scratch_, span);
    return;
  }
  ready_bands(bands);
  ++split_batches_;
  split_triangles_ += batch_triangles_.size();
  const int r0 = batch_r0_;
  // The raster cache (sim/draw_replay.cpp): the batch's triangles and its bands
  // are the key; each band replays, or records into, its own recording.
  const bool cache = raster_cache_applies(ds);
  std::vector<std::int64_t> key;
  const std::vector<RasterRecording>* replay = nullptr;
  std::vector<RasterRecording> recorded;
  if (cache) {
    // The glEnds' memo serials name the triangles when each of them had one (and
    // they account for every triangle); else every triangle's positions.
    std::uint64_t named = 0;
    for (std::size_t i = 1; i < batch_geometry_.size(); i += 2) named += batch_geometry_[i];
    const bool by_serial = !batch_unkeyed_ && named == batch_triangles_.size();
    // The key reads the triangles for their positions, or their coords_reuse_mask;
    // named, with fewer than two sampled units, it reads neither.
    sequence_scratch_.clear();
    if (!by_serial || coords_may_be_reused(*ds.plan))
      for (const BatchTriangle& t : batch_triangles_) sequence_scratch_.push_back(tri(t));
    key = raster_key(ds, sequence_scratch_.data(), batch_triangles_.size(), {r0, rows, bands},
                     by_serial ? std::span<const std::uint64_t>(batch_geometry_) : std::span<const std::uint64_t>());
    replay = raster_cache_.find(key);
    if (!replay) recorded.resize(static_cast<std::size_t>(bands));
  }
  run_split(bands, [&](int b) {
    const int y0 = r0 + static_cast<int>(std::int64_t{rows} * b / bands);
    const int y1 = r0 + static_cast<int>(std::int64_t{rows} * (b + 1) / bands);
    FragmentSpan& bs = band_spans_[static_cast<std::size_t>(b)].span;
    std::vector<TriangleRef>& seq = band_scratch_[static_cast<std::size_t>(b)].sequence;
    seq.clear();
    if (replay) {  // this band's triangles as the recording holds them (the key fixes them)
      const RasterRecording& rec = (*replay)[static_cast<std::size_t>(b)];
      for (const std::uint32_t i : rec.band_triangles) seq.push_back(tri(batch_triangles_[i]));
      replay_sequence(ds, seq, rec, bs, b);
      return;
    }
    // Every triangle, in order; only this band's rows (kept by a recording).
    RasterRecording* const rec = cache ? &recorded[static_cast<std::size_t>(b)] : nullptr;
    for (std::size_t i = 0; i < batch_triangles_.size(); ++i) {
      const BatchTriangle& t = batch_triangles_[i];
      if (t.r0 >= y1 || t.r1 <= y0) continue;
      seq.push_back(tri(t));
      if (rec) rec->band_triangles.push_back(static_cast<std::uint32_t>(i));
    }
    if (rec) {
      record_sequence(ds, seq, y0, y1, bs, b, *rec);
    } else {
      for (const TriangleRef& t : seq) raster_triangle(ds, t, y0, y1, bs, b);
      shade_group(ds, bs, b);
    }
  });
  if (cache && !replay) raster_cache_.insert(std::move(key), std::move(recorded));
}

}  // namespace ffsim

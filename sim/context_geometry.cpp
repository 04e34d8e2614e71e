// Immediate-mode geometry (GL121 §2.6-2.12): glBegin/glEnd and the current
// vertex attributes, the viewport and depth range, the shading model and the
// raster position. Primitives are assembled at glEnd and drawn by
// sim/draw.cpp (clipping, rasterization, shading).
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <stdexcept>

#include "pipeline/gl/enum_names.h"
#include "sim/context.h"
#include "sim/draw_span.h"  // WindowVertex

namespace ffsim {

namespace {

constexpr int kMaxViewportDims = 16384;  // MAX_VIEWPORT_DIMS (= the largest framebuffer side)

bool drawable_mode(GLenum m) {
  return m == gl::TRIANGLES || m == gl::TRIANGLE_STRIP || m == gl::TRIANGLE_FAN || m == gl::QUADS ||
         m == gl::QUAD_STRIP || m == gl::POLYGON;
}

double clamp01(double v) { return std::isnan(v) ? 0.0 : std::clamp(v, 0.0, 1.0); }

}  // namespace

bool Context::reject_in_begin(const char* function) {
  if (!in_begin_) return false;
  error(gl::INVALID_OPERATION, function, "not allowed between glBegin and glEnd");
  return true;
}

void Context::begin(GLenum mode) {
  if (in_begin_) {
    error(gl::INVALID_OPERATION, "glBegin", "glBegin inside glBegin/glEnd");
    return;
  }
  if (mode == gl::POINTS || mode == gl::LINES || mode == gl::LINE_LOOP || mode == gl::LINE_STRIP) {
    // Values 0..3 are shared with GL_FALSE/GL_TRUE/GL_ONE..., so name them here.
    static const char* const kModes[] = {"GL_POINTS", "GL_LINES", "GL_LINE_LOOP", "GL_LINE_STRIP"};
    error(gl::INVALID_ENUM, "glBegin", std::string(kModes[mode]) + ": points and lines are not modelled by ffsim");
    return;
  }
  if (!drawable_mode(mode)) {
    error(gl::INVALID_ENUM, "glBegin", gl::enum_name(mode) + " is not a primitive mode");
    return;
  }
  in_begin_ = true;
  begin_mode_ = mode;
  begin_count_ = 0;
  run_fill_.pending = nullptr;
  run_fill_.in_place = false;
}

void Context::end() {
  if (!in_begin_) {
    error(gl::INVALID_OPERATION, "glEnd", "glEnd without glBegin");
    return;
  }
  in_begin_ = false;
  std::vector<ClipVertex> v;
  v.swap(begin_vertices_);
  v.resize(begin_count_);  // (never larger: vertex4 grows it)
  // A replayed run's vertices not copied into v yet (they are all of them): the
  // record's, with fill's values where the run does not write. Copied where a
  // path reads v; the window attributes from the memo read the record.
  const VertexRunFill fill = run_fill_;
  run_fill_.pending = nullptr;
  run_fill_.in_place = false;
  const ClipVertex* const object = fill.pending ? fill.pending->vertices.data() : v.data();  // (the same positions)
  if (fill.pending && fill.pending->vertices.size() != v.size())  // (pending only while there are no other vertices)
    throw std::logic_error("glEnd: a replayed run's pending vertices are not the glBegin's");
  begin_count_ = 0;
  struct GiveBack {  // the vertices' storage back to begin_vertices_, however this ends
    std::vector<ClipVertex>& v;
    std::vector<ClipVertex>& to;
    ~GiveBack() {
      if (to.empty()) to.swap(v);  // (a glBegin's next vertices then reuse it: no growth per strip)
    }
  } give_back{v, begin_vertices_};
  const std::size_t n = v.size();
  // Deferred (set_defer_draws): the state lives in members, where the pending
  // batch's set-up points; it equals the pending batch's (only vertex data since).
  const bool defer = defer_draws_ && threads_ > 1 && !probe_.enabled() && !on_explain_;
  if (!defer) flush_deferred();
  ShadingState st_here;
  ShadingPlan plan_here;
  ShadingState& st = defer ? deferred_st_ : st_here;
  ShadingPlan& plan = defer ? deferred_plan_ : plan_here;
  // Deferred with a batch pending: only glBegin, glEnd and vertex data reached
  // the Context since the glEnd that left it (set_defer_draws' promise), and
  // shading_state, shading_plan and draw_setup read none of those, so that
  // glEnd's state, plan and set-up are this one's: reused, not recomputed. Every
  // flush (flush_batch, however it ends) clears batch_pending_, so a glEnd after
  // one recomputes them, and draw_setup's group clearing runs again.
  const bool reuse = defer && batch_pending_;
  if (!reuse) {
    st = shading_state();
    plan = shading_plan(st);
  } else {
    ++deferred_setup_reuses_;
  }
  if (on_explain_ && n >= 3) on_explain_(ffsim::explain_shading(st, plan));
  const DrawSetup ds = reuse ? deferred_ds_ : draw_setup(st, plan);
  // One thread: each polygon is drawn at once. Threads: the polygons are prepared
  // into batches, each rasterized in row bands (sim/draw.cpp, docs/performance.md).
  if (ds.bands && !batch_pending_) clear_batch();
  // Shared vertices (span path, smooth shading, every vertex inside the view
  // volume with w > 0): clip_polygon leaves every polygon as it is and
  // prepare_polygon keeps it, so a vertex's window form is the same in every
  // polygon that uses it; each is computed once and the polygons' fans index
  // them. The same triangles in the same order as polygon by polygon.
  bool shared = fast_paths_ && !ds.flat && n >= 3;
  // The vertices hold their object positions (vertex4). With the geometry memo
  // (sim/geometry_memo.h), a glEnd of the same positions under the same
  // transformation as an earlier one takes its window positions and depth
  // codes; otherwise they are transformed here.
  const bool memo = shared && geometry_memo_on_;
  GeometryKey gkey;
  std::uint64_t positions_hash = 0;
  const GeometryEntry* geo = nullptr;
  const GeometryEntry* entry = nullptr;  // this glEnd's memo entry, found or made
  if (memo) {
    gkey = {begin_mode_, modelview_.top(), projection_.top(), ds.hw, ds.hh, depth_near_, depth_far_,
            profile_.subpixel_bits, ds.has_depth ? fb_.format().depth_bits : 0};
    const auto object_at = [object](std::size_t i) -> const glm::dvec4& { return object[i].position; };
    // (a replayed run's record keeps its positions' hash; a miss inserts with it)
    positions_hash = fill.pending ? fill.pending->positions_hash : GeometryMemo::positions_hash(n, object_at);
    geo = geometry_memo_.find(gkey, n, positions_hash, object_at, fill.pending ? fill.pending->serial : 0);
  }
  if (!geo) {
    if (fill.pending && !fill.in_place) run_vertices(*fill.pending, fill, v.data());
    if (memo) {
      object_scratch_.resize(n);
      for (std::size_t i = 0; i < n; ++i) object_scratch_[i] = v[i].position;
    }
    for (ClipVertex& c : v) c.position = projection_.top() * (modelview_.top() * c.position);  // §2.10
    for (std::size_t i = 0; i < n && shared; ++i) shared = inside_view_volume(v[i].position);
  }
  // The memo's entry says every vertex lies at one window position: no triangle
  // of this glEnd makes a fragment (triangle_never_covers), so nothing is put in
  // window form, batched or drawn; a pending batch is left as it is (its state is
  // this glEnd's: only vertex data came since).
  if (shared && geo && geo->one_point) {
    ++one_point_draws_;
    return;
  }
  std::size_t shared_base = 0;
  std::uint64_t geometry = 0;  // the memo's serial of this glEnd's window positions
  FragmentSpan shared_span;
  sequence_scratch_.clear();
  WindowVertices* shared_wv = nullptr;  // where the shared window vertices go
  if (shared) {
    ++shared_vertex_draws_;
    WindowVertices& wv = *(shared_wv = ds.bands ? &batch_vertices_ : &window_scratch_);
    if (!ds.bands) wv.clear();
    shared_base = wv.size();
    wv.resize(shared_base + n);
    WindowVertex* w = wv.data() + shared_base;
    if (geo) {  // (its window vertices filled below, or by the batch's flush)
      geometry = geo->serial;
      entry = geo;
    } else if (!memo) {
      for (std::size_t i = 0; i < n; ++i) window_vertex(v[i], ds, w[i]);
    } else {  // window_vertex's two halves, keeping 1/w_c and the position half in the memo
      if (!window_fills_.empty() && geometry_memo_.insert_drops(gkey, n, positions_hash))
        settle_window_fills();  // (before an entry they read goes)
      GeometryEntry& e = geometry_memo_.insert(gkey, n, positions_hash, [this](std::size_t i) -> const glm::dvec4& { return object_scratch_[i]; });
      e.iw.resize(n);
      e.p.resize(n);
      e.depth.resize(ds.has_depth ? n : 0);
      e.one_point = true;
      e.same_run = fill.pending ? fill.pending->serial : 0;  // (its positions were copied from the record)
      // Threads, a recorded run's vertices: the window attributes are left to
      // the batch's flush, as for a replay below (batch_triangle reads only the
      // positions; the record and this entry stay until the fills are made).
      const bool leave = ds.bands && fill.pending;
      for (std::size_t i = 0; i < n; ++i) {
        e.iw[i] = 1.0 / v[i].position.w;
        window_position(v[i].position, e.iw[i], ds, w[i]);
        if (!leave) window_attributes(v[i], e.iw[i], ds, w[i]);
        e.p[i] = w[i].p;
        if (ds.has_depth) e.depth[i] = w[i].depth;
        e.one_point = e.one_point && e.p[i].x == e.p[0].x && e.p[i].y == e.p[0].y;
      }
      if (leave) leave_window_fill({shared_base, n, &e, fill});
      geometry = e.serial;
      entry = &e;
    }
  }
  // A polygon's fan over the shared window vertices: corner j is vertex at(j).
  auto shared_fan = [&](auto at, std::size_t count) {
    for (std::size_t j = 1; j + 1 < count; ++j) {
      if (ds.bands) {
        batch_triangle(shared_base + at(0), shared_base + at(j), shared_base + at(j + 1), ds);
      } else {  // drawn after the glEnd's last polygon (draw_sequence)
        const WindowVertices& wv = window_scratch_;
        sequence_scratch_.push_back({&wv[at(0)], &wv[at(j)], &wv[at(j + 1)]});
      }
    }
  };
  // Threads: the batch's raster key names this glEnd's triangles by its memo
  // serial (pushed after them), or by their positions when it has none.
  const std::size_t batch_before = batch_triangles_.size();
  if (ds.bands && (!shared || geometry == 0)) batch_unkeyed_ = true;
  auto draw_polygon = [&](std::initializer_list<std::size_t> index, std::size_t provoking) {
    if (shared) {
      const std::size_t* k = index.begin();
      shared_fan([k](std::size_t j) { return k[j]; }, index.size());
      return;
    }
    std::vector<ClipVertex>& poly = polygon_scratch_;  // (keeps its capacity)
    poly.clear();
    for (const std::size_t k : index) poly.push_back(v[k]);
    if (ds.bands) batch_polygon(poly, provoking, ds);
    else this->draw_polygon(poly, provoking, ds);
  };
  // Threads, shared vertices with a memo entry: the triangles batch_triangle
  // made for this entry in this window before are appended as they were.
  const std::int64_t area_before = batch_area_;
  BatchMemo* batch_memo = shared && ds.bands && entry ? &entry->batch : nullptr;
  const bool from_memo = batch_memo && batch_memo->valid && batch_memo->cx0 == ds.cx0 && batch_memo->cy0 == ds.cy0 &&
                         batch_memo->cx1 == ds.cx1 && batch_memo->cy1 == ds.cy1;
  if (geo) {  // the entry's positions and depth codes, and the attributes
    if (fill.pending) ++run_record_reads_;  // (the record and the fills: the vertices are never copied)
    if (from_memo && fill.pending) {
      // Its triangles come from the memo and the record outlives the batch (a
      // memo insertion that would drop it settles the fills first): nothing
      // reads these vertices before the flush, which fills them over the pool
      // (performance.md 35).
      leave_window_fill({shared_base, n, geo, fill});
    } else {
      WindowVertex* w = shared_wv->data() + shared_base;
      memo_window_vertices(*geo, fill.pending ? object : v.data(), fill.pending ? &fill : nullptr, 0, n, ds, w);
    }
  }
  if (from_memo) {
    ++batch_memo_uses_;
    const auto base = static_cast<std::uint32_t>(shared_base);
    const std::size_t at = batch_triangles_.size();
    batch_triangles_.resize(at + batch_memo->triangles.size());  // (one size check, not one per triangle; no fill)
    rebase_triangles(batch_memo->triangles.data(), batch_memo->triangles.size(), base, batch_triangles_.data() + at);
    if (!batch_memo->triangles.empty()) {
      batch_r0_ = batch_before == 0 ? batch_memo->r0 : std::min(batch_r0_, batch_memo->r0);
      batch_r1_ = batch_before == 0 ? batch_memo->r1 : std::max(batch_r1_, batch_memo->r1);
    }
    batch_area_ += batch_memo->area;
  }
  // Shared vertices and triangle primitives: each triangle straight to the batch
  // or the sequence, as draw_polygon and shared_fan give it for a 3-vertex polygon.
  const bool direct = shared && !from_memo &&
                      (begin_mode_ == gl::TRIANGLES || begin_mode_ == gl::TRIANGLE_STRIP || begin_mode_ == gl::TRIANGLE_FAN);
  if (direct) {
    // One thread: the sequence sized once for at most n − 2 triangles, written
    // in place and cut to what was written (no capacity check per triangle).
    const WindowVertex* const sw = window_scratch_.data() + shared_base;  // (0: one glEnd at a time)
    TriangleRef* out = nullptr;
    if (!ds.bands) {
      sequence_scratch_.resize(n - 2);  // (empty before: cleared above; n >= 3: shared)
      out = sequence_scratch_.data();
    }
    struct Cut {  // (however this ends)
      std::vector<TriangleRef>& seq;
      TriangleRef*& out;
      ~Cut() {
        if (out) seq.resize(static_cast<std::size_t>(out - seq.data()));
      }
    } cut{sequence_scratch_, out};
    auto triangle = [&](std::size_t a, std::size_t b, std::size_t c) {
      if (ds.bands) batch_triangle(shared_base + a, shared_base + b, shared_base + c, ds);
      else *out++ = {sw + a, sw + b, sw + c};
    };
    if (begin_mode_ == gl::TRIANGLES) {
      for (std::size_t i = 0; i + 2 < n; i += 3) triangle(i, i + 1, i + 2);
    } else if (begin_mode_ == gl::TRIANGLE_STRIP) {
      for (std::size_t i = 0; i + 2 < n; ++i) {
        if (i % 2 == 0) triangle(i, i + 1, i + 2);
        else triangle(i + 1, i, i + 2);  // keep the strip's orientation
      }
    } else {
      for (std::size_t i = 1; i + 1 < n; ++i) triangle(0, i, i + 1);
    }
  }
  // Provoking vertex for flat shading (GL121 Table 2.9, 0-based here).
  switch (from_memo || direct ? GLenum{0} : begin_mode_) {
    case gl::TRIANGLES:
      for (std::size_t i = 0; i + 2 < n; i += 3) draw_polygon({i, i + 1, i + 2}, 2);
      break;
    case gl::TRIANGLE_STRIP:
      for (std::size_t i = 0; i + 2 < n; ++i) {
        if (i % 2 == 0) draw_polygon({i, i + 1, i + 2}, 2);
        else draw_polygon({i + 1, i, i + 2}, 2);  // keep the strip's orientation
      }
      break;
    case gl::TRIANGLE_FAN:
      for (std::size_t i = 1; i + 1 < n; ++i) draw_polygon({0, i, i + 1}, 2);
      break;
    case gl::QUADS:
      for (std::size_t i = 0; i + 3 < n; i += 4) draw_polygon({i, i + 1, i + 2, i + 3}, 3);
      break;
    case gl::QUAD_STRIP:
      for (std::size_t i = 0; i + 3 < n; i += 2) draw_polygon({i, i + 1, i + 3, i + 2}, 2);
      break;
    case gl::POLYGON:
      if (n >= 3 && shared) {
        shared_fan([](std::size_t j) { return j; }, n);  // the fan of the whole polygon
      } else if (n >= 3) {
        polygon_scratch_.assign(v.begin(), v.end());
        if (ds.bands) batch_polygon(polygon_scratch_, 0, ds);
        else this->draw_polygon(polygon_scratch_, 0, ds);
      }
      break;
    default: break;
  }
  if (batch_memo && !from_memo) {  // (the glEnd's triangles are added whole: none flushed since batch_before)
    BatchMemo& m = *batch_memo;
    m.valid = true;
    m.cx0 = ds.cx0, m.cy0 = ds.cy0, m.cx1 = ds.cx1, m.cy1 = ds.cy1;
    m.triangles.clear();
    const auto base = static_cast<std::uint32_t>(shared_base);
    for (std::size_t i = batch_before; i < batch_triangles_.size(); ++i) {
      const BatchTriangle& t = batch_triangles_[i];
      m.triangles.push_back({{t.v[0] - base, t.v[1] - base, t.v[2] - base}, t.r0, t.r1});
      m.r0 = i == batch_before ? t.r0 : std::min(m.r0, t.r0);
      m.r1 = i == batch_before ? t.r1 : std::max(m.r1, t.r1);
    }
    m.area = batch_area_ - area_before;
  }
  if (shared && !ds.bands) draw_sequence(ds, sequence_scratch_, shared_span, geometry);  // through the raster cache
  if (shared && ds.bands && geometry != 0)  // (no flush since batch_before: a shared glEnd's triangles are added whole)
    batch_geometry_.insert(batch_geometry_.end(), {geometry, batch_triangles_.size() - batch_before});
  // Shared vertices: the batch is flushed when full only here, after the glEnd's
  // triangles (they index this glEnd's vertices, which a flush would clear).
  if (shared && ds.bands && batch_triangles_.size() >= kBatchTriangles) flush_batch(ds);
  if (ds.bands && defer) {  // drawn by a later glEnd's flush or flush_deferred()
    deferred_ds_ = ds;
    batch_pending_ = !batch_triangles_.empty();
  } else if (ds.bands) {
    flush_batch(ds);
  }
}

void Context::flush_deferred() {
  if (!batch_pending_) return;
  batch_pending_ = false;
  flush_batch(deferred_ds_);
}

void Context::vertex_attributes(ClipVertex& cv) const {
  cv.color = current_color_clamped_;  // §2.13.6 colour clamping (done by color4, secondaryColor3)
  cv.secondary = current_secondary_clamped_;
  for (int u = 0; u < profile_.texture_units; ++u) {
    const auto& tc = current_.texcoord[u];
    cv.texcoord[u] = texture_matrix_[u].top() * glm::dvec4(tc[0], tc[1], tc[2], tc[3]);
  }
  // The units past the profile's: unused_units() when the vertex was made.
}

void Context::unused_units(ClipVertex& cv) const {
  // Their current coordinates stay (0, 0, 0, 1) and their texture matrices the
  // identity (glMultiTexCoord and glActiveTexture refuse them), whose product is
  // (0, 0, 0, 1) exactly. Written once per vertex made: nothing else writes them
  // (vertex4 reuses begin_vertices_' slots; glEnd and clipping copy vertices).
  for (int u = profile_.texture_units; u < kMaxTextureUnits; ++u) cv.texcoord[u] = glm::dvec4(0, 0, 0, 1);
}

ClipVertex Context::make_vertex(const glm::dvec4& object) const {
  ClipVertex cv;
  unused_units(cv);
  vertex_attributes(cv);
  cv.position = projection_.top() * (modelview_.top() * object);  // §2.10 clip coordinates
  return cv;
}

void Context::vertex4(double x, double y, double z, double w) {
  // Outside glBegin/glEnd a vertex has no effect (GL121 §2.6.3 leaves it undefined).
  if (!in_begin_) return;
  if (run_fill_.pending) copy_pending_run();  // (a replay's vertices before this one)
  // The vertices of earlier glEnds are overwritten in place (every field is
  // written: constructing one costs more than filling it). The object position
  // is kept: glEnd transforms it (the matrices cannot change inside
  // glBegin/glEnd), or takes its window position from the geometry memo.
  if (begin_count_ == begin_vertices_.size()) unused_units(begin_vertices_.emplace_back());
  ClipVertex& cv = begin_vertices_[begin_count_++];
  vertex_attributes(cv);
  cv.position = glm::dvec4(x, y, z, w);
}
void Context::vertex2(double x, double y) { vertex4(x, y, 0, 1); }
void Context::vertex3(double x, double y, double z) { vertex4(x, y, z, 1); }

void Context::color4(double r, double g, double b, double a) {
  current_.color = {r, g, b, a};
  for (int c = 0; c < 4; ++c) current_color_clamped_[c] = clamp01(current_.color[c]);
}
void Context::color3(double r, double g, double b) { color4(r, g, b, 1); }
void Context::secondaryColor3(double r, double g, double b) {
  current_.secondary = {r, g, b, 0};
  for (int c = 0; c < 4; ++c) current_secondary_clamped_[c] = clamp01(current_.secondary[c]);
}
void Context::normal3(double x, double y, double z) { current_.normal = {x, y, z, 0}; }
void Context::texCoord4(double s, double t, double r, double q) { current_.texcoord[0] = {s, t, r, q}; }
void Context::texCoord2(double s, double t) { texCoord4(s, t, 0, 1); }

void Context::multiTexCoord4(GLenum texture, double s, double t, double r, double q) {
  const int unit = texture_unit("glMultiTexCoord", texture);
  if (unit >= 0) current_.texcoord[unit] = {s, t, r, q};
}
void Context::multiTexCoord2(GLenum texture, double s, double t) { multiTexCoord4(texture, s, t, 0, 1); }

void Context::viewport(int x, int y, int width, int height) {
  if (reject_in_begin("glViewport")) return;
  if (width < 0 || height < 0) {
    error(gl::INVALID_VALUE, "glViewport", "negative width or height");
    return;
  }
  // §2.10.1: width and height are silently clamped to MAX_VIEWPORT_DIMS.
  viewport_ = {x, y, std::min(width, kMaxViewportDims), std::min(height, kMaxViewportDims)};
}

void Context::depthRange(double n, double f) {
  if (reject_in_begin("glDepthRange")) return;
  depth_near_ = clamp01(n);  // §2.10.1: clamped to [0,1]
  depth_far_ = clamp01(f);
}

void Context::shadeModel(GLenum mode) {
  if (reject_in_begin("glShadeModel")) return;
  if (mode != gl::FLAT && mode != gl::SMOOTH) {
    error(gl::INVALID_ENUM, "glShadeModel", gl::enum_name(mode) + " is not FLAT or SMOOTH");
    return;
  }
  shade_model_ = mode;
}

// §2.12: the raster position is transformed like a vertex; if it lies outside
// the view volume it is invalid, otherwise it takes window coordinates, the
// clip w, the current colours and the current texture coordinates after the
// texture matrix.
void Context::rasterPos4(double x, double y, double z, double w) {
  if (reject_in_begin("glRasterPos")) return;
  const ClipVertex cv = make_vertex(glm::dvec4(x, y, z, w));
  RasterPosState& rp = raster_pos_;
  if (!inside_view_volume(cv.position)) {
    rp.valid = false;
    return;
  }
  const glm::dvec4& p = cv.position;
  rp.valid = true;
  rp.x = viewport_[0] + (p.x / p.w + 1) * (viewport_[2] / 2.0);
  rp.y = viewport_[1] + (p.y / p.w + 1) * (viewport_[3] / 2.0);
  rp.z = depth_near_ + (depth_far_ - depth_near_) * ((p.z / p.w + 1) / 2);
  rp.w = p.w;
  rp.color = cv.color;
  rp.secondary_color = cv.secondary;
  for (int u = 0; u < kMaxTextureUnits; ++u)
    rp.texcoord[u] = {cv.texcoord[u].x, cv.texcoord[u].y, cv.texcoord[u].z, cv.texcoord[u].w};
}
void Context::rasterPos2(double x, double y) { rasterPos4(x, y, 0, 1); }
void Context::rasterPos3(double x, double y, double z) { rasterPos4(x, y, z, 1); }

}  // namespace ffsim

// The vertex-run memo (sim/vertex_run_memo.h, docs/performance.md 25.1): a run
// of vertex-data calls replayed from its recording.
#include <cstring>

#include "sim/context.h"

namespace ffsim {

namespace {

template <class T>
bool same_bits(const T& a, const T& b) {  // (−0 and +0 differ: the recording's inputs, bit for bit)
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

// Attribute k of a, as VertexAttribBit numbers them (color, secondary, normal, texcoord 0..).
const std::array<double, 4>& attribute(const CurrentAttribs& a, int k) {
  return k == 0 ? a.color : k == 1 ? a.secondary : k == 2 ? a.normal : a.texcoord[static_cast<std::size_t>(k - 3)];
}
std::array<double, 4>& attribute(CurrentAttribs& a, int k) {
  return const_cast<std::array<double, 4>&>(attribute(std::as_const(a), k));
}
constexpr int kAttributes = 3 + kClipTexUnits;

}  // namespace

bool Context::vertex_run_replay(std::uint64_t id, const VertexRunUsage& usage) {
  vertex_run_start_.id = 0;
  if (!fast_paths_ || !vertex_run_memo_on_ || id == 0) return false;
  const VertexRunMemo::Record* r = vertex_run_memo_.find(id);
  bool same = r && r->in_begin == in_begin_;
  for (int k = 0; k < kAttributes && same; ++k)
    if (usage.read_first & (1u << k)) same = same_bits(attribute(r->entry, k), attribute(current_, k));
  // The written coordinates of the recorded vertices went through these matrices
  // (the matrices cannot change within the run: glMatrixMode and the matrix
  // calls are not vertex data).
  const bool made_vertices = in_begin_ && usage.has_vertex;
  for (int u = 0; u < kMaxTextureUnits && same && made_vertices; ++u)
    if (usage.written & texcoord_bit(u)) same = same_bits(r->texture_matrix[u], texture_matrix_[u].top());
  if (!same) {
    vertex_run_memo_.count(false);
    vertex_run_start_ = {id, current_, begin_count_, usage.written};
    return false;
  }
  vertex_run_memo_.count(true);
  if (in_begin_ && !r->vertices.empty()) {
    copy_pending_run();  // (an earlier replay's vertices: these follow them)
    const std::size_t n = r->vertices.size();
    const VertexRunFill f = current_fill(usage.written);
    if (begin_count_ == 0) {  // the glBegin's first vertices: copied when needed (glEnd may not)
      run_fill_ = f;
      run_fill_.pending = r;
    } else {
      if (begin_vertices_.size() < begin_count_ + n) begin_vertices_.resize(begin_count_ + n);  // (every slot copied)
      run_vertices(*r, f, begin_vertices_.data() + begin_count_);
    }
    begin_count_ += n;
  }
  for (int k = 0; k < kAttributes; ++k)
    if (usage.written & (1u << k)) attribute(current_, k) = attribute(r->exit, k);
  if (usage.written & kAttribColor) current_color_clamped_ = r->exit_color_clamped;
  if (usage.written & kAttribSecondary) current_secondary_clamped_ = r->exit_secondary_clamped;
  return true;
}

VertexRunFill Context::current_fill(std::uint8_t written) const {
  // The attributes the run does not write: each vertex took the current value
  // (vertex_attributes), the same for all of them.
  VertexRunFill f{nullptr, written, {}, {}, {}};
  if (!(written & kAttribColor)) f.color = current_color_clamped_;
  if (!(written & kAttribSecondary)) f.secondary = current_secondary_clamped_;
  for (int u = 0; u < profile_.texture_units; ++u) {
    if (!f.fills_texcoord(u, profile_.texture_units)) continue;
    const auto& tc = current_.texcoord[u];
    f.texcoord[static_cast<std::size_t>(u)] = texture_matrix_[u].top() * glm::dvec4(tc[0], tc[1], tc[2], tc[3]);
  }
  return f;
}

void Context::run_vertices(const VertexRunMemo::Record& r, const VertexRunFill& f, ClipVertex* out) const {
  const std::size_t n = r.vertices.size();
  std::memcpy(static_cast<void*>(out), r.vertices.data(), n * sizeof(ClipVertex));
  if (!(f.written & kAttribColor))
    for (std::size_t i = 0; i < n; ++i) out[i].color = f.color;
  if (!(f.written & kAttribSecondary))
    for (std::size_t i = 0; i < n; ++i) out[i].secondary = f.secondary;
  for (int u = 0; u < profile_.texture_units; ++u)
    if (f.fills_texcoord(u, profile_.texture_units))
      for (std::size_t i = 0; i < n; ++i) out[i].texcoord[u] = f.texcoord[static_cast<std::size_t>(u)];
}

void Context::copy_pending_run() {
  if (!run_fill_.pending) return;
  if (!run_fill_.in_place) {
    // The glBegin's first vertices (pending only while there are no others).
    const std::size_t n = run_fill_.pending->vertices.size();
    if (begin_vertices_.size() < n) begin_vertices_.resize(n);  // (every slot copied)
    run_vertices(*run_fill_.pending, run_fill_, begin_vertices_.data());
  }
  run_fill_.pending = nullptr;
  run_fill_.in_place = false;
}

void Context::vertex_run_record(std::uint64_t id) {
  copy_pending_run();  // (the vertices are read below, and a record may replace the pending one)
  if (vertex_run_start_.id != id || id == 0 || begin_count_ < vertex_run_start_.first) return;
  vertex_run_start_.id = 0;
  const std::size_t first = vertex_run_start_.first;
  const std::size_t n = in_begin_ ? begin_count_ - first : 0;
  if (!window_fills_.empty() && vertex_run_memo_.insert_drops(id, n)) settle_window_fills();  // (before a record they read goes)
  VertexRunMemo::Record& r = vertex_run_memo_.insert(id, begin_vertices_.data() + first, n);
  r.in_begin = in_begin_;
  r.entry = vertex_run_start_.entry;
  for (int u = 0; u < kMaxTextureUnits; ++u) r.texture_matrix[u] = texture_matrix_[u].top();
  r.exit = current_;
  r.exit_color_clamped = current_color_clamped_;
  r.exit_secondary_clamped = current_secondary_clamped_;
  // (a glEnd of only this run's replay looks its geometry up without hashing again)
  r.positions_hash = GeometryMemo::positions_hash(
      n, [&r](std::size_t i) -> const glm::dvec4& { return r.vertices[i].position; });
  // The glBegin's vertices are all this run's: its glEnd reads them from the
  // record, as after a replay (its positions' hash kept; with threads, its
  // window attributes left to the batch's flush, Context::end). The fill is a
  // replay's now: the run changed no attribute it does not write, and no
  // texture matrix (not vertex data), so the vertices hold those values.
  if (in_begin_ && first == 0 && n > 0) {
    run_fill_ = current_fill(vertex_run_start_.written);
    run_fill_.pending = &r;
    run_fill_.in_place = true;
  }
}

}  // namespace ffsim

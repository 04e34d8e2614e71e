// The geometry memo (docs/performance.md 18.1): the window positions of a
// glEnd's vertices, kept so that the next glEnd with the same object positions
// under the same transformation (the next pass of a multipass algorithm over the
// same mesh) does not transform, divide and snap them again.
//
// An entry is a pure function of its key: the object positions in order (bit
// for bit), the modelview and projection matrices, the viewport's half width
// and height, the depth range, the sub-pixel bits and the depth buffer's bits
// (GL121 §2.10-2.11: nothing else enters clip, normalized-device or window
// coordinates). It holds, per vertex, 1/w_c, the snapped window position and
// the depth code exactly as Context::window_vertex computes them, and is made
// only when every vertex lies inside the view volume (nothing clipped: the
// window vertices are the glEnd's own). Each entry has a serial, never reused,
// that names its content: the raster cache keys a glEnd by it instead of by
// every triangle's positions (sim/draw_replay.cpp).
#pragma once
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "pipeline/gl/enums.h"
#include "pipeline/raster/triangle.h"
#include "sim/hash.h"

namespace ffsim {

struct GeometryKey {
  GLenum mode = 0;  // the primitive (the serial then names the triangles too)
  glm::dmat4 modelview{1.0}, projection{1.0};
  double hw = 0, hh = 0;                // viewport half width and height
  double depth_near = 0, depth_far = 1;
  int subpixel_bits = 0, depth_bits = 0;  // depth_bits 0: no depth buffer (no depth codes)
};

// Threads (Context::end into a batch): the glEnd's triangles as
// Context::batch_triangle makes them for one window, [cx0, cx1) x [cy0, cy1)
// relative to the viewport corner: vertex indices relative to the glEnd's first,
// the rows each may cover, and the batch's sums. A pure function of the entry
// (its positions, the primitive key.mode, the sub-pixel bits) and the window, so
// a later glEnd of the entry in the same window appends them as they are
// (docs/performance.md 20.6); another window makes them again.
struct BatchMemo {
  struct Triangle {  // (also Context::BatchTriangle, the batch's)
    std::array<std::uint32_t, 3> v;  // vertex indices
    int r0, r1;                      // rows
  };
  bool valid = false;
  int cx0 = 0, cy0 = 0, cx1 = 0, cy1 = 0;
  std::vector<Triangle> triangles;
  int r0 = 0, r1 = 0;     // the rows of all of them (when there are any)
  std::int64_t area = 0;  // the sum batch_triangle adds to the batch's area
};

// `n` triangles from `in` to `out` with `base` added to each one's three vertex
// indices (modulo 2^32, as base + v in uint32_t) and its rows copied: a memo'd
// glEnd's triangles appended to the batch after its vertices. A triangle is five
// 32-bit words, (v0, v1, v2, r0, r1): eight (40 words, five 256-bit vectors) at
// a time.
void rebase_triangles(const BatchMemo::Triangle* in, std::size_t n, std::uint32_t base, BatchMemo::Triangle* out);

struct GeometryEntry {
  std::uint64_t serial = 0;
  GeometryKey key;
  std::vector<glm::dvec4> object;  // the key's positions
  std::vector<double> iw;          // 1 / w_c
  std::vector<SnappedVertex> p;
  std::vector<std::uint32_t> depth;  // empty without a depth buffer
  // Every window position equal (a mesh scaled to a point): no triangle of the
  // glEnd has area, so none makes a fragment (triangle_never_covers).
  bool one_point = false;
  mutable BatchMemo batch;           // (derived from the above: made when first needed)
  // A vertex-run record (VertexRunMemo::Record::serial) whose positions are these
  // bit for bit, compared once or inserted from; 0: none.
  mutable std::uint64_t same_run = 0;
};

class GeometryMemo {
 public:
  // At most this many vertices are kept; an insertion beyond it empties the memo.
  static constexpr std::size_t kMaxVertices = std::size_t{1} << 18;

  // `hash_bits` < 64 keeps only that many bits of each key's hash: the tests
  // make every key collide (0 bits), so that only the comparison tells keys apart.
  explicit GeometryMemo(int hash_bits = 64)
      : hash_mask_(hash_bits >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << hash_bits) - 1) {}

  // The part of an entry's hash that the n object positions at position_of(i)
  // make (the key's part is added by find and insert). A caller that draws
  // the same positions again keeps it (a vertex-run record, sim/vertex_run_memo.h).
  template <class PositionOf>
  static std::uint64_t positions_hash(std::size_t n, PositionOf position_of);
  // The entry for `key` and the n object positions at position_of(i), whose
  // positions_hash is `ph`, or null. (The positions are compared, not only hashed.)
  // `run`: the serial of the vertex-run record the positions are (0: none); a
  // serial names one record's positions, which never change, so an entry that
  // matched them once (GeometryEntry::same_run) is not compared with them again.
  template <class PositionOf>
  const GeometryEntry* find(const GeometryKey& key, std::size_t n, std::uint64_t ph, PositionOf position_of,
                            std::uint64_t run = 0);
  // A new entry (its vectors empty but `object`), with a serial of its own; the
  // caller fills iw, p and depth. Replaces an entry of the same hash.
  template <class PositionOf>
  GeometryEntry& insert(const GeometryKey& key, std::size_t n, std::uint64_t ph, PositionOf position_of);
  // Whether insert(key, n, ph, .) would drop an entry (the one it replaces, or
  // all of them when full): entries are never moved otherwise.
  bool insert_drops(const GeometryKey& key, std::size_t n, std::uint64_t ph) const {
    return vertices_ + n > kMaxVertices || entries_.count(hash(key, n, ph)) != 0;
  }
  // The same, hashing the positions here.
  template <class PositionOf>
  const GeometryEntry* find(const GeometryKey& key, std::size_t n, PositionOf position_of) {
    return find(key, n, positions_hash(n, position_of), position_of);
  }
  template <class PositionOf>
  GeometryEntry& insert(const GeometryKey& key, std::size_t n, PositionOf position_of) {
    return insert(key, n, positions_hash(n, position_of), position_of);
  }
  void clear();

  std::uint64_t hits() const { return hits_; }
  std::uint64_t misses() const { return misses_; }
  // Hits whose positions were not compared (the entry's same_run).
  std::uint64_t run_hits() const { return run_hits_; }
  std::size_t size() const { return entries_.size(); }

 private:
  std::uint64_t hash(const GeometryKey& key, std::size_t n, std::uint64_t ph) const {
    std::uint64_t h = hash_key(key, n);
    hash_mix(h, ph);
    return h & hash_mask_;
  }
  static std::uint64_t hash_key(const GeometryKey& key, std::size_t n);
  // hash_mix over the value's bits (−0 and +0, and NaNs of other payloads,
  // differ: the key is compared bit for bit).
  static void mix(std::uint64_t& h, double v) { hash_mix(h, std::bit_cast<std::uint64_t>(v)); }
  static bool same_key(const GeometryKey& a, const GeometryKey& b);
  std::unordered_map<std::uint64_t, GeometryEntry> entries_;  // by hash; the key is compared
  std::uint64_t hash_mask_;
  std::size_t vertices_ = 0;
  std::uint64_t next_serial_ = 1, hits_ = 0, misses_ = 0, run_hits_ = 0;
};

// ---- implementation ------------------------------------------------------------

template <class PositionOf>
std::uint64_t GeometryMemo::positions_hash(std::size_t n, PositionOf position_of) {
  // One multiply-xorshift lane per coordinate (four independent chains; one
  // chain over every coordinate was slower than the transformation it saves).
  std::array<std::uint64_t, 4> h{0x9E3779B97F4A7C15ull, 0x9E3779B97F4A7C15ull * 3, 0x9E3779B97F4A7C15ull * 5,
                                 0x9E3779B97F4A7C15ull * 7};
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec4& o = position_of(i);
    for (int c = 0; c < 4; ++c) mix(h[static_cast<std::size_t>(c)], o[c]);
  }
  for (std::size_t c = 1; c < 4; ++c) hash_mix(h[0], h[c]);
  return h[0];
}

template <class PositionOf>
const GeometryEntry* GeometryMemo::find(const GeometryKey& key, std::size_t n, std::uint64_t ph,
                                        PositionOf position_of, std::uint64_t run) {
  const auto it = entries_.find(hash(key, n, ph));
  bool same = it != entries_.end() && it->second.object.size() == n && same_key(it->second.key, key);
  if (same && run != 0 && it->second.same_run == run) {
    ++hits_;
    ++run_hits_;
    return &it->second;
  }
  // Bit for bit (−0 is not +0; a NaN equals its own bits): each position's four
  // coordinates as 64-bit words, or-ed together, one test per vertex.
  const glm::dvec4* kept = it != entries_.end() ? it->second.object.data() : nullptr;
  for (std::size_t i = 0; i < n && same; ++i) {
    const glm::dvec4& a = kept[i];
    const glm::dvec4& b = position_of(i);
    std::uint64_t diff = 0;
    for (int c = 0; c < 4; ++c) diff |= std::bit_cast<std::uint64_t>(a[c]) ^ std::bit_cast<std::uint64_t>(b[c]);
    same = diff == 0;
  }
  if (!same) {
    ++misses_;
    return nullptr;
  }
  ++hits_;
  if (run != 0) it->second.same_run = run;
  return &it->second;
}

template <class PositionOf>
GeometryEntry& GeometryMemo::insert(const GeometryKey& key, std::size_t n, std::uint64_t ph, PositionOf position_of) {
  if (vertices_ + n > kMaxVertices) clear();
  const std::uint64_t h = hash(key, n, ph);
  const auto old = entries_.find(h);
  if (old != entries_.end()) {
    vertices_ -= old->second.object.size();
    entries_.erase(old);
  }
  GeometryEntry& e = entries_[h];
  e.serial = next_serial_++;
  e.key = key;
  e.object.resize(n);
  for (std::size_t i = 0; i < n; ++i) e.object[i] = position_of(i);
  vertices_ += n;
  return e;
}

}  // namespace ffsim

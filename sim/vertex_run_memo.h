// The vertex-run memo (docs/performance.md 25.1): the effect of a run of
// vertex-data calls (glColor, glSecondaryColor, glNormal, glTexCoord,
// glMultiTexCoord, glVertex; none can record an error), recorded the first time
// and replayed when the same calls run again under the same state. The terrain of
// the paper's traces is drawn several times a frame, each time by the same
// 1860 vertices and 3720 texture-coordinate calls: a replay copies the recorded
// vertices instead of calling, converting and transforming again.
//
// A run's effect is a pure function of its calls (the trace names runs of equal
// calls, argument bits included, by one id: sim/trace/vertex_runs.cpp), of the
// current attributes it reads (GL121 §2.7), of the texture matrices of the units
// whose coordinates it sets, and of whether it lies inside glBegin/glEnd (outside,
// a vertex has no effect). The trace also says how the run uses each attribute
// (VertexRunUsage), which decides what a replay compares and what it takes from
// the current state instead of the record:
//  - not written by the run: every vertex takes the current value (the current
//    colour clamped, §2.13.6; a coordinate through the current texture matrix,
//    §2.10.2), and the value stays; a replay fills it from the current state,
//    so passes that differ only in their glColor share one record.
//  - written before any vertex reads it: the vertices hold the run's own values
//    (and for coordinates the texture matrix, compared); the exit value is the
//    record's.
//  - written after a vertex has read it: as above, and the entry value is
//    compared too (the vertices before the write hold it).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "pipeline/geometry/clip.h"

namespace ffsim {

struct CurrentAttribs {  // GL121 §2.7 current values
  std::array<double, 4> color{1, 1, 1, 1};
  std::array<double, 4> secondary{0, 0, 0, 0};
  std::array<double, 4> normal{0, 0, 1, 0};
  std::array<std::array<double, 4>, kClipTexUnits> texcoord{{{0, 0, 0, 1}, {0, 0, 0, 1}, {0, 0, 0, 1}, {0, 0, 0, 1}}};
};

// The current attributes, as bits of VertexRunUsage's masks.
enum VertexAttribBit : std::uint8_t {
  kAttribColor = 1u << 0,
  kAttribSecondary = 1u << 1,
  kAttribNormal = 1u << 2,
  kAttribTexCoord0 = 1u << 3,  // unit u: kAttribTexCoord0 << u
};
constexpr std::uint8_t texcoord_bit(int unit) { return static_cast<std::uint8_t>(kAttribTexCoord0 << unit); }

struct VertexRunUsage {
  std::uint8_t written = 0;     // attributes some call of the run sets
  std::uint8_t read_first = 0;  // written attributes a vertex reads before the run's first write of them
  bool has_vertex = false;      // the run calls glVertex
};

class VertexRunMemo {
 public:
  // At most this many vertices are kept; a record beyond it empties the memo.
  static constexpr std::size_t kMaxVertices = std::size_t{1} << 18;

  struct Record {
    bool in_begin = false;
    CurrentAttribs entry;  // compared: the read_first attributes
    std::array<glm::dmat4, kClipTexUnits> texture_matrix{};  // compared: the written units'
    CurrentAttribs exit;   // taken: the written attributes
    std::array<double, 4> exit_color_clamped{}, exit_secondary_clamped{};
    std::vector<ClipVertex> vertices;  // inside glBegin/glEnd: the vertices the run made
    std::uint64_t positions_hash = 0;  // GeometryMemo::positions_hash of their object positions
    // Names this record's vertices, which never change (never 0; a replacing
    // record, or one after clear(), has a new serial): GeometryEntry::same_run.
    std::uint64_t serial = 0;
  };

  const Record* find(std::uint64_t id) const {
    const auto it = records_.find(id);
    return it == records_.end() ? nullptr : &it->second;
  }
  // Whether insert(id, ., n) would drop a record (the one it replaces, or all
  // of them when full): records are never moved otherwise.
  bool insert_drops(std::uint64_t id, std::size_t n) const {
    return vertices_ + n > kMaxVertices || records_.count(id) != 0;
  }
  // A record for `id` (replacing any) holding the n vertices at `vertices`; the
  // caller fills in the rest.
  Record& insert(std::uint64_t id, const ClipVertex* vertices, std::size_t n) {
    if (const auto old = records_.find(id); old != records_.end()) {
      vertices_ -= old->second.vertices.size();
      records_.erase(old);
    }
    if (vertices_ + n > kMaxVertices) clear();
    Record& r = records_[id];
    r.serial = next_serial_++;
    r.vertices.assign(vertices, vertices + n);
    vertices_ += n;
    return r;
  }
  void clear() {
    records_.clear();
    vertices_ = 0;
  }
  std::size_t size() const { return records_.size(); }
  // Replays, and runs recorded instead (counted by the Context, which compares).
  void count(bool hit) { ++(hit ? hits_ : misses_); }
  std::uint64_t hits() const { return hits_; }
  std::uint64_t misses() const { return misses_; }

 private:
  std::uint64_t hits_ = 0, misses_ = 0, next_serial_ = 1;
  std::unordered_map<std::uint64_t, Record> records_;
  std::size_t vertices_ = 0;
};

// A replay whose vertices begin the glBegin, not copied into the glBegin's
// array yet: its record and what it took from the current state instead of the
// record (the attributes the run does not write: each vertex holds the current
// value, the same for all of them). Copied when something else needs the
// array (Context::copy_pending_run); a glEnd whose vertices are all the
// run's and whose positions the geometry memo knows reads the record and the
// fills instead (window_attributes_n; docs/performance.md 26).
struct VertexRunFill {
  const VertexRunMemo::Record* pending = nullptr;  // null: none
  std::uint8_t written = 0;                        // VertexRunUsage::written
  // The colours when the run does not write them, and each unit's coordinates
  // after its texture matrix when the run does not write them and the profile
  // has the unit (else 0).
  std::array<double, 4> color{}, secondary{};
  std::array<glm::dvec4, kClipTexUnits> texcoord{};
  // The vertices are in the glBegin's array already (a run just called and
  // recorded: Context::vertex_run_record); `pending` names their record, which
  // a glEnd reads like a replay's, and nothing is copied.
  bool in_place = false;
  // Whether unit u's coordinates are filled (else the vertices' own).
  bool fills_texcoord(int u, int units) const { return u < units && !(written & texcoord_bit(u)); }
};

}  // namespace ffsim

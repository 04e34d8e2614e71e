// The vertex-run memo (sim/vertex_run_memo.h, docs/performance.md 25.1): the
// trace names runs of equal vertex-data calls by one id and says how they use
// each current attribute (sim/trace/vertex_runs.cpp); a Context replays a run
// from its recording when the state it depends on is the recording's. Checked
// here: the classes and usages of hand-written runs, the replays of a
// hand-written trace, and random traces (a few run templates repeated inside and
// outside glBegin/glEnd, with colours, coordinates and texture matrices changed
// between them) whose every hash, final buffers and current attributes must be
// those of the memo off and of the per-fragment path.
#include <doctest/doctest.h>

#include <sstream>
#include <string>
#include <vector>

#include "fast_scene.h"
#include "trace_test_util.h"
#include "sim/trace/executor.h"
#include "sim/trace/trace.h"

using namespace ffsim;
using namespace ffsim::test;
using namespace ffsim::trace;

namespace {

// The StepHot::run_class of the quiet run starting at `line` of a trace whose
// first call is on line `first_line` (each line one step).
std::uint32_t class_at(const Program& p, int line, int first_line) {
  return p.hot.at(static_cast<std::size_t>(line - first_line)).run_class;
}

const VertexRunUsage& usage_of(const Program& p, std::uint32_t cls) { return p.vertex_runs.at(cls - 1).usage; }

struct Outcome {
  RunResult result;
  std::array<double, 4> color, secondary, normal;
  std::vector<std::array<double, 4>> texcoord;
  std::uint64_t hits = 0, misses = 0, record_reads = 0, geometry_run_hits = 0;
};

Outcome run(const Program& p, int mode) {  // 0: memo on, 1: memo off, 2: per-fragment path (memo off with it)
  Context c(p.profile, p.width, p.height);
  if (mode == 1) c.set_vertex_run_memo(false);
  if (mode == 2) c.set_fast_paths(false);
  std::ostringstream out;
  Outcome o;
  o.result = run_program_on(c, p, {}, out);
  o.color = c.current_color();
  o.secondary = c.current_secondary_color();
  o.normal = c.current_normal();
  for (int u = 0; u < p.profile.texture_units; ++u) o.texcoord.push_back(c.current_texcoord(u));
  o.hits = c.vertex_run_memo().hits();
  o.misses = c.vertex_run_memo().misses();
  o.record_reads = c.run_record_reads();
  o.geometry_run_hits = c.geometry_memo().run_hits();
  return o;
}

void check_same(const Outcome& a, const Outcome& b) {
  check_same_run(a.result, b.result);
  CHECK(a.color == b.color);
  CHECK(a.secondary == b.secondary);
  CHECK(a.normal == b.normal);
  CHECK(a.texcoord == b.texcoord);
}

// The first lines of a test trace: 24x24 pixels, one unit per pixel.
std::string header(const std::string& profile = "") {
  return "ffsim-trace 1\n" + (profile.empty() ? "" : "profile " + profile + "\n") +
         "framebuffer 24 24\n"
         "glMatrixMode GL_PROJECTION\n"
         "glOrtho 0 24 0 24 -1 1\n"
         "glMatrixMode GL_MODELVIEW\n";
}

// Every unit of `units` textured (MODULATE) by a 4x1 RGBA table, from the last
// unit down (unit 0 active at the end), so that every coordinate shows.
std::string textured_units(int units) {
  std::string t = "table tex 4 x 1-x 0.25+0.5*x 1\n";
  for (int u = units - 1; u >= 0; --u) {
    t += "glActiveTexture GL_TEXTURE" + std::to_string(u) + "\n";
    t += "glBindTexture GL_TEXTURE_2D " + std::to_string(u + 1) + "\n";
    t += "glTexImage2D GL_TEXTURE_2D 0 GL_RGBA 4 1 0 GL_RGBA GL_FLOAT tex\n";
    t += "glTexParameteri GL_TEXTURE_2D GL_TEXTURE_MIN_FILTER GL_NEAREST\n";
    t += "glTexParameteri GL_TEXTURE_2D GL_TEXTURE_MAG_FILTER GL_LINEAR\n";
    t += "glEnable GL_TEXTURE_2D\n";
  }
  return t;
}

}  // namespace

TEST_CASE("vertex runs: equal calls share a class, the usage says what a replay compares, takes and fills") {
  // Run A: eight calls (lines 7-14 the first time); `last` is its last vertex's y.
  auto run_a = [](const char* last) {
    return std::string("glColor4d 1 0.5 0.25 1\n"
                       "glVertex2d 0 0\n"
                       "glMultiTexCoord2d GL_TEXTURE1 0 1\n"
                       "glVertex2d 8 0\n"
                       "glTexCoord2d 1 1\n"
                       "glNormal3d 0 1 0\n"
                       "glVertex2d 0 8\n"
                       "glVertex2d 8 ") + last + "\n";
  };
  const std::string t = header() +                                        // lines 1-5
                        "glBegin GL_TRIANGLE_STRIP\n" + run_a("8") +      // 6; 7-14: run A
                        "glEnd\n"                                         // 15
                        "glTexCoord2d 0 0\n"                              // 16: short runs are not memoized;
                        "glMultiTexCoord4d GL_TEXTURE1 0 0 0 1\n"         // 17  line 7's entry coordinates again
                        "glBegin GL_TRIANGLE_STRIP\n" + run_a("8") +      // 18; 19-26: run A again
                        "glEnd\n"                                         // 27
                        "glBegin GL_TRIANGLE_STRIP\n" +                   // 28; 29-36: run A but one coordinate bit
                        run_a("8.000000000000002") +
                        "glEnd\n"                                         // 37
                        "glBegin GL_TRIANGLE_STRIP\n" + run_a("8") +      // 38; 39-46: run A, entry coordinates (1, 1) and (0, 1)
                        "glEnd\n"                                         // 47
                        "hash color\n";
  const Program p = load_trace_text(t, "t.trace", {});
  const int first = 3;  // line 3 is step 0 (line 2, framebuffer, is set-up)
  REQUIRE(p.steps.at(static_cast<std::size_t>(7 - first)).name == "glColor4d");
  const std::uint32_t a = class_at(p, 7, first), b = class_at(p, 29, first);
  CHECK(a != 0);
  CHECK(class_at(p, 19, first) == a);
  CHECK(class_at(p, 39, first) == a);
  CHECK(b != 0);
  CHECK(b != a);
  CHECK(class_at(p, 8, first) == 0);  // (inside a run)
  CHECK(class_at(p, 16, first) == 0);
  CHECK(p.vertex_runs.size() == 2);
  CHECK(p.vertex_runs[0].id != p.vertex_runs[1].id);
  const VertexRunUsage& u = usage_of(p, a);
  CHECK(u.has_vertex);
  // Written: the colour, unit 1's and unit 0's coordinates, the normal.
  CHECK(u.written == (kAttribColor | texcoord_bit(1) | texcoord_bit(0) | kAttribNormal));
  // Read before written: unit 1's coordinates (line 8's vertex) and unit 0's
  // (lines 8 and 10); the colour is written first; the normal is no vertex's.
  CHECK(u.read_first == (texcoord_bit(1) | texcoord_bit(0)));
  // Another program's runs have other ids, even for the same text.
  const Program q = load_trace_text(t, "t.trace", {});
  CHECK(q.vertex_runs[0].id != p.vertex_runs[0].id);

  // Replays: run A is recorded at line 7 and replayed at line 19 (the same
  // entry coordinates); at line 39 unit 0's and unit 1's entry coordinates are
  // those line 29's run left: recorded again.
  const Outcome on = run(p, 0), off = run(p, 1), ref = run(p, 2);
  CHECK(on.misses == 3);  // lines 7, 29 (its own class), 39
  CHECK(on.hits == 1);    // line 19
  CHECK(off.hits + off.misses == 0);
  CHECK(ref.hits + ref.misses == 0);
  check_same(on, off);
  check_same(on, ref);
}

TEST_CASE("vertex runs: a replay compares the read-first attributes and the written units' texture matrices") {
  // One run (line 9) drawn five times; between the draws the state it depends
  // on changes or not.
  const std::string body =
      "glBegin GL_TRIANGLE_STRIP\n"
      "glVertex2d 0 0\n"                      // reads unit 0's entry coordinates (written below: compared)
      "glTexCoord2d 0.5 0.25\n"
      "glVertex2d 20 0\n"
      "glVertex2d 0 20\n"
      "glMultiTexCoord2d GL_TEXTURE1 1 0\n"  // unit 1: the vertices above read its entry value
      "glVertex2d 20 20\n"
      "glVertex2d 10 24\n"
      "glVertex2d 24 10\n"
      "glTexCoord2d 0 0\n"                      // the entry coordinates back (the next draw's entry)
      "glMultiTexCoord4d GL_TEXTURE1 0 0 0 1\n"
      "glEnd\n"
      "hash color\n";
  const std::string t = header() +
                        "glEnable GL_BLEND\nglBlendFunc GL_ONE GL_ONE\n"
                        "glColor4d 0.125 0 0 0\n" + body +     // record
                        body +                                 // hit: the same state
                        "glColor4d 0 0.125 0 0\n" + body +     // hit: colour is not written, filled from the current one
                        "glTexCoord2d 0.75 0\n" + body +       // miss: unit 0's entry coordinates differ
                        body +                                 // miss: they differ from that recording's
                        "glMatrixMode GL_TEXTURE\nglActiveTexture GL_TEXTURE1\nglScaled 2 2 1\n"
                        "glActiveTexture GL_TEXTURE0\nglMatrixMode GL_MODELVIEW\n" + body +  // miss: unit 1's matrix
                        body;                                  // hit
  const Program p = load_trace_text(t, "t.trace", {});
  REQUIRE(p.vertex_runs.size() == 1);
  const VertexRunUsage& u = p.vertex_runs[0].usage;
  CHECK(u.written == (texcoord_bit(0) | texcoord_bit(1)));
  CHECK(u.read_first == (texcoord_bit(0) | texcoord_bit(1)));
  const Outcome on = run(p, 0), off = run(p, 1), ref = run(p, 2);
  CHECK(on.misses == 4);
  CHECK(on.hits == 3);
  check_same(on, off);
  check_same(on, ref);
}

TEST_CASE("vertex runs: a replay's vertices are read from its record until something else needs them") {
  // Run R: unit 0's coordinates and the positions of a strip; the colours and
  // unit 1's coordinates are filled in from the current state.
  const std::string r =
      "glTexCoord2d 0.25 0\nglVertex2d 0 0\n"
      "glTexCoord2d 0.75 0\nglVertex2d 20 0\n"
      "glTexCoord2d 0.25 1\nglVertex2d 0 20\n"
      "glTexCoord2d 0.75 1\nglVertex2d 20 20\n"
      "glVertex2d 24 24\n";
  auto strip = [&](const std::string& before, const std::string& after) {  // (a hash ends a run)
    return "glBegin GL_TRIANGLE_STRIP\n" + before + (before.empty() ? "" : "hash alpha\n") + r +
           (after.empty() ? "" : "hash alpha\n") + after + "glEnd\nhash color\n";
  };
  const std::string t =
      header("geforce256") + textured_units(2) + "glEnable GL_BLEND\nglBlendFunc GL_ONE GL_ONE\n" +
      "glColor4d 0.25 0.5 0.125 1\n" + strip("", "") +  // R recorded; the geometry memo's entry made
      "glColor4d 0.5 0.25 0.75 1\nglMultiTexCoord2d GL_TEXTURE1 0.5 0.5\n" +
      strip("", "") +                     // replayed, read from the record: other colour, unit 1 filled
      strip("", "glVertex2d 5 22\n") +    // replayed, copied for the vertex after it
      strip("", r) +                      // replayed twice: the first copied for the second
      strip("", "glColor4d 1 0 0 1\n") +  // read from the record: the colour set after the run is no vertex's
      strip("glVertex2d 3 3\n", "");      // after a vertex: copied at once
  const Program p = load_trace_text(t, "t.trace", {});
  REQUIRE(p.vertex_runs.size() == 1);
  const Outcome on = run(p, 0), off = run(p, 1), ref = run(p, 2);
  CHECK(on.misses == 1);
  CHECK(on.hits == 6);
  CHECK(on.record_reads == 2);  // the second and the fifth glEnd
  CHECK(off.record_reads == 0);
  // The first glEnd, of the run just recorded, made the geometry memo's entry
  // from the record's positions (the run's vertices are all the glBegin's:
  // Context::vertex_run_record), so the second and the fifth glEnd, of that
  // record, take the entry without comparing positions.
  CHECK(on.geometry_run_hits == 2);
  CHECK(off.geometry_run_hits == 0);
  check_same(on, off);
  check_same(on, ref);
}

TEST_CASE("vertex runs: random traces of repeated runs == memo off == per-fragment path") {
  for (const char* profile : {"geforce256", "rgba12"}) {
    std::uint64_t hits = 0, misses = 0, reads = 0;
#ifdef FFSIM_SANITIZE
    for (std::uint32_t seed = 1; seed <= 4; ++seed) {
#else
    for (std::uint32_t seed = 1; seed <= 24; ++seed) {
#endif
      INFO("profile ", profile, " seed ", seed);
      SceneRng r(seed);
      const Profile& prof = profile_named(profile);
      const int units = prof.texture_units;
      auto num = [&](int lo, int hi) { return std::to_string(r.i(lo, hi)) + "/8"; };
      // Run templates: 8-24 quiet calls each.
      std::vector<std::string> templates;
      for (int k = 0; k < 4; ++k) {
        std::string s;
        if (k % 2 == 0)  // every unit's coordinates written first (not compared: replays more often)
          for (int u = 0; u < units; ++u) s += "glMultiTexCoord2d GL_TEXTURE" + std::to_string(u) + " " + num(0, 8) + " 1\n";
        const int calls = r.i(8, 24);
        for (int c = 0; c < calls; ++c) {
          switch (r.i(0, 9)) {
            case 0: s += "glColor4d " + num(-2, 10) + " " + num(0, 8) + " " + num(0, 8) + " " + num(0, 8) + "\n"; break;
            case 1: s += "glColor3f " + num(0, 8) + " " + num(-1, 9) + " " + num(0, 8) + "\n"; break;
            case 2: s += "glSecondaryColor3d " + num(0, 8) + " " + num(0, 8) + " " + num(0, 8) + "\n"; break;
            case 3: s += "glNormal3d 0 " + num(0, 8) + " 1\n"; break;
            case 4: s += "glTexCoord2d " + num(-4, 12) + " " + num(-4, 12) + "\n"; break;
            case 5:
              s += "glMultiTexCoord4d GL_TEXTURE" + std::to_string(r.i(0, units - 1)) + " " + num(-4, 12) + " " +
                   num(0, 8) + " 0 " + num(6, 10) + "\n";
              break;
            case 6:
              s += "glMultiTexCoord2d GL_TEXTURE" + std::to_string(r.i(0, units - 1)) + " " + num(-4, 12) + " " + num(-4, 12) + "\n";
              break;
            case 7: s += "glVertex3d " + std::to_string(r.i(0, 24)) + " " + std::to_string(r.i(0, 24)) + " 0\n"; break;
            default: s += "glVertex2d " + std::to_string(r.i(0, 24)) + " " + std::to_string(r.i(0, 24)) + "\n"; break;
          }
        }
        templates.push_back(s);
      }
      std::string t = header(profile) + textured_units(units) +
                      "glEnable GL_BLEND\nglBlendFunc GL_ONE GL_ONE\nglEnable GL_COLOR_SUM\n";
      const char* const modes[] = {"GL_TRIANGLE_STRIP", "GL_TRIANGLES", "GL_TRIANGLE_FAN", "GL_QUADS", "GL_POLYGON"};
      for (int k = 0; k < 40; ++k) {
        // State between runs.
        if (r.b(40)) t += "glColor4d " + num(0, 3) + " " + num(0, 3) + " " + num(0, 3) + " 1\n";
        if (r.b(25)) t += "glSecondaryColor3d " + num(0, 2) + " 0 " + num(0, 2) + "\n";
        if (r.b(25)) t += "glMultiTexCoord2d GL_TEXTURE" + std::to_string(r.i(0, units - 1)) + " " + num(0, 8) + " " + num(0, 8) + "\n";
        if (r.b(15)) {
          t += "glMatrixMode GL_TEXTURE\nglActiveTexture GL_TEXTURE" + std::to_string(r.i(0, units - 1)) + "\n";
          t += r.b(50) ? "glLoadIdentity\n" : "glTranslated " + num(-4, 4) + " 0 0\n";
          t += "glActiveTexture GL_TEXTURE0\nglMatrixMode GL_MODELVIEW\n";
        }
        const std::string& run = templates[static_cast<std::size_t>(r.i(0, 3))];
        if (r.b(20)) {
          t += run;  // outside glBegin/glEnd: the current values alone
        } else {
          t += std::string("glBegin ") + r.pick(modes) + "\n" + run;
          if (r.b(30)) t += "hash alpha\n" + templates[static_cast<std::size_t>(r.i(0, 3))];  // a second run after vertices
          t += "glEnd\nhash color\n";
        }
      }
      const Program p = load_trace_text(t, "random.trace", {});
      const Outcome on = run(p, 0), off = run(p, 1), ref = run(p, 2);
      hits += on.hits;
      misses += on.misses;
      reads += on.record_reads;
      check_same(on, off);
      check_same(on, ref);
    }
    CHECK(hits > 0);  // (both taken: about one replay to five recordings)
    CHECK(misses > 0);
    CHECK(reads > 0);  // (glEnds whose attributes were read from a record)
  }
}

TEST_CASE("vertex runs: the memo keeps at most kMaxVertices vertices, a record replaces its id's") {
  VertexRunMemo m;
  const std::size_t per_record = 1000;
  const std::vector<ClipVertex> vertices(VertexRunMemo::kMaxVertices / 2);
  std::size_t most = 0;
  for (std::uint64_t id = 1; id <= VertexRunMemo::kMaxVertices / per_record + 10; ++id) {
    // insert_drops: whether this insertion empties the memo (a new id: only at the bound).
    const std::size_t before = m.size();
    CHECK(m.insert_drops(id, per_record) == ((before + 1) * per_record > VertexRunMemo::kMaxVertices));
    CHECK(m.insert(id, vertices.data(), per_record).vertices.size() == per_record);
    most = std::max(most, m.size());
    CHECK(m.find(id) != nullptr);
  }
  CHECK(most * per_record <= VertexRunMemo::kMaxVertices);
  CHECK(m.size() < most);  // emptied once
  // Recording an id again replaces its record and its count.
  VertexRunMemo r;
  CHECK_FALSE(r.insert_drops(7, vertices.size()));
  for (int k = 0; k < 3; ++k) r.insert(7, vertices.data(), vertices.size());
  CHECK(r.insert_drops(7, 1));  // (replaces 7's record)
  CHECK(r.size() == 1);
  CHECK_FALSE(r.insert_drops(8, vertices.size()));
  r.insert(8, vertices.data(), vertices.size());
  CHECK(r.size() == 2);  // (7's half and 8's half: within the bound, nothing emptied)
  CHECK(r.find(7) != nullptr);
  CHECK(r.insert_drops(9, 1));
  r.insert(9, vertices.data(), 1);
  CHECK(r.size() == 1);  // one vertex more than the bound: emptied first
  CHECK(r.find(9) != nullptr);
  // Serials name records: never 0, new for a replacing record and after clear().
  const std::uint64_t s9 = r.find(9)->serial;
  CHECK(s9 > 0);
  CHECK(r.insert(9, vertices.data(), 1).serial > s9);
  const std::uint64_t again = r.find(9)->serial;
  r.clear();
  CHECK(r.insert(9, vertices.data(), 1).serial > again);
}

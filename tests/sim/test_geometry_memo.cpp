// The geometry memo (sim/geometry_memo.h, docs/performance.md 18.1): a glEnd
// whose object positions, primitive and transformation equal an earlier one's
// takes that one's window positions and depth codes, and the raster cache keys
// it by the memo's serial. The buffers must be exactly those of the same calls
// with the memo off and of the per-fragment reference, and the memo must miss
// whenever anything its key holds differs, by as little as one ulp or the sign
// of a zero.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "draw_test_util.h"
#include "fast_scene.h"

using namespace ffsim;
using namespace ffsim::test;

namespace {

constexpr int kW = 96, kH = 64;

// Perspective as in random_projection (w_c differs from 1 and from vertex to
// vertex): the window spans object x in [0, kW], y in [0, kH] at z = 0.
void perspective(Context& c, double far) {
  c.matrixMode(gl::PROJECTION);
  c.loadIdentity();
  c.frustum(-0.5, 0.5, -0.5, 0.5, 1, far);
  c.matrixMode(gl::MODELVIEW);
  c.loadIdentity();
  c.translate(0, 0, -2);
  c.scale(2.0 / kW, 2.0 / kH, 1);
  c.translate(-kW / 2.0, -kH / 2.0, 0);
}

void textured_additive(Context& c) {
  std::vector<std::uint8_t> texels(4 * 4 * 4);
  for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = static_cast<std::uint8_t>(29 * i + 3);
  c.bindTexture(gl::TEXTURE_2D, 1);
  c.texImage2D(gl::TEXTURE_2D, 0, gl::RGBA8, 4, 4, 0, gl::RGBA, gl::UNSIGNED_BYTE, texels.data());
  c.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MIN_FILTER, gl::LINEAR);
  c.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MAG_FILTER, gl::LINEAR);
  c.texEnvi(gl::TEXTURE_ENV, gl::TEXTURE_ENV_MODE, gl::MODULATE);
  c.enable(gl::TEXTURE_2D);
  c.enable(gl::BLEND);
  c.blendFunc(gl::ONE, gl::ONE);  // every draw leaves its trace
  c.enable(gl::DEPTH_TEST);
  c.depthFunc(gl::ALWAYS);
  c.color4(0.1, 0.07, 0.05, 0.1);
}

struct Strip {
  GLenum mode = gl::TRIANGLE_STRIP;
  int nudged = -1;           // this vertex's x one ulp up
  bool negative_zero = false;  // z = -0 where it is +0
  double far_x = 0;          // vertex 0's x (0: in the window; large: outside the view volume)
};

void draw_strip(Context& c, const Strip& s) {
  c.begin(s.mode);
  for (int i = 0; i <= 6; ++i)
    for (int j : {1, 0}) {
      const int k = 2 * i + (1 - j);
      double x = 4 + 14.5 * i, y = 6 + 50.0 * j, z = (i % 3 == 0) ? 0.0 : 0.1 * (i - 3) + 0.01 * j;
      if (k == s.nudged) x = std::nextafter(x, 1e9);
      if (s.negative_zero && z == 0.0) z = -0.0;
      if (k == 0 && s.far_x != 0) x = s.far_x;
      c.texCoord2(i / 6.0, j);
      c.vertex3(x, y, z);
    }
  c.end();
}

}  // namespace

TEST_CASE("geometry memo: a glEnd takes an earlier one's window positions only under the same key") {
  const Profile& p = profile_named("geforce256");
  Context on(p, kW, kH), off(p, kW, kH), ref(p, kW, kH);
  off.set_geometry_memo(false);
  ref.set_fast_paths(false);
  std::vector<Context*> all{&on, &off, &ref};
  for (Context* c : all) {
    perspective(*c, 10);
    textured_additive(*c);
  }
  std::uint64_t hits = 0, misses = 0;
  // Draws `s` in the three contexts and checks the memo's counters moved by
  // (h, m) and the buffers agree.
  auto step = [&](const char* what, const Strip& s, int h, int m) {
    INFO(what);
    for (Context* c : all) draw_strip(*c, s);
    hits += static_cast<std::uint64_t>(h);
    misses += static_cast<std::uint64_t>(m);
    CHECK(on.geometry_memo().hits() == hits);
    CHECK(on.geometry_memo().misses() == misses);
    CHECK(buffer_hashes(on) == buffer_hashes(off));
    CHECK(buffer_hashes(on) == buffer_hashes(ref));
  };
  auto each = [&](auto f) {
    for (Context* c : all) f(*c);
  };
  step("first", {}, 0, 1);
  const std::uint64_t raster_hits = on.raster_cache().hits();
  step("the same again", {}, 1, 0);
  CHECK(on.raster_cache().hits() == raster_hits + 1);  // keyed by the serial
  step("one x one ulp up", {gl::TRIANGLE_STRIP, 5}, 0, 1);
  step("z = -0 for +0", {gl::TRIANGLE_STRIP, -1, true}, 0, 1);
  step("the first again", {}, 1, 0);
  each([](Context& c) { c.pushMatrix(), c.translate(0, 0, 1e-9); });
  step("modelview moved by 1e-9", {}, 0, 1);
  each([](Context& c) { c.popMatrix(); });
  step("modelview back", {}, 1, 0);
  each([](Context& c) { perspective(c, 11); });
  step("another far plane", {}, 0, 1);
  each([](Context& c) { perspective(c, 10); });
  step("projection back", {}, 1, 0);
  each([](Context& c) { c.viewport(0, 0, kW - 2, kH); });
  step("another viewport width", {}, 0, 1);
  each([](Context& c) { c.viewport(0, 0, kW, kH - 1); });
  step("another viewport height", {}, 0, 1);
  each([](Context& c) { c.viewport(3, 2, kW, kH); });
  step("the viewport's corner moved (window positions are relative to it)", {}, 1, 0);
  each([](Context& c) { c.viewport(0, 0, kW, kH); });
  step("viewport back", {}, 1, 0);
  each([](Context& c) { c.depthRange(0, 0.5); });
  step("another depth range", {}, 0, 1);
  each([](Context& c) { c.depthRange(0.25, 1); });
  step("another near value", {}, 0, 1);
  each([](Context& c) { c.depthRange(0, 1); });
  step("depth range back", {}, 1, 0);
  step("QUAD_STRIP of the same vertices", {gl::QUAD_STRIP}, 0, 1);
  step("TRIANGLE_STRIP again", {}, 1, 0);
  step("a vertex outside the view volume (clipped: not kept)", {gl::TRIANGLE_STRIP, -1, false, -500}, 0, 1);
  step("the same: still not kept", {gl::TRIANGLE_STRIP, -1, false, -500}, 0, 1);
  each([](Context& c) { c.shadeModel(gl::FLAT); });
  step("flat shading does not use the memo", {}, 0, 0);
  each([](Context& c) { c.shadeModel(gl::SMOOTH); });
  on.set_geometry_memo(false);
  CHECK(on.geometry_memo().size() == 0);
  step("memo off", {}, 0, 0);
  on.set_geometry_memo(true);
  step("memo on again: emptied", {}, 0, 1);
  step("and kept", {}, 1, 0);
  CHECK(off.geometry_memo().hits() + off.geometry_memo().misses() == 0);
  CHECK(ref.geometry_memo().hits() + ref.geometry_memo().misses() == 0);
}

TEST_CASE("geometry memo: a framebuffer without depth keeps no depth codes, and the memo stays within its bound") {
  Profile p = profile_named("geforce256");
  p.depth_bits = 0;
  Context on(p, kW, kH), off(p, kW, kH);
  off.set_geometry_memo(false);
  for (Context* c : {&on, &off}) {
    perspective(*c, 10);
    textured_additive(*c);
    for (int k = 0; k < 3; ++k) draw_strip(*c, {});
  }
  CHECK(on.geometry_memo().hits() == 2);
  CHECK(buffer_hash(on.framebuffer(), BufferKind::Color) == buffer_hash(off.framebuffer(), BufferKind::Color));
  // Distinct strips until the vertex bound empties the memo: it never holds more.
  Context big(profile_named("geforce256"), kW, kH);
  perspective(big, 10);
  const std::size_t per_strip = 14, strips = GeometryMemo::kMaxVertices / per_strip + 10;
  std::size_t most = 0;
  for (std::size_t k = 0; k < strips; ++k) {
    draw_strip(big, {gl::TRIANGLE_STRIP, static_cast<int>(k % 14), false, k < 14 ? 0 : 1.0 + 1e-6 * static_cast<double>(k)});
    most = std::max(most, big.geometry_memo().size());
  }
  CHECK(most * per_strip <= GeometryMemo::kMaxVertices);
  CHECK(big.geometry_memo().size() < most);  // emptied once
}

TEST_CASE("geometry memo: random multipass scenes with moving transformations == memo off == per-fragment path") {
  std::uint64_t hits = 0, misses = 0, batch_memo = 0;
  for (const char* profile : {"geforce256", "rgba12"})
    for (int threads : {1, 2})
#ifdef FFSIM_SANITIZE
      for (std::uint32_t seed = 40; seed < 42; ++seed) {
#else
      for (std::uint32_t seed = 40; seed < 48; ++seed) {
#endif
        INFO("profile ", std::string(profile), " threads ", threads, " seed ", seed);
        Context on(profile_named(profile), kW, kH), off(profile_named(profile), kW, kH), ref(profile_named(profile), kW, kH);
        off.set_geometry_memo(false);
        ref.set_fast_paths(false);
        for (Context* c : {&on, &off, &ref}) {
          c->set_threads(threads);
          SceneRng r(seed);
          random_clear_and_projection(*c, r, 0.3);
          // A mesh of strips with per-vertex depth and coordinates, drawn in
          // passes; between passes the transformation, viewport or depth range
          // may change (and change back), or one vertex move by an ulp.
          const int cols = r.i(4, 9), rows = r.i(2, 5);
          std::vector<std::array<double, 3>> grid;
          for (int j = 0; j <= rows; ++j)
            for (int i = 0; i <= cols; ++i)
              grid.push_back({3 + i * (kW - 6.0) / cols + r.d(-1, 1), 3 + j * (kH - 6.0) / rows + r.d(-1, 1),
                              r.d(-0.5, 0)});  // (inside the view volume of either projection, moved or not)
          for (int pass = 0; pass < 6; ++pass) {
            c->flush_deferred();
            random_texture_or_off(*c, r, 0, static_cast<std::uint32_t>(1 + pass), 70);
            random_fragment_ops(*c, r);
            const int change = r.i(0, 9);
            if (change == 0) c->translate(r.d(-0.9, 0.9), 0, 0);  // (one pass in ten)
            if (change == 1) c->viewport(r.i(-3, 3), r.i(-3, 3), kW + r.i(-4, 4), kH + r.i(-4, 4));
            if (change == 2) c->viewport(0, 0, kW, kH);
            if (change == 3) c->depthRange(r.d(0, 0.3), r.d(0.7, 1));
            if (change == 4) grid[static_cast<std::size_t>(r.i(0, static_cast<int>(grid.size()) - 1))][0] += 1e-12;
            // The viewport's corner alone: the memo's key (its size) is unchanged,
            // but the window relative to the corner moves, and with it the
            // triangles a batch keeps (the batch memo holds for one window).
            if (change == 5 || change == 6) c->viewport(r.i(-40, 40), r.i(-30, 30), kW, kH);
            if (change == 7) c->viewport(0, 0, kW, kH);
            const GLenum mode = r.b(80) ? gl::TRIANGLE_STRIP : gl::QUAD_STRIP;
            for (int j = 0; j < rows; ++j) {
              c->begin(mode);
              for (int i = 0; i <= cols; ++i)
                for (int dj : {1, 0}) {
                  const auto& g = grid[static_cast<std::size_t>((j + dj) * (cols + 1) + i)];
                  c->color4(r.d(0, 1), r.d(0, 1), r.d(0, 1), r.d(0, 1));
                  c->multiTexCoord2(gl::TEXTURE0, g[0] / kW, g[1] / kH);
                  c->vertex3(g[0], g[1], g[2]);
                }
              c->end();
            }
          }
          c->flush_deferred();
        }
        REQUIRE(buffer_hashes(on) == buffer_hashes(off));
        REQUIRE(buffer_hashes(on) == buffer_hashes(ref));
        CHECK(on.fragments_written() == off.fragments_written());
        hits += on.geometry_memo().hits();
        misses += on.geometry_memo().misses();
        batch_memo += on.batch_memo_uses();
        if (threads == 1) CHECK(on.batch_memo_uses() == 0);  // (no batches on one thread)
        CHECK(off.batch_memo_uses() == 0);
      }
  MESSAGE("memo hits " << hits << ", misses " << misses << ", batch memo uses " << batch_memo);
  CHECK(hits > 0);
  CHECK(misses > 0);
  CHECK(batch_memo > 0);
}

TEST_CASE("geometry memo: texture units past the profile's hold (0, 0, 0, 1)") {
  // vertex_attributes computes the profile's units only; the others keep the
  // product of their untouched current coordinates and identity matrices.
  Context c(profile_named("geforce256"), kW, kH);  // 2 units
  REQUIRE(c.profile().texture_units == 2);
  ortho_window(c);
  c.multiTexCoord4(gl::TEXTURE1, 0.5, 0.25, 0.125, 2);
  c.rasterPos2(3, 4);
  REQUIRE(c.raster_pos().valid);
  CHECK(c.raster_pos().texcoord[1] == std::array<double, 4>{0.5, 0.25, 0.125, 2});
  for (int u = 2; u < kMaxTextureUnits; ++u) CHECK(c.raster_pos().texcoord[static_cast<std::size_t>(u)] == std::array<double, 4>{0, 0, 0, 1});
}

TEST_CASE("geometry memo: keys are compared whole, field by field and bit for bit") {
  // Every hash collides (0 bits kept): only the comparison tells keys apart.
  GeometryMemo memo(0);
  GeometryKey base;
  base.mode = gl::TRIANGLE_STRIP;
  base.modelview = glm::dmat4(2.0);
  base.projection = glm::dmat4(0.5);
  base.hw = 48;
  base.hh = 32;
  base.depth_near = 0.25;
  base.depth_far = 0.75;
  base.subpixel_bits = 4;
  base.depth_bits = 24;
  const std::vector<glm::dvec4> pos{{1, 2, 0, 1}, {3, 4, 0.5, 1}, {5, 6, -0.5, 1}};
  auto at = [](const std::vector<glm::dvec4>& v) {
    return [&v](std::size_t i) -> const glm::dvec4& { return v[i]; };
  };
  GeometryEntry& e = memo.insert(base, pos.size(), at(pos));
  const std::uint64_t serial = e.serial;
  CHECK(serial > 0);
  REQUIRE(memo.find(base, pos.size(), at(pos)) == &e);
  std::vector<GeometryKey> other(11, base);
  other[0].mode = gl::QUAD_STRIP;
  other[1].modelview[3][0] = 1e-300;
  other[2].projection[2][3] = -0.0;  // (+0 in base: the bits differ)
  other[3].hw = 48.5;
  other[4].hh = std::nextafter(32.0, 0.0);
  other[5].depth_near = 0;
  other[6].depth_far = 1;
  other[7].subpixel_bits = 8;
  other[8].depth_bits = 0;
  other[9].modelview[0][0] = -other[9].modelview[0][0];
  other[10].projection[3][3] = 1;
  for (std::size_t k = 0; k < other.size(); ++k) {
    INFO("field change ", k);
    CHECK(memo.find(other[k], pos.size(), at(pos)) == nullptr);
  }
  std::vector<std::vector<glm::dvec4>> moved(4, pos);
  moved[0][0].x = std::nextafter(1.0, 2.0);
  moved[1][2].z = -0.5000000000000001;
  moved[2][1].w = 1.0000000000000002;
  moved[3].pop_back();  // a prefix
  for (std::size_t k = 0; k < moved.size(); ++k) {
    INFO("position change ", k);
    CHECK(memo.find(base, moved[k].size(), at(moved[k])) == nullptr);
  }
  // Inserting a colliding key replaces the entry; its serial is new.
  GeometryEntry& f = memo.insert(other[0], pos.size(), at(pos));
  CHECK(f.serial > serial);
  CHECK(memo.size() == 1);
  CHECK(memo.find(base, pos.size(), at(pos)) == nullptr);
  CHECK(memo.find(other[0], pos.size(), at(pos)) == &f);
  const std::uint64_t last = f.serial;
  memo.clear();
  CHECK(memo.size() == 0);
  CHECK(memo.find(other[0], pos.size(), at(pos)) == nullptr);
  CHECK(memo.insert(base, pos.size(), at(pos)).serial > last);  // serials are never reused
}

TEST_CASE("geometry memo: a vertex-run record's positions are compared with an entry once, the key always") {
  // Every hash collides (0 bits kept): only the comparisons tell entries apart.
  GeometryMemo memo(0);
  GeometryKey key;
  key.mode = gl::TRIANGLE_STRIP;
  key.hw = 32;
  key.hh = 16;
  const std::vector<glm::dvec4> pos{{1, 2, 0, 1}, {3, 4, 0.5, 1}, {5, 6, -0.5, 1}};
  std::vector<glm::dvec4> moved = pos;
  moved[1].y = std::nextafter(4.0, 5.0);
  auto at = [](const std::vector<glm::dvec4>& v) {
    return [&v](std::size_t i) -> const glm::dvec4& { return v[i]; };
  };
  const std::uint64_t ph = GeometryMemo::positions_hash(pos.size(), at(pos));
  GeometryEntry& e = memo.insert(key, pos.size(), ph, at(pos));
  CHECK(e.same_run == 0);
  REQUIRE(memo.find(key, pos.size(), ph, at(pos), 5) == &e);  // compared, then named by run 5
  CHECK(memo.run_hits() == 0);
  CHECK(e.same_run == 5);
  CHECK(memo.find(key, pos.size(), ph, at(pos), 5) == &e);  // not compared
  CHECK(memo.run_hits() == 1);
  CHECK(memo.find(key, moved.size(), ph, at(moved), 6) == nullptr);  // another run: compared
  CHECK(e.same_run == 5);
  GeometryKey other = key;
  other.hw = 33;
  CHECK(memo.find(other, pos.size(), ph, at(pos), 5) == nullptr);  // the key is compared whatever the run
  CHECK(memo.find(key, pos.size(), ph, at(pos)) == &e);             // no run: compared
  CHECK(memo.run_hits() == 1);
  // A replacing entry is named by no run until compared (or made from one).
  GeometryEntry& f = memo.insert(key, moved.size(), ph, at(moved));
  CHECK(f.same_run == 0);
  CHECK(memo.find(key, pos.size(), ph, at(pos), 5) == nullptr);
  CHECK(memo.run_hits() == 1);
  CHECK(memo.hits() == 3);
}

TEST_CASE("geometry memo: a glEnd at one window point is skipped whole, zero-area triangles are left out, == memo off == "
          "per-fragment path at 1 and 2 threads") {
  // The paper traces' polygon scene draws the terrain scaled by 0: every vertex
  // at one window point, no triangle with area. On a memo hit such a glEnd is
  // skipped whole (GeometryEntry::one_point); elsewhere triangles of zero snapped
  // area are left out of the batch and the sequence (triangle_never_covers). The
  // buffers must stay those of the memo off and of the per-fragment path.
  const Profile& p = profile_named("geforce256");
  Context on(p, kW, kH), off(p, kW, kH), ref(p, kW, kH), two(p, kW, kH);
  off.set_geometry_memo(false);
  ref.set_fast_paths(false);
  two.set_threads(2);
  two.set_split_fragments(64);  // every glEnd's batch in bands
  std::vector<Context*> all{&on, &off, &ref, &two};
  for (Context* c : all) {
    perspective(*c, 10);
    textured_additive(*c);
  }
  // The strip scaled to the point (px, py, 0) of object space.
  auto to_point = [](Context& c, double px, double py) {
    c.pushMatrix();
    c.translate(px, py, 0);
    c.scale(0, 0, 0);
    draw_strip(c, {});
    c.popMatrix();
  };
  // A fan whose middle triangles are collinear with its centre (zero area), and
  // whose others are not.
  auto fan = [](Context& c) {
    c.begin(gl::TRIANGLE_FAN);
    const double pts[][2] = {{48, 32}, {80, 32}, {88, 32}, {94, 32}, {80, 60}, {40, 60}, {20, 10}, {20, 10}, {60, 4}};
    for (const auto& q : pts) {
      c.texCoord2(q[0] / kW, q[1] / kH);
      c.vertex3(q[0], q[1], 0);
    }
    c.end();
  };
  auto same = [&](const char* what) {
    INFO(what);
    CHECK(buffer_hashes(on) == buffer_hashes(off));
    CHECK(buffer_hashes(on) == buffer_hashes(ref));
    CHECK(buffer_hashes(on) == buffer_hashes(two));
  };
  for (Context* c : all) draw_strip(*c, {});
  same("a strip");
  for (Context* c : all) to_point(*c, 30.5, 20.5);  // a miss: window form computed, its triangles left out
  same("the strip at one point, first");
  CHECK(on.one_point_draws() == 0);
  for (int k = 0; k < 3; ++k)
    for (Context* c : all) to_point(*c, 30.5, 20.5);  // hits: skipped whole
  same("the strip at one point, again");
  CHECK(on.one_point_draws() == 3);
  CHECK(two.one_point_draws() == 3);
  CHECK(off.one_point_draws() == 0);
  CHECK(ref.one_point_draws() == 0);
  for (Context* c : all) to_point(*c, 31.25, 20.75);  // another point: another key, a miss
  CHECK(on.one_point_draws() == 3);
  for (Context* c : all) fan(*c);
  same("a fan with zero-area triangles");
  for (Context* c : all) fan(*c);  // a memo hit with triangles of zero area (not one point)
  same("the fan again");
  CHECK(on.one_point_draws() == 3);
  for (Context* c : all) draw_strip(*c, {});
  same("the strip after them");
}

TEST_CASE("geometry memo: rebase_triangles adds base to each triangle's three indices and copies its rows, any count") {
  // Against the word-by-word definition: counts 0 .. 41 (the eight-triangle
  // blocks, and every tail), bases that wrap around 2^32, rows of any sign;
  // nothing past the n triangles is written.
  SceneRng r(4242);
  for (const std::uint32_t base : {0u, 1u, 123457u, 0xFFFFFFF0u})
    for (std::size_t n = 0; n <= 41; ++n) {
      // (the triangles as their words: two sentinel triangles past the n)
      std::vector<std::uint32_t> in(5 * n), out(5 * n + 10, 0xABABABABu);
      for (std::uint32_t& w : in) w = static_cast<std::uint32_t>(r.i(0, 0x7FFFFFFF)) * 2u + (r.b(50) ? 1u : 0u);
      std::vector<BatchMemo::Triangle> tin(n), tout(n + 2);
      if (n > 0) std::memcpy(tin.data(), in.data(), 4 * in.size());
      std::memcpy(tout.data(), out.data(), 4 * out.size());
      rebase_triangles(tin.data(), n, base, tout.data());
      std::memcpy(out.data(), tout.data(), 4 * out.size());
      INFO("base ", base, " n ", n);
      for (std::size_t w = 0; w < 5 * n; ++w) {
        const std::uint32_t want = w % 5 < 3 ? static_cast<std::uint32_t>(base + in[w]) : in[w];
        REQUIRE(out[w] == want);
      }
      for (std::size_t w = 5 * n; w < out.size(); ++w) REQUIRE(out[w] == 0xABABABABu);
    }
}

TEST_CASE("geometry memo: insert_drops says whether an insertion drops an entry (a replaced hash, the bound's emptying)") {
  // Every hash collides (0 bits kept): a second key replaces the first.
  GeometryMemo colliding(0);
  GeometryKey a, b;
  a.mode = b.mode = gl::TRIANGLE_STRIP;
  b.hw = 2;
  const std::vector<glm::dvec4> pos{{1, 2, 0, 1}, {3, 4, 0.5, 1}, {5, 6, -0.5, 1}};
  auto at = [&pos](std::size_t i) -> const glm::dvec4& { return pos[i]; };
  const std::uint64_t ph = GeometryMemo::positions_hash(pos.size(), at);
  CHECK_FALSE(colliding.insert_drops(a, pos.size(), ph));  // (empty)
  colliding.insert(a, pos.size(), ph, at);
  CHECK(colliding.insert_drops(b, pos.size(), ph));
  colliding.insert(b, pos.size(), ph, at);
  CHECK(colliding.size() == 1);  // it did drop a's entry
  CHECK(colliding.find(a, pos.size(), ph, at) == nullptr);
  // Full hashes: distinct keys coexist until the vertex bound, whose next
  // insertion empties the memo.
  GeometryMemo memo;
  std::size_t held = 0;
  bool dropped = false;
  for (int k = 0; k <= static_cast<int>(GeometryMemo::kMaxVertices / pos.size()) && !dropped; ++k) {
    GeometryKey key = a;
    key.hw = 1 + k;
    const bool drops = memo.insert_drops(key, pos.size(), ph);
    const std::size_t before = memo.size();
    memo.insert(key, pos.size(), ph, at);
    CHECK(drops == (memo.size() <= before));
    if (drops) {
      CHECK(memo.size() == 1);  // emptied, then this one
      CHECK((held + 1) * pos.size() > GeometryMemo::kMaxVertices);
      dropped = true;
    }
    held = memo.size();
  }
  CHECK(dropped);  // (the bound's insertion is within the loop)
}

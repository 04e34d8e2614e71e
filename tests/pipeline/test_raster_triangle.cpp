// Rasterization: pixel-centre rule, top-left tie rule, sub-pixel snapping
// (pipeline/raster/triangle.h). Every expectation is derived by hand from the
// rule "centre inside, or on a left or top edge" on the 1/16-pixel grid.
#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <random>
#include <vector>
#include <map>
#include <set>

#include "pipeline/raster/triangle.h"

using namespace ffsim;

namespace {

constexpr int S = 4;

SnappedVertex sv(double x, double y) { return {snap_coordinate(x, S), snap_coordinate(y, S)}; }

std::map<std::pair<int, int>, int> cover(const std::array<SnappedVertex, 3>& t, std::map<std::pair<int, int>, int> acc = {}) {
  rasterize_triangle(t, S, -100, -100, 100, 100, [&](const TriangleCoverage& cov, const CoverageRun& run) {
    for (std::size_t i = 0; i < run.weight.size(); ++i) {
      ++acc[{run.x0 + static_cast<int>(i), run.y}];
      const auto& w = run.weight[i];
      CHECK(w[0] >= 0);
      CHECK(w[1] >= 0);
      CHECK(w[2] >= 0);
      CHECK(w[0] + w[1] + w[2] == cov.area);  // barycentric numerators sum to the area
    }
  });
  return acc;
}

}  // namespace

TEST_CASE("raster: snapping rounds to the nearest 1/16 pixel, ties up") {
  CHECK(snap_coordinate(1.03, 4) == 16);      // 16.48 -> 16
  CHECK(snap_coordinate(1.03125, 4) == 17);   // 16.5 exactly -> 17 (half up)
  CHECK(snap_coordinate(-1.03125, 4) == -16); // -16.5 -> -16 (half up)
  CHECK(snap_coordinate(std::nan(""), 4) > kMaxSnapped);  // NaN is out of range: rejected
}

TEST_CASE("raster: snapping is floor(ldexp(v, S) + 1/2) for every S, value and special case") {
  // The rule of triangle.h computed independently (std::ldexp), against
  // snap_coordinate's exact power-of-two multiplication.
  auto rule = [](double v, int S) {
    const double s = std::floor(std::ldexp(v, S) + 0.5);
    if (!(s > -static_cast<double>(kMaxSnapped) * 4 && s < static_cast<double>(kMaxSnapped) * 4))
      return s < 0 ? -kMaxSnapped * 4 : kMaxSnapped * 4;
    return static_cast<std::int64_t>(s);
  };
  std::mt19937_64 rng(31);
  std::vector<double> values = {0.0, -0.0, 0.5, -0.5, 1e-320, -1e-320, 1e300, -1e300, std::nan(""),
                                INFINITY, -INFINITY, 0x1p27, -0x1p27, 0x1p28 - 0.5, 1.0 / 3};
  for (int i = 0; i < 20000; ++i) {
    const double mag = std::ldexp(1.0, static_cast<int>(rng() % 80) - 40);
    values.push_back((static_cast<double>(rng() % 2000001) / 1e6 - 1.0) * mag);  // both signs, ties included
    values.push_back(std::bit_cast<double>(rng()));                               // any bit pattern
  }
  for (int S = 0; S <= 20; ++S)
    for (const double v : values) {
      CAPTURE(S);
      CAPTURE(v);
      REQUIRE(snap_coordinate(v, S) == rule(v, S));
    }
}

TEST_CASE("raster: a 2x2 square on integer corners covers exactly its four pixels") {
  // Square (1,1)-(3,3): centres 1.5, 2.5 are strictly inside; 0.5 and 3.5 outside.
  auto c = cover({sv(1, 1), sv(3, 1), sv(3, 3)});
  c = cover({sv(1, 1), sv(3, 3), sv(1, 3)}, c);
  CHECK(c.size() == 4);
  for (int y = 1; y <= 2; ++y)
    for (int x = 1; x <= 2; ++x) CHECK(c[{x, y}] == 1);
}

TEST_CASE("raster: centres on edges follow the left/top rule") {
  // Square (0.5,0.5)-(2.5,2.5): centre columns 0.5 (left edge: in), 1.5, 2.5 (right
  // edge: out); centre rows 0.5 (bottom edge: out), 1.5, 2.5 (top edge: in).
  auto c = cover({sv(0.5, 0.5), sv(2.5, 0.5), sv(2.5, 2.5)});
  c = cover({sv(0.5, 0.5), sv(2.5, 2.5), sv(0.5, 2.5)}, c);
  std::set<std::pair<int, int>> got;
  for (auto& [p, n] : c) {
    CHECK(n == 1);  // the diagonal through centres (1.5,1.5) is shared: drawn once
    got.insert(p);
  }
  const std::set<std::pair<int, int>> want{{0, 1}, {1, 1}, {0, 2}, {1, 2}};
  CHECK(got == want);
}

TEST_CASE("raster: clockwise and counter-clockwise triangles cover the same pixels") {
  const auto a = cover({sv(0.3, 0.2), sv(7.7, 1.9), sv(2.5, 6.5)});
  const auto b = cover({sv(0.3, 0.2), sv(2.5, 6.5), sv(7.7, 1.9)});
  CHECK(a == b);
  CHECK(!a.empty());
}

TEST_CASE("raster: a fan around a point covers every pixel of the polygon exactly once") {
  // 12 triangles around (8.5, 8.5), a pixel centre, with rim vertices on a circle of
  // radius 6.3 (some rim vertices and edges pass through centres after snapping).
  // Expected: no pixel twice; every pixel whose centre is strictly inside the rim
  // polygon (tested independently with the float cross products) covered.
  const double cx = 8.5, cy = 8.5;
  std::vector<SnappedVertex> rim;
  for (int i = 0; i < 12; ++i) {
    const double a = 2 * 3.14159265358979323846 * i / 12;
    rim.push_back(sv(cx + 6.3 * std::cos(a), cy + 6.3 * std::sin(a)));
  }
  std::map<std::pair<int, int>, int> c;
  for (int i = 0; i < 12; ++i) c = cover({sv(cx, cy), rim[i], rim[(i + 1) % 12]}, c);
  for (auto& [p, n] : c) CHECK_MESSAGE(n == 1, "pixel " << p.first << "," << p.second << " drawn " << n << " times");
  int inside = 0;
  for (int y = 0; y < 18; ++y)
    for (int x = 0; x < 18; ++x) {
      const double px = (x + 0.5) * 16, py = (y + 0.5) * 16;
      bool strictly = true;
      for (int i = 0; i < 12; ++i) {
        const SnappedVertex &a = rim[i], &b = rim[(i + 1) % 12];
        const double e = static_cast<double>(b.x - a.x) * (py - a.y) - static_cast<double>(b.y - a.y) * (px - a.x);
        if (e <= 0) strictly = false;
      }
      if (strictly) {
        ++inside;
        CHECK_MESSAGE(c.count({x, y}) == 1, "missing pixel " << x << "," << y);
      }
    }
  CHECK(inside > 100);  // pi * 6.3^2 ~ 125 pixels
  // The centre pixel (8, 8) has its centre on all 12 spokes: exactly one owner.
  CHECK(c[{8, 8}] == 1);
}

TEST_CASE("raster: degenerate and tiny triangles produce no fragments") {
  CHECK(cover({sv(1, 1), sv(5, 5), sv(3, 3)}).empty());  // collinear: area 0
  CHECK(cover({sv(2, 2), sv(2, 2), sv(2, 2)}).empty());  // a point
  // A sliver between centres: (0.6,0.6)-(1.4,0.6)-(1,1.4) contains no centre x+0.5.
  CHECK(cover({sv(0.6, 0.6), sv(1.4, 0.6), sv(1.0, 1.4)}).empty());
  // Snapping: 0.51 -> 8/16 exactly, so the vertex (0.51,0.51) of this tiny triangle
  // lands on the centre (0.5,0.5), which lies on its left edge: one fragment.
  const auto c = cover({sv(0.51, 0.51), sv(0.9, 0.2), sv(0.9, 0.9)});
  CHECK(c.size() == 1);
}

TEST_CASE("raster: triangle_never_covers holds exactly for the triangles that set up nothing") {
  // Callers leave out a triangle that triangle_never_covers names (sim/draw.cpp,
  // sim/draw_replay.cpp): it must make no fragment, and every other triangle must
  // be set up (area != 0). Random triangles on a small grid, a third of them made
  // degenerate on purpose (a repeated vertex, or c = a + k (b - a)), some with a
  // vertex beyond the snapped range.
  std::mt19937 rng(20261206);
  std::uniform_int_distribution<std::int64_t> coord(-40, 40), kind(0, 9), mult(-3, 3);
  int never = 0, set_up = 0;
  for (int i = 0; i < 20000; ++i) {
    std::array<SnappedVertex, 3> t{};
    for (SnappedVertex& v : t) v = {coord(rng), coord(rng)};
    const auto k = kind(rng);
    if (k == 0) t[2] = t[0];
    if (k == 1 || k == 2) {
      const std::int64_t m = mult(rng);
      t[2] = {t[0].x + m * (t[1].x - t[0].x), t[0].y + m * (t[1].y - t[0].y)};
    }
    if (k == 3) t[static_cast<std::size_t>(i % 3)].x = (i % 2 ? 1 : -1) * (kMaxSnapped + 1 + coord(rng) * coord(rng));
    int runs = 0;
    const TriangleCoverage cov =
        rasterize_triangle(t, S, -100, -100, 100, 100, [&](const TriangleCoverage&, const CoverageRun&) { ++runs; });
    if (triangle_never_covers(t[0], t[1], t[2])) {
      ++never;
      REQUIRE(runs == 0);
      REQUIRE(cov.area == 0);
    } else {
      ++set_up;
      REQUIRE(cov.area != 0);
      REQUIRE(cov.area == std::abs(snapped_twice_area(t[0], t[1], t[2])));
    }
  }
  CHECK(never > 4000);
  CHECK(set_up > 10000);
  // The range is inclusive: a vertex at exactly +-kMaxSnapped is accepted.
  CHECK_FALSE(triangle_never_covers({kMaxSnapped, 0}, {0, kMaxSnapped}, {-kMaxSnapped, -kMaxSnapped}));
  CHECK(triangle_never_covers({kMaxSnapped + 1, 0}, {0, 16}, {16, 16}));
  CHECK(triangle_never_covers({0, -kMaxSnapped - 1}, {0, 16}, {16, 16}));
}

TEST_CASE("raster: fragments are clipped to the given window") {
  const auto c = [&] {
    std::map<std::pair<int, int>, int> acc;
    rasterize_triangle({sv(-50, -50), sv(50, -50), sv(0, 50)}, S, 0, 0, 4, 3, [&](const TriangleCoverage&, const CoverageRun& r) {
      for (std::size_t i = 0; i < r.weight.size(); ++i) ++acc[{r.x0 + static_cast<int>(i), r.y}];
    });
    return acc;
  }();
  CHECK(c.size() == 12);  // the 4x3 window lies fully inside the triangle
}

TEST_CASE("raster: attribute codes are the exact barycentric value rounded half up once") {
  // Weights (1, 1, 2) of A = 4: (1·10 + 1·11 + 2·12)/4 = 45/4 = 11.25 -> 11.
  CHECK(interpolate_code({1, 1, 2}, 4, 10, 11, 12) == 11);
  // A tie: (1·0 + 1·0 + 2·1)/4 = 0.5 -> 1 (half up).
  CHECK(interpolate_code({1, 1, 2}, 4, 0, 0, 1) == 1);
  // 24-bit depth codes with weights near the int64 limit: no overflow.
  const std::int64_t big = std::int64_t{1} << 60;
  CHECK(interpolate_code({big, big, 0}, 2 * big, 16777215, 0, 7) == 8388608);  // 8388607.5 -> 8388608
  CHECK(interpolate_code({0, 0, big}, big, 1, 2, 16777215) == 16777215);
}

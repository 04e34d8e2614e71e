// The rasterizer solves each row's run per edge (pipeline/raster/triangle.cpp);
// here it is compared with the plain definition: every pixel centre of the
// clipped bounding box tested against the three edge functions with the
// top-left rule (the loop the rasterizer used before, kept as the reference).
// Random triangles (tiny, huge, slivers, degenerate, both orientations,
// out-of-range vertices) and random clip rectangles; runs and weights must be
// identical.
#include <doctest/doctest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "pipeline/raster/triangle.h"

using namespace ffsim;

namespace {

struct Row {
  int y, x0;
  std::vector<std::array<std::int64_t, 3>> w;
  bool operator==(const Row&) const = default;
};

std::int64_t floor_div(std::int64_t a, std::int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
std::int64_t ceil_div(std::int64_t a, std::int64_t b) { return -floor_div(-a, b); }

// The reference: every centre of the bounding box.
std::vector<Row> reference(const std::array<SnappedVertex, 3>& vin, int S, int cx0, int cy0, int cx1, int cy1) {
  std::vector<Row> rows;
  for (const SnappedVertex& p : vin)
    if (p.x < -kMaxSnapped || p.x > kMaxSnapped || p.y < -kMaxSnapped || p.y > kMaxSnapped) return rows;
  std::array<SnappedVertex, 3> v = vin;
  std::array<int, 3> idx{0, 1, 2};
  std::int64_t area = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (v[1].y - v[0].y);
  if (area == 0) return rows;
  if (area < 0) {
    std::swap(v[1], v[2]);
    std::swap(idx[1], idx[2]);
  }
  struct E { std::int64_t a, b, c; bool inc; };
  auto edge = [](const SnappedVertex& p, const SnappedVertex& q) {
    const std::int64_t dx = q.x - p.x, dy = q.y - p.y;
    return E{-dy, dx, dy * p.x - dx * p.y, dy < 0 || (dy == 0 && dx < 0)};
  };
  const std::array<E, 3> e{edge(v[1], v[2]), edge(v[2], v[0]), edge(v[0], v[1])};
  const std::int64_t one = std::int64_t{1} << S, half = one >> 1;
  const std::int64_t minx = std::min({v[0].x, v[1].x, v[2].x}), maxx = std::max({v[0].x, v[1].x, v[2].x});
  const std::int64_t miny = std::min({v[0].y, v[1].y, v[2].y}), maxy = std::max({v[0].y, v[1].y, v[2].y});
  const std::int64_t x0 = std::max<std::int64_t>(ceil_div(minx - half, one), cx0), x1 = std::min<std::int64_t>(floor_div(maxx - half, one), cx1 - 1);
  const std::int64_t y0 = std::max<std::int64_t>(ceil_div(miny - half, one), cy0), y1 = std::min<std::int64_t>(floor_div(maxy - half, one), cy1 - 1);
  for (std::int64_t y = y0; y <= y1; ++y) {
    Row row{static_cast<int>(y), 0, {}};
    for (std::int64_t x = x0; x <= x1; ++x) {
      std::array<std::int64_t, 3> w{};
      bool in = true;
      for (int k = 0; k < 3 && in; ++k) {
        const std::int64_t ek = e[k].a * (x * one + half) + e[k].b * (y * one + half) + e[k].c;
        in = ek > 0 || (ek == 0 && e[k].inc);
        w[idx[k]] = ek;
      }
      if (in) {
        if (row.w.empty()) row.x0 = static_cast<int>(x);
        row.w.push_back(w);
      }
    }
    if (!row.w.empty()) rows.push_back(row);
  }
  return rows;
}

std::vector<Row> fast(const std::array<SnappedVertex, 3>& v, int S, int cx0, int cy0, int cx1, int cy1) {
  std::vector<Row> rows;
  rasterize_triangle(v, S, cx0, cy0, cx1, cy1, [&](const TriangleCoverage&, const CoverageRun& run) {
    REQUIRE(run.count == static_cast<int>(run.weight.size()));
    rows.push_back({run.y, run.x0, run.weight});
  });
  return rows;
}

// RunWeights::First (the span path): the first weight only, the count, and
// weight[i] = weight[0] + i·dwdx rebuilt here from the returned gradients.
std::vector<Row> first_only(const std::array<SnappedVertex, 3>& v, int S, int cx0, int cy0, int cx1, int cy1) {
  std::vector<Row> rows;
  const TriangleCoverage cov = rasterize_triangle(
      v, S, cx0, cy0, cx1, cy1,
      [&](const TriangleCoverage&, const CoverageRun& run) {
        REQUIRE(run.weight.size() == 1);
        Row row{run.y, run.x0, {}};
        for (int i = 0; i < run.count; ++i) row.w.push_back(run.weight[0]);
        rows.push_back(row);
      },
      RunWeights::First);
  for (Row& row : rows)
    for (std::size_t i = 0; i < row.w.size(); ++i)
      for (int k = 0; k < 3; ++k) row.w[i][k] += static_cast<std::int64_t>(i) * cov.dwdx[k];
  return rows;
}

}  // namespace

TEST_CASE("fast raster: per-row solved runs == testing every centre, random triangles and clips") {
  std::mt19937 rng(2024);
  auto coord = [&](int scale) { return std::uniform_int_distribution<std::int64_t>(-scale, scale)(rng); };
  int nonempty = 0;
  for (int it = 0; it < 4000; ++it) {
    const int S = it % 3 == 0 ? 8 : 4;
    const int kind = it % 5;  // tiny, medium, sliver, shared-grid (ties), off-range
    std::array<SnappedVertex, 3> v;
    for (auto& p : v) {
      const int scale = kind == 0 ? 40 : kind == 1 ? 1200 : 600;
      p = {coord(scale) + 300, coord(scale) + 300};
      if (kind == 3) p = {(coord(8) << S) + (std::int64_t{1} << (S - 1)) * (it % 2), (coord(8) << S)};  // centres on edges
    }
    if (kind == 2) v[2] = {v[0].x + coord(3), v[0].y + coord(900)};  // sliver
    if (kind == 4 && it % 50 == 4) v[1].x = kMaxSnapped + 1;        // rejected
    const int cx0 = static_cast<int>(coord(20)), cy0 = static_cast<int>(coord(20));
    const int cx1 = cx0 + static_cast<int>(std::abs(coord(120))), cy1 = cy0 + static_cast<int>(std::abs(coord(120)));
    const auto want = reference(v, S, cx0, cy0, cx1, cy1);
    INFO("iteration ", it);
    REQUIRE(fast(v, S, cx0, cy0, cx1, cy1) == want);
    REQUIRE(first_only(v, S, cx0, cy0, cx1, cy1) == want);
    nonempty += !want.empty();
  }
  CHECK(nonempty > 1000);
}

TEST_CASE("fast raster: a planted difference is detected") {
  // The comparison notices one weight off by one.
  std::array<SnappedVertex, 3> v{SnappedVertex{0, 0}, SnappedVertex{400, 0}, SnappedVertex{0, 400}};
  auto rows = fast(v, 4, 0, 0, 100, 100);
  REQUIRE(rows == reference(v, 4, 0, 0, 100, 100));
  rows[3].w[2][1] += 1;
  CHECK_FALSE(rows == reference(v, 4, 0, 0, 100, 100));
}

// Triangle rasterization (GL121 §3.5.1) on a sub-pixel grid with the OpenGL
// pixel-centre rule and a top-left tie rule.
//
// Coordinates are window coordinates snapped to 1/2^S pixel (S = the profile's
// subpixel_bits), held as integers relative to an integer origin (the viewport's
// corner), so every edge function is an exact integer: no fragment depends on
// floating-point rounding once the vertices are snapped.
//
// A fragment (x, y) is produced iff its centre (x + 1/2, y + 1/2) is inside the
// triangle; a centre exactly on an edge belongs to the triangle only if that edge
// is a "left" edge (interior to its right, going down in y-up window
// coordinates) or a "top" edge (horizontal, interior below). Two triangles that
// share an edge therefore never both produce, nor both miss, a centre on it
// (docs/numerics.md §8.1).
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace ffsim {

struct SnappedVertex {
  std::int64_t x = 0, y = 0;  // window coordinate × 2^S, relative to the origin
};

// Snap a window coordinate (relative to the origin) to the grid: floor(v·2^S + 1/2).
std::int64_t snap_coordinate(double v, int subpixel_bits);

// Largest |snapped coordinate| the rasterizer accepts: keeps every edge function
// below 2^61 in int64. Vertices beyond it (2^20 pixels from the origin at S = 8,
// 2^24 at S = 4; clipped geometry stays inside the viewport, whose sides are at
// most 16384) make the triangle draw nothing.
inline constexpr std::int64_t kMaxSnapped = std::int64_t{1} << 28;

// A row run of covered fragments. weight[i][k] is the edge function opposite
// vertex k at fragment i's centre: the barycentric weight of vertex k is
// weight[i][k] / area (all weights >= 0, sum = area). With RunWeights::First only
// weight[0] is filled (weight[i] = weight[0] + i·dwdx, exactly).
struct CoverageRun {
  int y = 0;      // window row (relative to the origin)
  int x0 = 0;     // first fragment (relative to the origin)
  int count = 0;  // fragments in the run
  std::vector<std::array<std::int64_t, 3>> weight;
};

enum class RunWeights : std::uint8_t { All, First };

struct TriangleCoverage {
  std::int64_t area = 0;  // twice the signed area in grid units², made positive; 0 = degenerate
  // d(weight[k])/dx and /dy per pixel step: the gradients of the barycentric
  // numerators (for derivatives, e.g. the texture LOD).
  std::array<std::int64_t, 3> dwdx{}, dwdy{};
};

// A snapped vertex the rasterizer accepts (beyond, a triangle is rejected whole).
inline bool snapped_in_range(const SnappedVertex& p) {
  return p.x >= -kMaxSnapped && p.x <= kMaxSnapped && p.y >= -kMaxSnapped && p.y <= kMaxSnapped;
}
// Twice the signed area on the grid (counter-clockwise positive); exact in 64
// bits for vertices in range (differences below 2^29).
inline std::int64_t snapped_twice_area(const SnappedVertex& a, const SnappedVertex& b, const SnappedVertex& c) {
  return (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
}
// rasterize_triangle produces no fragment for this triangle in any window: a
// vertex out of range, or zero area on the grid (GL121 §3.5.1 produces the
// fragments whose centres lie inside the polygon; a degenerate one has no
// inside, and rasterize_triangle returns before its edges are set up). The tests
// it makes first, so a caller may leave such a triangle out unseen.
inline bool triangle_never_covers(const SnappedVertex& a, const SnappedVertex& b, const SnappedVertex& c) {
  return !snapped_in_range(a) || !snapped_in_range(b) || !snapped_in_range(c) || snapped_twice_area(a, b, c) == 0;
}

// Rasterize one triangle; `clip_*` bound the fragments produced (relative to the
// origin, half-open: x in [clip_x0, clip_x1), y in [clip_y0, clip_y1)). Calls
// `emit` with the setup for every non-empty run, bottom row first. Returns the
// setup (area 0: degenerate, nothing was produced). `weights`: every fragment's
// weights, or the first fragment's only (the span path steps them itself).
// `scratch`: the run handed to `emit`, kept by the caller so that its weight
// buffer is reused from triangle to triangle (null: a local one, allocated per
// triangle).
TriangleCoverage rasterize_triangle(const std::array<SnappedVertex, 3>& v, int subpixel_bits, int clip_x0,
                                    int clip_y0, int clip_x1, int clip_y1,
                                    const std::function<void(const TriangleCoverage&, const CoverageRun&)>& emit,
                                    RunWeights weights = RunWeights::All, CoverageRun* scratch = nullptr);

// A code attribute (colour or depth) at a fragment: the exact barycentric value
// Σ w_k·k_k / A rounded half up once, floor((2·Σ w_k·k_k + A) / 2A), in 128-bit
// integers (weights < 2^61, codes < 2^32).
std::uint32_t interpolate_code(const std::array<std::int64_t, 3>& w, std::int64_t area, std::uint32_t k0,
                               std::uint32_t k1, std::uint32_t k2);

// interpolate_code at the n fragments of a run: w0 the weights at the first,
// dwdx added per step to the right (CoverageRun/TriangleCoverage). The same
// values, by an exact DDA: the quotient and remainder of (2·num + A) / 2A are
// carried from fragment to fragment (num grows by Σ dwdx_k·k_k per step), with
// one division per run: in int64 when A·max code <= 2^59, else 128-bit
// (docs/performance.md). Three equal codes
// are the run's value everywhere (Σ w_k = A), filled without a division.
void interpolate_code_run(const std::array<std::int64_t, 3>& w0, const std::array<std::int64_t, 3>& dwdx,
                          std::int64_t area, std::uint32_t k0, std::uint32_t k1, std::uint32_t k2, int n,
                          std::uint32_t* out);

// interpolate_code_run for the `runs` runs of one triangle (run r: first weights
// first[r], length[r] fragments), written one after the other into `out`: the same
// values, with the step's division done once per triangle instead of per run.
void interpolate_code_runs(const std::array<std::int64_t, 3>* first, const int* length, int runs,
                           const std::array<std::int64_t, 3>& dwdx, std::int64_t area, std::uint32_t k0,
                           std::uint32_t k1, std::uint32_t k2, std::uint32_t* out);

}  // namespace ffsim

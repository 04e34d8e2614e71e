#include "pipeline/raster/triangle.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace ffsim {

std::int64_t snap_coordinate(double v, int subpixel_bits) {
  // v·2^S as a multiplication by the exact power 2^S (0 <= S <= 1023): the value
  // ldexp gives (one correctly rounded result, ±inf beyond the range), without
  // the library call per coordinate.
  const double scaled = subpixel_bits >= 0 && subpixel_bits <= 1023
                            ? v * std::bit_cast<double>(static_cast<std::uint64_t>(1023 + subpixel_bits) << 52)
                            : std::ldexp(v, subpixel_bits);
  const double s = std::floor(scaled + 0.5);
  if (!(s > -static_cast<double>(kMaxSnapped) * 4 && s < static_cast<double>(kMaxSnapped) * 4))
    return s < 0 ? -kMaxSnapped * 4 : kMaxSnapped * 4;  // out of range (also NaN): rejected by the rasterizer
  return static_cast<std::int64_t>(s);
}

namespace {

std::int64_t floor_div(std::int64_t a, std::int64_t b) {  // b > 0
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}
std::int64_t ceil_div(std::int64_t a, std::int64_t b) { return -floor_div(-a, b); }

struct Edge {
  std::int64_t a = 0, b = 0, c = 0;  // E(p) = a·px + b·py + c
  bool inclusive = false;            // a centre on this edge belongs to the triangle
};

// Edge from p to q, positive on its left (the interior of a counter-clockwise
// triangle in y-up coordinates).
Edge make_edge(const SnappedVertex& p, const SnappedVertex& q) {
  const std::int64_t dx = q.x - p.x, dy = q.y - p.y;
  Edge e;
  // E = dx·(y − p.y) − dy·(x − p.x)
  e.a = -dy;
  e.b = dx;
  e.c = dy * p.x - dx * p.y;
  e.inclusive = dy < 0 || (dy == 0 && dx < 0);  // left edge, or top edge
  return e;
}

}  // namespace

TriangleCoverage rasterize_triangle(const std::array<SnappedVertex, 3>& vin, int S, int clip_x0, int clip_y0,
                                    int clip_x1, int clip_y1,
                                    const std::function<void(const TriangleCoverage&, const CoverageRun&)>& emit,
                                    RunWeights weights, CoverageRun* scratch) {
  TriangleCoverage cov;
  if (triangle_never_covers(vin[0], vin[1], vin[2])) return cov;
  std::array<SnappedVertex, 3> v = vin;
  std::array<int, 3> idx{0, 1, 2};  // which input vertex each v[k] is
  std::int64_t area = snapped_twice_area(v[0], v[1], v[2]);
  if (area < 0) {  // make it counter-clockwise; weights are mapped back through idx
    std::swap(v[1], v[2]);
    std::swap(idx[1], idx[2]);
    area = -area;
  }
  // Edge opposite vertex k: from v[k+1] to v[k+2].
  std::array<Edge, 3> e{make_edge(v[1], v[2]), make_edge(v[2], v[0]), make_edge(v[0], v[1])};
  cov.area = area;
  const std::int64_t one = std::int64_t{1} << S, half = one >> 1;
  for (int k = 0; k < 3; ++k) {
    cov.dwdx[idx[k]] = e[k].a * one;
    cov.dwdy[idx[k]] = e[k].b * one;
  }
  // Bounding box of the centres that can be inside: centre = (x·2^S + 2^(S-1)).
  const std::int64_t minx = std::min({v[0].x, v[1].x, v[2].x}), maxx = std::max({v[0].x, v[1].x, v[2].x});
  const std::int64_t miny = std::min({v[0].y, v[1].y, v[2].y}), maxy = std::max({v[0].y, v[1].y, v[2].y});
  // Pixels whose centre x·2^S + 2^(S-1) lies in [lo, hi].
  auto first_pixel = [&](std::int64_t lo) { return ceil_div(lo - half, one); };
  auto last_pixel = [&](std::int64_t hi) { return floor_div(hi - half, one); };
  std::int64_t x0 = first_pixel(minx), x1 = last_pixel(maxx);
  std::int64_t y0 = first_pixel(miny), y1 = last_pixel(maxy);
  x0 = std::max<std::int64_t>(x0, clip_x0);
  y0 = std::max<std::int64_t>(y0, clip_y0);
  x1 = std::min<std::int64_t>(x1, clip_x1 - 1);
  y1 = std::min<std::int64_t>(y1, clip_y1 - 1);
  // Each row's run is solved per edge instead of testing every pixel of the
  // bounding box: along a row E_k(x) = A_k·x + C_k exactly (A_k = a_k·2^S), and
  // "inside" is E_k >= t_k with t_k = 0 on an inclusive edge, 1 otherwise
  // (integers), so each edge bounds x by one exact floor/ceil division. The run
  // is the intersection: the same fragments and weights as evaluating every
  // centre (tests/pipeline/test_fast_raster.cpp compares with that loop).
  CoverageRun local;
  CoverageRun& run = scratch ? *scratch : local;
  std::array<std::int64_t, 3> step{}, t{};
  for (int k = 0; k < 3; ++k) {
    step[k] = e[k].a * one;
    t[k] = e[k].inclusive ? 0 : 1;
  }
  for (std::int64_t y = y0; y <= y1; ++y) {
    const std::int64_t py = y * one + half;
    std::int64_t lo = x0, hi = x1;
    std::array<std::int64_t, 3> c0{};  // E_k at x = 0 of this row
    for (int k = 0; k < 3 && lo <= hi; ++k) {
      c0[k] = e[k].a * half + e[k].b * py + e[k].c;
      if (step[k] > 0) lo = std::max(lo, ceil_div(t[k] - c0[k], step[k]));
      else if (step[k] < 0) hi = std::min(hi, floor_div(c0[k] - t[k], -step[k]));
      else if (c0[k] < t[k]) hi = lo - 1;  // horizontal edge with the row outside
    }
    if (lo > hi) continue;
    run.y = static_cast<int>(y);
    run.x0 = static_cast<int>(lo);
    run.count = static_cast<int>(hi - lo + 1);
    run.weight.resize(weights == RunWeights::All ? static_cast<std::size_t>(run.count) : 1);
    // Element by element: a whole-array copy of w just after these indexed
    // stores made the load wait on them (a store-forwarding stall, per row).
    for (std::size_t i = 0; i < run.weight.size(); ++i)
      for (int k = 0; k < 3; ++k) run.weight[i][static_cast<std::size_t>(idx[k])] = step[k] * (lo + static_cast<std::int64_t>(i)) + c0[k];
    emit(cov, run);
  }
  return cov;
}

std::uint32_t interpolate_code(const std::array<std::int64_t, 3>& w, std::int64_t area, std::uint32_t k0,
                               std::uint32_t k1, std::uint32_t k2) {
  __extension__ typedef __int128 i128;
  const i128 num = i128{w[0]} * k0 + i128{w[1]} * k1 + i128{w[2]} * k2;
  return static_cast<std::uint32_t>((2 * num + area) / (2 * i128{area}));
}

// A·kmax at most this: interpolate_code_run's DDA fits int64 (see there).
constexpr std::int64_t kSmallProduct = std::int64_t{1} << 59;

namespace {

// interpolate_code_run in 128-bit integers (A·max code > 2^59), n >= 1.
void interpolate_code_run_wide(const std::array<std::int64_t, 3>& w0, const std::array<std::int64_t, 3>& dwdx,
                               std::int64_t area, std::uint32_t k0, std::uint32_t k1, std::uint32_t k2, int n,
                               std::uint32_t* out);

// The int64 DDA of one run from its quotient and remainder (q, r) at the first
// fragment, with the per-step (dq, dr), 0 <= dr < d.
inline void code_run_int64(std::int64_t q, std::int64_t r, std::int64_t d, std::int64_t dq, std::int64_t dr, int n,
                           std::uint32_t* out) {
  out[0] = static_cast<std::uint32_t>(q);
  for (int i = 1; i < n; ++i) {  // branch free: the carry is data-dependent
    r += dr;
    const bool carry = r >= d;
    r = carry ? r - d : r;  // a conditional move (a multiply by the carry lengthened the chain)
    q += dq + carry;
    out[i] = static_cast<std::uint32_t>(q);
  }
}

bool small_product(std::int64_t area, std::uint32_t kmax) {
  __extension__ typedef unsigned __int128 u128;
  return static_cast<u128>(area) * kmax <= static_cast<u128>(kSmallProduct);  // (area > 0)
}

}  // namespace

void interpolate_code_run(const std::array<std::int64_t, 3>& w0, const std::array<std::int64_t, 3>& dwdx,
                          std::int64_t area, std::uint32_t k0, std::uint32_t k1, std::uint32_t k2, int n,
                          std::uint32_t* out) {
  if (n <= 0) return;
  if (k0 == k1 && k1 == k2) {  // Σ w_k = A: floor((2·k·A + A) / 2A) = k, no division needed
    std::fill_n(out, n, k0);
    return;
  }
  if (small_product(area, std::max({k0, k1, k2}))) {
    // The same quotients in int64 (hardware division, not __divmodti4): inside the
    // triangle the weights are >= 0 with Σ w_k = A, so 0 <= Σ w_k·k_k <= A·kmax
    // < 2^59; for n >= 2, |dwdx_k| = |w_k(1) − w_k(0)| <= A, so |Σ dwdx_k·k_k| <= 3·A·kmax.
    // Every term below stays under 2^62.
    const std::int64_t d = 2 * area;
    const std::int64_t x0 = 2 * (w0[0] * k0 + w0[1] * k1 + w0[2] * k2) + area;  // >= 0
    std::int64_t dq = 0, dr = 0;
    if (n >= 2) {
      const std::int64_t step = 2 * (dwdx[0] * k0 + dwdx[1] * k1 + dwdx[2] * k2);
      dq = step / d;
      dr = step % d;
      if (dr < 0) {  // floor division: remainder in [0, d)
        dr += d;
        --dq;
      }
    }
    code_run_int64(x0 / d, x0 % d, d, dq, dr, n, out);
    return;
  }
  interpolate_code_run_wide(w0, dwdx, area, k0, k1, k2, n, out);
}

void interpolate_code_runs(const std::array<std::int64_t, 3>* first, const int* length, int runs,
                           const std::array<std::int64_t, 3>& dwdx, std::int64_t area, std::uint32_t k0,
                           std::uint32_t k1, std::uint32_t k2, std::uint32_t* out) {
  if (k0 == k1 && k1 == k2) {
    int n = 0;
    for (int r = 0; r < runs; ++r) n += std::max(length[r], 0);
    std::fill_n(out, n, k0);
    return;
  }
  if (!small_product(area, std::max({k0, k1, k2}))) {
    for (int r = 0; r < runs; out += std::max(length[r], 0), ++r)
      if (length[r] > 0) interpolate_code_run_wide(first[r], dwdx, area, k0, k1, k2, length[r], out);
    return;
  }
  // interpolate_code_run's int64 DDA, run after run, the step's quotient and
  // remainder divided once per triangle instead of once per run: the same
  // (dq, dr), computed at the first run of two or more fragments (only such a run
  // bounds |dwdx_k| by A; a triangle of one-fragment runs never steps).
  const std::int64_t d = 2 * area;
  std::int64_t dq = 0, dr = 0;
  bool stepped = false;
  for (int r = 0; r < runs; ++r) {
    const int n = length[r];
    if (n <= 0) continue;
    if (n >= 2 && !stepped) {
      const std::int64_t step = 2 * (dwdx[0] * k0 + dwdx[1] * k1 + dwdx[2] * k2);
      dq = step / d;
      dr = step % d;
      if (dr < 0) {
        dr += d;
        --dq;
      }
      stepped = true;
    }
    const std::array<std::int64_t, 3>& w0 = first[r];
    const std::int64_t x0 = 2 * (w0[0] * k0 + w0[1] * k1 + w0[2] * k2) + area;  // >= 0
    code_run_int64(x0 / d, x0 % d, d, dq, dr, n, out);
    out += n;
  }
}

namespace {

void interpolate_code_run_wide(const std::array<std::int64_t, 3>& w0, const std::array<std::int64_t, 3>& dwdx,
                               std::int64_t area, std::uint32_t k0, std::uint32_t k1, std::uint32_t k2, int n,
                               std::uint32_t* out) {
  __extension__ typedef __int128 i128;
  const i128 D = 2 * i128{area};
  const i128 x0 = 2 * (i128{w0[0]} * k0 + i128{w0[1]} * k1 + i128{w0[2]} * k2) + area;  // >= 0 inside
  const i128 step = 2 * (i128{dwdx[0]} * k0 + i128{dwdx[1]} * k1 + i128{dwdx[2]} * k2);
  // Floor division by D > 0 for both signs; remainders in [0, D).
  auto floor_div = [&](i128 a, i128& rem) {
    i128 q = a / D;
    rem = a - q * D;
    if (rem < 0) {
      rem += D;
      --q;
    }
    return q;
  };
  i128 r0 = 0, dr0 = 0;
  const i128 q0 = floor_div(x0, r0);
  if (n == 1) {  // no step (a one-fragment run of a sliver may have a huge gradient)
    out[0] = static_cast<std::uint32_t>(q0);
    return;
  }
  const i128 dq0 = floor_div(step, dr0);
  // Every fragment of the run is inside the triangle, so every quotient is a
  // code (< 2^32) and the remainders stay below D < 2^62: int64 suffices.
  std::int64_t q = static_cast<std::int64_t>(q0), r = static_cast<std::int64_t>(r0);
  const std::int64_t dq = static_cast<std::int64_t>(dq0), dr = static_cast<std::int64_t>(dr0);
  const std::int64_t d = static_cast<std::int64_t>(D);
  for (int i = 0;; ++i) {
    out[i] = static_cast<std::uint32_t>(q);
    if (i + 1 == n) break;
    q += dq;
    r += dr;
    if (r >= d) {
      r -= d;
      ++q;
    }
  }
}

}  // namespace

}  // namespace ffsim

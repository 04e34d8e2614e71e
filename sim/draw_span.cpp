// The span path of the draw (docs/performance.md): a group of runs shaded at
// once (the rows of one or several consecutive triangles, or one run next to a
// probed pixel), in fixed profiles, with the same numbers as the per-fragment
// path of sim/draw.cpp (which stays the reference and serves --probe). Every
// fragment's numbers depend only on its own weights and its triangle's vertices;
// only the DDAs below restart at every run:
//   - colour and depth codes by interpolate_code_run, the exact DDA form of
//     interpolate_code (numerics §8.2);
//   - texture coordinates as the binary32 values the sampler rounds the
//     reference's binary64 s/q, t/q to: the same sums, then one reciprocal and a
//     test that proves the rounding, else the reference's divisions
//     (coordinates_rounded);
//   - texels by sample_span_fixed (textures whose result cannot depend on λ);
//   - texture environments by texture_environment_span_fixed where an integer
//     kernel exists, else texture_environment per fragment; the colour sum on
//     codes; or the register combiners' shade_span over all the fragments.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <memory>
#ifdef __AVX2__
#include <immintrin.h>
#endif

#include "pipeline/combiners/combiner_span.h"
#include "pipeline/combiners/register_combiners.h"
#include "pipeline/number/unorm.h"
#include "sim/draw_span.h"

namespace ffsim {

namespace {

// Interpolated colour codes of the runs, 4 per fragment (flat: the provoking
// vertex's, which draw_polygon copied to every vertex).
void interpolate_colors(const std::array<const WindowVertex*, 3>& tv, bool secondary, const TriangleCoverage& cov,
                        const FastRuns& runs, bool flat, std::uint32_t* lane, std::uint16_t* out) {
  auto code = [&](const WindowVertex* v, int c) { return secondary ? v->secondary_code[c] : v->color_code[c]; };
  auto constant = [&](int c) { return flat || (code(tv[0], c) == code(tv[1], c) && code(tv[1], c) == code(tv[2], c)); };
  const int n = runs.count;
  if (constant(0) && constant(1) && constant(2) && constant(3)) {  // one colour for every fragment
    const std::array<std::uint16_t, 4> k{static_cast<std::uint16_t>(code(tv[0], 0)), static_cast<std::uint16_t>(code(tv[0], 1)),
                                         static_cast<std::uint16_t>(code(tv[0], 2)), static_cast<std::uint16_t>(code(tv[0], 3))};
    for (int f = 0; f < n; ++f) std::copy_n(k.data(), 4, out + 4 * f);
    return;
  }
  for (int c = 0; c < 4; ++c) {
    // Flat shading, or three equal codes (Σ w_k = A: the value is the code).
    if (constant(c)) {
      const auto k = static_cast<std::uint16_t>(code(tv[0], c));
      for (int f = 0; f < n; ++f) out[4 * f + c] = k;
      continue;
    }
    // The DDA restarts at every run (one step division per triangle).
    interpolate_code_runs(runs.first, runs.length, runs.runs, cov.dwdx, cov.area, code(tv[0], c), code(tv[1], c),
                          code(tv[2], c), lane);
    for (int f = 0; f < n; ++f) out[4 * f + c] = static_cast<std::uint16_t>(lane[f]);
  }
}

// s/q and t/q of unit u at the runs' fragments, rounded to binary32 as the
// sampler rounds them: the per-fragment path's values (v_j = ((0 + w_0·c_0j) +
// w_1·c_1j) + w_2·c_2j, then v_j / A, then v_0 / v_2 and v_1 / v_2, binary64),
// computed as loops over fragments in vector lanes (IEEE operations give the same
// bits in lanes), and on most triangles from one reciprocal per fragment
// (coordinates_rounded below proves each rounding or falls back).
//  - The weights are stepped, not read: w_k = first_k + i·dwdx_k. A covered
//    fragment's weights lie in [0, A] (each edge function >= 0, their sum A), so
//    for A < 2^53 every w_k, every i·dwdx_k (= w_k − first_k, in [−A, A]) and
//    dwdx_k itself (i >= 1) is an integer below 2^53: first_k + i·dwdx_k computed
//    in binary64 is the exact integer the reference converts. (i = 0: i·dwdx_k is
//    ±0 and first_k + ±0 = first_k.) A >= 2^53: int64 weights, converted, as the
//    reference does.
//  - When the three q/w are exactly 1 (an affine mapping with w_clip = 1, e.g. an
//    orthographic screen quad) and A < 2^53, v_2 = (Σ w_k)/A = A/A = 1 exactly
//    (the integer weights and their partial sums are exact in binary64), and
//    x / 1 = x: v_2 and the two divisions by it are skipped with the same result.
//  - When A is a power of two 2^k (k <= 52; the triangles of a screen-aligned
//    square, e.g.), x / A and x · 2^−k are the same correctly rounded value of
//    the same real number (2^−k is exact), subnormal, zero, infinite and NaN
//    results included: the divisions by A become multiplications.
//  - When, in addition, A = 2^k, q = 1 and a coordinate's three vertex values
//    are integer multiples m_j·2^e of one power of two with
//    2·W·Σ|m_j| < 2^53, W the largest |w_k| of the run's lanes (a screen-aligned
//    quad with coordinates of a few bits, e.g. texel-aligned), every product and
//    partial sum of v = ((0 + w_0·c_0) + w_1·c_1) + w_2·c_2 is an integer multiple
//    of 2^e below 2^53·2^e, so exact, and v·2^−k is exact too: along a run
//    v_i = V_0 + i·D exactly (D the same formula on the steps dwdx_k, whose
//    |dwdx_k| <= 2W), and V_0 + i·D computed in binary64 is exact for the same
//    reason (|i·Σ dwdx_j·m_j| and |Σ w_j·m_j| are within the bound). An exact zero
//    is +0 both ways (the reference starts from 0 + ·; V_0 is the reference's
//    value, and x + (−x) = +0). `DyadicCoords::exact_for` checks the bound per run.
using Coords = std::array<double, 3>;  // s/w, t/w, q/w at a vertex

// Coordinate j (s or t) of a triangle's three vertices as m_k·2^e (e the exponent
// of the lowest set bit among them, m_k integers); ok false when a value is not
// finite, a multiple is 2^53 or more, or 2^e·2^−k could underflow.
struct DyadicCoords {
  bool ok = false;
  std::uint64_t sum_m = 0;  // Σ|m_k| < 3·2^53

  DyadicCoords() = default;  // not ok
  DyadicCoords(const Coords& c0, const Coords& c1, const Coords& c2, int j, int k) {
    const double v[3] = {c0[static_cast<std::size_t>(j)], c1[static_cast<std::size_t>(j)], c2[static_cast<std::size_t>(j)]};
    int e = 1 << 20;  // the lowest set bit's exponent (no bit: any)
    for (const double x : v) {
      if (!std::isfinite(x)) return;
      if (x == 0) continue;
      int ex = 0;
      const double f = std::frexp(x, &ex);  // |f| in [0.5, 1): x = F·2^(ex−53), F = f·2^53 an integer
      const auto F = static_cast<std::uint64_t>(std::fabs(std::ldexp(f, 53)));
      e = std::min(e, ex - 53 + std::countr_zero(F));
    }
    if (e == 1 << 20) e = 0;  // all three zero
    if (e - k < -1000) return;  // far from the subnormals: every v·2^−k stays normal or zero
    for (const double x : v) {
      const double m = std::fabs(std::ldexp(x, -e));  // an integer (exact: a power-of-two scale)
      if (m >= 0x1p53) return;
      sum_m += static_cast<std::uint64_t>(m);
    }
    ok = true;
  }
  // The bound for a run whose lanes' weights are at most W in magnitude.
  // 2·W·Σ|m_k| < 2^53, i.e. W·Σ|m_k| <= 2^52 − 1.
  bool exact_for(std::uint64_t W) const {
    return ok && (sum_m == 0 || W <= ((std::uint64_t{1} << 52) - 1) / sum_m);
  }
};

// x / A: a division, or (kPow2) the multiplication by 1/A = 2^−k, the same value.
template <bool kPow2>
struct ByArea {
  double a, inv;
  double operator()(double x) const {
    if constexpr (kPow2) return x * inv;
    else return x / a;
  }
};

// s/q and t/q at one fragment of weights (w0, w1, w2) (binary64, the reference's order).
template <bool kUnitQ, class Div>
inline void coordinates_at(const Coords& c0, const Coords& c1, const Coords& c2, Div by_a, double w0, double w1,
                           double w2, double& s, double& t) {
  const double v0 = by_a(((0.0 + w0 * c0[0]) + w1 * c1[0]) + w2 * c2[0]);
  const double v1 = by_a(((0.0 + w0 * c0[1]) + w1 * c1[1]) + w2 * c2[1]);
  if constexpr (kUnitQ) {
    s = v0;
    t = v1;
  } else {
    const double q = by_a(((0.0 + w0 * c0[2]) + w1 * c1[2]) + w2 * c2[2]);
    s = v0 / q;
    t = v1 / q;
  }
}

template <bool kUnitQ, class Div>
void coordinates_stepped(const Coords& c0, const Coords& c1, const Coords& c2, Div by_a, const Coords& first,
                         const Coords& d, int n, float* s, float* t) {
  for (int i = 0; i < n; ++i) {
    const double fi = static_cast<double>(i);
    double sd = 0, td = 0;
    coordinates_at<kUnitQ>(c0, c1, c2, by_a, first[0] + fi * d[0], first[1] + fi * d[1], first[2] + fi * d[2], sd, td);
    s[i] = static_cast<float>(sd);
    t[i] = static_cast<float>(td);
  }
}

// ---- s/q and t/q rounded to binary32, from one division per fragment ----------
// The sampler uses RN32(s), the reference's binary64 s rounded to binary32
// (sample_level), so that is what the span path computes. With v_0, v_1, v_2 the
// reference's sums (the same operations), r = RN(1/v_2) (RN(1/A) when q = 1)
// and a = RN(v_0·r), u = 2^−53:
//  - s = RN(RN(v_0/A)/RN(v_2/A)) (q = 1: RN(v_0/A)) = (v_0/v_2)(1+e1)(1+e3)/(1+e2)
//    and a = (v_0/v_2)(1+e4)(1+e5), every |e_i| <= u when no step underflows or
//    overflows, so s = a·(1+η) with |η| < 2^−49;
//  - lo = RN(a·(1 − 2^−40)) and hi = RN(a·(1 + 2^−40)) then enclose s (each
//    product's rounding moves it by at most u·|a|, far inside the 2^−40 margin),
//    and RN32 is monotone: when RN32(lo) == RN32(hi), RN32(s) is that value. A
//    zero keeps a's sign, which is s's (sign(v_0)·sign(v_2) both ways).
// When may a step underflow or overflow? r is checked: 2^−190 <= |r| <= 2^190
// (q = 1: r = RN(1/A) is in [2^−53, 1]). Then, with A in [1, 2^53):
//  - |a| >= 2^−190: |v_0| >= 2^−381 or so, every step above is normal;
//  - |a| < 2^−190: |v_0/v_2| is below 2^−189, so both s and a are far below the
//    smallest binary32 (2^−149): RN32 gives a zero of the sign above either way
//    (an underflowed RN(v_0/A) keeps v_0's sign), and lo, hi are such zeros;
//  - a quotient too large for binary64 is also far above the largest binary32:
//    RN32 gives the infinity of that sign either way, and lo, hi are too (a
//    product that overflows rounds to that infinity);
//  - a NaN (v_0 or v_1 not finite with q = 0, or a NaN input) fails lo == hi.
// Any lane that fails (s within about 2^−40 relative of a binary32 rounding
// boundary, or r out of its range) takes the reference's divisions.
constexpr double kBelow = 1 - 0x1p-40, kAbove = 1 + 0x1p-40;
inline bool r_in_range(double r) {
  const double a = std::fabs(r);
  return a >= 0x1p-190 && a <= 0x1p190;
}

// Lanes [0, n) of w0, w1, w2 (weights), n a multiple of 4: s[i], t[i] as RN32 of
// coordinates_at's values for i < used; the lanes from `used` on are padding,
// written with any value (not worth the reference's divisions). kExact: A = 2^k
// and q = 1, where coordinates_at is one exact-scale multiplication per
// coordinate: its values are rounded directly.
template <bool kUnitQ, bool kExact, class Div>
void coordinates_rounded(const Coords& c0, const Coords& c1, const Coords& c2, Div by_a, double inv_a,
                         const double* w0, const double* w1, const double* w2, int n, int used, float* s, float* t) {
  if constexpr (kExact) {
    for (int i = 0; i < n; ++i) {  // (vectorised by the compiler)
      double sd = 0, td = 0;
      coordinates_at<true>(c0, c1, c2, by_a, w0[i], w1[i], w2[i], sd, td);
      s[i] = static_cast<float>(sd);
      t[i] = static_cast<float>(td);
    }
    return;
  }
  int i = 0;
  // A lane that fails the test: the reference's divisions.
  auto exact = [&](int k) {
    double sd = 0, td = 0;
    coordinates_at<kUnitQ>(c0, c1, c2, by_a, w0[k], w1[k], w2[k], sd, td);
    s[k] = static_cast<float>(sd);
    t[k] = static_cast<float>(td);
  };
#ifdef __AVX2__
  {
    const __m256d zero = _mm256_setzero_pd(), below = _mm256_set1_pd(kBelow), above = _mm256_set1_pd(kAbove);
    const __m256d abs_mask = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7FFFFFFFFFFFFFFFll));
    const __m256d lo_bound = _mm256_set1_pd(0x1p-190), hi_bound = _mm256_set1_pd(0x1p190);
    // ((0 + w0·c0) + w1·c1) + w2·c2: the reference's sum, lane by lane (no FMA).
    __m256d k[3][3];
    for (std::size_t j = 0; j < 3; ++j) {
      k[j][0] = _mm256_set1_pd(c0[j]);
      k[j][1] = _mm256_set1_pd(c1[j]);
      k[j][2] = _mm256_set1_pd(c2[j]);
    }
    auto sum = [&](__m256d W0, __m256d W1, __m256d W2, int j) {
      const __m256d* kj = k[j];
      return _mm256_add_pd(_mm256_add_pd(_mm256_add_pd(zero, _mm256_mul_pd(W0, kj[0])), _mm256_mul_pd(W1, kj[1])),
                           _mm256_mul_pd(W2, kj[2]));
    };
    for (; i + 4 <= n; i += 4) {
      const __m256d W0 = _mm256_loadu_pd(w0 + i), W1 = _mm256_loadu_pd(w1 + i), W2 = _mm256_loadu_pd(w2 + i);
      const __m256d v0 = sum(W0, W1, W2, 0), v1 = sum(W0, W1, W2, 1);
      __m256d r;
      int good = 0xF;
      if constexpr (kUnitQ) {
        r = _mm256_set1_pd(inv_a);
      } else {
        r = _mm256_div_pd(_mm256_set1_pd(1.0), sum(W0, W1, W2, 2));
        const __m256d ar = _mm256_and_pd(r, abs_mask);
        good = _mm256_movemask_pd(_mm256_and_pd(_mm256_cmp_pd(ar, lo_bound, _CMP_GE_OQ), _mm256_cmp_pd(ar, hi_bound, _CMP_LE_OQ)));
      }
      const __m256d as = _mm256_mul_pd(v0, r), at = _mm256_mul_pd(v1, r);
      const __m128 s_lo = _mm256_cvtpd_ps(_mm256_mul_pd(as, below)), s_hi = _mm256_cvtpd_ps(_mm256_mul_pd(as, above));
      const __m128 t_lo = _mm256_cvtpd_ps(_mm256_mul_pd(at, below)), t_hi = _mm256_cvtpd_ps(_mm256_mul_pd(at, above));
      good &= _mm_movemask_ps(_mm_and_ps(_mm_cmpeq_ps(s_lo, s_hi), _mm_cmpeq_ps(t_lo, t_hi)));
      _mm_storeu_ps(s + i, s_lo);
      _mm_storeu_ps(t + i, t_lo);
      const int real = used - i >= 4 ? 0xF : (1 << std::max(used - i, 0)) - 1;
      for (int bad = ~good & real; bad; bad &= bad - 1) exact(i + std::countr_zero(static_cast<unsigned>(bad)));
    }
  }
#endif
  for (; i < n; ++i) {
    const double v0 = ((0.0 + w0[i] * c0[0]) + w1[i] * c1[0]) + w2[i] * c2[0];
    const double v1 = ((0.0 + w0[i] * c0[1]) + w1[i] * c1[1]) + w2[i] * c2[1];
    bool ok = true;
    double r = inv_a;
    if constexpr (!kUnitQ) {
      r = 1.0 / (((0.0 + w0[i] * c0[2]) + w1[i] * c1[2]) + w2[i] * c2[2]);
      ok = r_in_range(r);
    }
    const double as = v0 * r, at = v1 * r;
    const auto s_lo = static_cast<float>(as * kBelow), s_hi = static_cast<float>(as * kAbove);
    const auto t_lo = static_cast<float>(at * kBelow), t_hi = static_cast<float>(at * kAbove);
    if ((ok && s_lo == s_hi && t_lo == t_hi) || i >= used) {
      s[i] = s_lo;
      t[i] = t_lo;
    } else {
      exact(i);
    }
  }
}

// A triangle's fragments, all its runs, in blocks: the weights first + i·d of
// each fragment (the binary64 operations coordinates_stepped performs per run),
// then coordinates_rounded over the block, padded to 4 lanes once per block
// instead of once per run (the terrain's runs are a few fragments long). The
// padding lanes (weights 0; nothing traps) write up to 3 slots past the
// triangle's last fragment, as coordinates_stepped does past a run.
template <bool kUnitQ, bool kExact, class Div>
void coordinates_blocked(const Coords& c0, const Coords& c1, const Coords& c2, Div by_a, double inv_a, const Coords& d,
                         const FastRuns& runs, float* s, float* t) {
  constexpr int kBlock = 256;
  alignas(32) double w0[kBlock + 3], w1[kBlock + 3], w2[kBlock + 3];
  int j = 0, out = 0;
  auto flush = [&] {
    const int n4 = (j + 3) & ~3;
    for (int i = j; i < n4; ++i) w0[i] = w1[i] = w2[i] = 0;
    coordinates_rounded<kUnitQ, kExact>(c0, c1, c2, by_a, inv_a, w0, w1, w2, n4, j, s + out, t + out);
    out += j;
    j = 0;
  };
  for (int r = 0; r < runs.runs; ++r) {
    const std::array<std::int64_t, 3>& w = runs.first[r];
    const Coords f{static_cast<double>(w[0]), static_cast<double>(w[1]), static_cast<double>(w[2])};
    for (int i0 = 0; i0 < runs.length[r];) {
      if (j == kBlock) flush();
      // The run's fragments i0 .. i0 + m − 1 that fit in the block: a loop the
      // compiler vectorises (the same binary64 operations per fragment).
      const int m = std::min(runs.length[r] - i0, kBlock - j);
#ifdef __AVX2__
      // Four at a time, up to 3 lanes past the run (the block's 3 spare slots, or
      // the next run's, which it then overwrites); the same mul and add per lane.
      {
        __m256d fi = _mm256_add_pd(_mm256_set1_pd(static_cast<double>(i0)), _mm256_setr_pd(0, 1, 2, 3));
        const __m256d four = _mm256_set1_pd(4), F0 = _mm256_set1_pd(f[0]), F1 = _mm256_set1_pd(f[1]),
                      F2 = _mm256_set1_pd(f[2]), D0 = _mm256_set1_pd(d[0]), D1 = _mm256_set1_pd(d[1]),
                      D2 = _mm256_set1_pd(d[2]);
        for (int i = 0; i < m; i += 4, fi = _mm256_add_pd(fi, four)) {
          _mm256_storeu_pd(w0 + j + i, _mm256_add_pd(F0, _mm256_mul_pd(fi, D0)));
          _mm256_storeu_pd(w1 + j + i, _mm256_add_pd(F1, _mm256_mul_pd(fi, D1)));
          _mm256_storeu_pd(w2 + j + i, _mm256_add_pd(F2, _mm256_mul_pd(fi, D2)));
        }
      }
#else
      for (int i = 0; i < m; ++i) {
        const double fi = static_cast<double>(i0 + i);
        w0[j + i] = f[0] + fi * d[0];
        w1[j + i] = f[1] + fi * d[1];
        w2[j + i] = f[2] + fi * d[2];
      }
#endif
      j += m;
      i0 += m;
    }
  }
  if (j > 0) flush();
}

}  // namespace

void texture_coordinates(const std::array<const WindowVertex*, 3>& tv, int u, const TriangleCoverage& cov,
                         const FastRuns& runs, float* s, float* t) {
  const double a = static_cast<double>(cov.area);
  const auto& c0 = tv[0]->tcw[u];
  const auto& c1 = tv[1]->tcw[u];
  const auto& c2 = tv[2]->tcw[u];
  const bool exact = cov.area < (std::int64_t{1} << 53);
  const bool unit_q = c0[2] == 1.0 && c1[2] == 1.0 && c2[2] == 1.0 && exact;
  const bool pow2 = exact && (cov.area & (cov.area - 1)) == 0;  // A = 2^k, k <= 52 (area > 0)
  const Coords d{static_cast<double>(cov.dwdx[0]), static_cast<double>(cov.dwdx[1]), static_cast<double>(cov.dwdx[2])};
  // The exact progression (above): A = 2^k, q = 1, dyadic coordinates.
  // (Checked only for such triangles: the decomposition costs a few library calls.)
  const bool candidate = pow2 && unit_q;
  const int k = candidate ? std::countr_zero(static_cast<std::uint64_t>(cov.area)) : 0;
  const DyadicCoords ds = candidate ? DyadicCoords(c0, c1, c2, 0, k) : DyadicCoords();
  const DyadicCoords dt = candidate ? DyadicCoords(c0, c1, c2, 1, k) : DyadicCoords();
  const bool progression = candidate && ds.ok && dt.ok;
  const ByArea<true> by_pow2{a, 1 / a};
  if (exact && !progression) {  // no run can take the progression: the triangle's runs at once
    const double inv_a = 1 / a;  // RN(1/A), for q = 1 (coordinates_rounded)
    if (pow2 && unit_q) coordinates_blocked<true, true>(c0, c1, c2, by_pow2, inv_a, d, runs, s, t);
    else if (pow2) coordinates_blocked<false, false>(c0, c1, c2, by_pow2, inv_a, d, runs, s, t);
    else if (unit_q) coordinates_blocked<true, false>(c0, c1, c2, ByArea<false>{a, 0}, inv_a, d, runs, s, t);
    else coordinates_blocked<false, false>(c0, c1, c2, ByArea<false>{a, 0}, inv_a, d, runs, s, t);
    return;
  }
  double ds_step = 0, dt_step = 0;
  if (progression) coordinates_at<true>(c0, c1, c2, by_pow2, d[0], d[1], d[2], ds_step, dt_step);
  for (int r = 0, off = 0; r < runs.runs; off += runs.length[r], ++r) {
    const std::array<std::int64_t, 3>& w = runs.first[r];
    const int n = runs.length[r];
    if (exact) {
      // n rounded up to 4 (the vector width): the scalar remainder loop cost more
      // than the extra lanes on runs of a few fragments. The extra lanes are the
      // next pixels' values (any double, inf or NaN: nothing traps), written past
      // the run into the next run's slots, which that run then overwrites; s and t
      // hold 3 slots more than the fragments.
      const int n4 = (n + 3) & ~3;
      const Coords f{static_cast<double>(w[0]), static_cast<double>(w[1]), static_cast<double>(w[2])};
      {  // (exact here means a progression: see above)
        std::uint64_t W = 0;  // the largest |w_k| over the lanes 0 .. n4 − 1 (the ends of each linear weight)
        for (int j = 0; j < 3; ++j)
          W = std::max({W, static_cast<std::uint64_t>(std::abs(w[static_cast<std::size_t>(j)])),
                        static_cast<std::uint64_t>(std::abs(w[static_cast<std::size_t>(j)] + (n4 - 1) * cov.dwdx[static_cast<std::size_t>(j)]))});
        if (ds.exact_for(W) && dt.exact_for(W)) {
          double s0 = 0, t0 = 0;  // the reference's value at the run's first fragment
          coordinates_at<true>(c0, c1, c2, by_pow2, f[0], f[1], f[2], s0, t0);
          float* so = s + off;
          float* to = t + off;
          for (int i = 0; i < n4; ++i) {
            const double fi = static_cast<double>(i);
            so[i] = static_cast<float>(s0 + fi * ds_step);
            to[i] = static_cast<float>(t0 + fi * dt_step);
          }
          continue;
        }
      }
      // (Here the triangle is a progression, so A = 2^k and q = 1: the other cases
      // took coordinates_blocked above.)
      coordinates_stepped<true>(c0, c1, c2, by_pow2, f, d, n4, s + off, t + off);
      continue;
    }
    for (int i = 0; i < n; ++i) {  // the reference's conversions of the int64 weights
      double wd[3];
      for (int k = 0; k < 3; ++k) wd[k] = static_cast<double>(w[k] + i * cov.dwdx[k]);
      double sd = 0, td = 0;
      coordinates_at<false>(c0, c1, c2, ByArea<false>{a, 0}, wd[0], wd[1], wd[2], sd, td);
      s[off + i] = static_cast<float>(sd);
      t[off + i] = static_cast<float>(td);
    }
  }
}

unsigned coords_reuse_mask(const ShadingPlan& plan, const std::array<const WindowVertex*, 3>& tv) {
  unsigned mask = 0;
  int computed = -1;  // the last unit whose coordinates are computed
  for (int u = 0; u < kShadeUnits; ++u) {
    if (!plan.sample[u]) continue;
    bool same = computed >= 0;
    for (int k = 0; k < 3 && same; ++k) same = tv[k]->tcw[computed] == tv[k]->tcw[u];
    if (same) mask |= 1u << u;
    else computed = u;
  }
  return mask;
}

bool Context::span_path_supported(const ShadingState& st, const ShadingPlan& plan, bool shade) const {
  if (profile_.arithmetic != Arithmetic::Fixed) return false;
  if (shade)
    for (int u = 0; u < kShadeUnits; ++u)
      if (plan.sample[u] && !sample_span_supported(*st.units[u].texture, st.units[u].dims, st.sample)) return false;
  return true;
}

void Context::shade_runs_fast(const ShadingState& st, const ShadingPlan& plan, const GroupTriangle* tris,
                              int triangles, const FastRuns& runs, bool flat, bool shade, std::uint16_t* out,
                              std::uint32_t* depth, SpanScratch& sc) {
  const int n = runs.count;
  const auto N = static_cast<std::size_t>(n);
  sc.lane.resize(N);
  // Per-triangle work (colour and depth codes, texture coordinates) triangle by
  // triangle, each on its own runs and fragments; the rest once for the group.
  auto each = [&](auto&& f) {
    for (int i = 0; i < triangles; ++i) {
      const GroupTriangle& g = tris[i];
      const int r1 = i + 1 < triangles ? tris[i + 1].run_begin : runs.runs;
      const int f1 = i + 1 < triangles ? tris[i + 1].fragment_begin : n;
      f(g, FastRuns{runs.first + g.run_begin, runs.length + g.run_begin, r1 - g.run_begin, f1 - g.fragment_begin},
        static_cast<std::size_t>(g.fragment_begin));
    }
  };
  if (depth)  // (null: no depth buffer, or a raster-cache replay brings the codes)
    each([&](const GroupTriangle& g, const FastRuns& r, std::size_t off) {
      interpolate_code_runs(r.first, r.length, r.runs, g.cov.dwdx, g.cov.area, g.tv[0]->depth, g.tv[1]->depth,
                            g.tv[2]->depth, depth + off);
    });
  // s/q and t/q of unit u into s, t (N + 3 slots). texture_coordinates writes up
  // to 3 slots past a triangle's last run: into the next triangle's, which that
  // one then overwrites, or into the 3 spare slots after the last.
  auto compute_coordinates = [&](int u, float* s, float* t) {
    each([&](const GroupTriangle& g, const FastRuns& r, std::size_t off) {
      texture_coordinates(g.tv, u, g.cov, r, s + off, t + off);
    });
  };
  // Unit u's s/q, t/q: a replay's recorded ones when every triangle of the group
  // has, for unit u, the bits the recording's had (texture_coordinates is a
  // function of those bits, the coverage and the runs, which a replay shares);
  // else computed, and kept by a recording that has none yet.
  const float* s_of = nullptr;  // (set by the first sampled unit's coordinates)
  const float* t_of = nullptr;
  auto coordinates = [&](int u) {
    const RecordedGroup* from = sc.coords_from;
    bool recorded = from && from->s.size() == N + 3 && from->tcw.size() == static_cast<std::size_t>(triangles);
    for (int i = 0; i < triangles && recorded; ++i)
      for (std::size_t k = 0; k < 3 && recorded; ++k)
        recorded = std::memcmp(tris[i].tv[k]->tcw[static_cast<std::size_t>(u)].data(), from->tcw[static_cast<std::size_t>(i)][k].data(),
                               sizeof(double) * 3) == 0;
    if (recorded) {
      s_of = from->s.data();
      t_of = from->t.data();
      ++sc.coords_recorded;
      return;
    }
    RecordedGroup* to = sc.coords_to;
    if (!to || !to->s.empty()) {
      compute_coordinates(u, sc.s.data(), sc.t.data());
      s_of = sc.s.data();
      t_of = sc.t.data();
    } else {  // the first computed for a recording: straight into it
      to->s = sc.recording->arena.make<float>(N + 3);
      to->t = sc.recording->arena.make<float>(N + 3);
      compute_coordinates(u, to->s.data(), to->t.data());
      s_of = to->s.data();
      t_of = to->t.data();
      to->tcw = sc.recording->arena.make<std::array<std::array<double, 3>, 3>>(static_cast<std::size_t>(triangles));
      for (int i = 0; i < triangles; ++i)
        std::construct_at(&to->tcw[static_cast<std::size_t>(i)],
                          std::array<std::array<double, 3>, 3>{tris[i].tv[0]->tcw[static_cast<std::size_t>(u)],
                                                               tris[i].tv[1]->tcw[static_cast<std::size_t>(u)],
                                                               tris[i].tv[2]->tcw[static_cast<std::size_t>(u)]});
    }
  };
  auto colors = [&](bool secondary, std::uint16_t* to) {
    each([&](const GroupTriangle& g, const FastRuns& r, std::size_t off) {
      interpolate_colors(g.tv, secondary, g.cov, r, flat, sc.lane.data(), to + 4 * off);
    });
  };
  // One unit whose REPLACE of an RGBA texture at the colour width is the whole
  // result (no other unit, no colour sum, no combiners): its texels are the
  // fragments' colours (texture_environment's REPLACE: Ct, At), sampled straight
  // into `out`; the primary colour is not needed.
  int replace_unit = -1;
  if (shade && !combiners_.enabled && !plan.color_sum) {
    int units = 0;
    for (int u = 0; u < kShadeUnits; ++u)
      if (plan.sample[u] || plan.env[u]) {
        ++units;
        replace_unit = u;
      }
    if (units != 1 || !plan.sample[replace_unit] || !plan.env[replace_unit] ||
        st.units[replace_unit].env.mode != gl::REPLACE)
      replace_unit = -1;
    if (replace_unit >= 0) {
      const TextureObject& tex = *st.units[replace_unit].texture;
      const TextureImage& level = tex.levels[static_cast<std::size_t>(tex.params.base_level)];
      if (level.base != BaseFormat::RGBA || level.bits != st.color.bits) replace_unit = -1;
    }
  }
  if (replace_unit >= 0) {
    sc.s.resize(N + 3);  // (texture_coordinates writes up to 3 slots past the last run)
    sc.t.resize(N + 3);
    coordinates(replace_unit);
    sample_span_fixed(*st.units[replace_unit].texture, st.units[replace_unit].dims, s_of, t_of, n, st.sample, out);
    return;
  }
  colors(false, out);  // the primary colour, shaded in place
  if (!shade) return;

  const bool combine = combiners_.enabled;
  const combiners::CombinerPlan* cp = combine ? &combiner_plan() : nullptr;
  const bool need_secondary = combine ? cp->secondary_needed : plan.color_sum;
  if (need_secondary) {
    sc.secondary.resize(4 * N);
    colors(true, sc.secondary.data());
  }
  // Texture coordinates (the per-fragment path's operations exactly: Σ in k
  // order from 0, divided by A, then s/q and t/q) and the span's texels.
  sc.s.resize(N + 3);  // (texture_coordinates writes up to 3 slots past the last run)
  sc.t.resize(N + 3);
  // Units fed the same coordinates (the paper's maps on units 0 and 1) get the
  // same s/q, t/q: computed once (coords_reuse_mask, the same for every triangle).
  const unsigned reuse = coords_reuse_mask(plan, tris[0].tv);
  for (int u = 0; u < kShadeUnits; ++u) {
    if (!plan.sample[u]) continue;
    if (!(reuse & (1u << u))) coordinates(u);
    sc.texels[u].resize(4 * N);
    sample_span_fixed(*st.units[u].texture, st.units[u].dims, s_of, t_of, n, st.sample, sc.texels[u].data());
  }
  auto texel_bits = [&](int u) {
    const TextureObject& tex = *st.units[u].texture;
    return tex.levels[static_cast<std::size_t>(tex.params.base_level)].bits;
  };

  if (combine) {
    // combine_fragment for the whole run: texels at the profile's texture width.
    if (cp->primary_needed) {
      sc.primary.assign(out, out + 4 * N);
    }
    combiners::CombinerInputsFixed in;
    in.count = n;
    in.primary = cp->primary_needed ? sc.primary.data() : nullptr;
    in.secondary = need_secondary ? sc.secondary.data() : nullptr;
    for (int u = 0; u < kShadeUnits; ++u) {
      if (!plan.sample[u]) continue;
      const int bits = texel_bits(u);
      if (bits != profile_.texture_bits)
        for (std::uint16_t& k : sc.texels[u]) k = static_cast<std::uint16_t>(unorm_convert(k, bits, profile_.texture_bits));
      in.texture[u] = sc.texels[u].data();
    }
    const std::array<double, 4> fog{0, 0, 0, 0};  // fog not modelled (combine_fragment)
    if (!combiners::shade_span_fast(*cp, in, fog, out)) combiners::shade_span(*cp, in, fog, out);
    return;
  }

  // Texture environments (texture_environments), unit by unit, in place on `out`;
  // COMBINE may read the primary colour, kept aside first.
  const int bits = st.color.bits;
  bool primary_kept = false;
  for (int u = 0; u < kShadeUnits && !primary_kept; ++u)
    if (plan.env[u] && st.units[u].env.mode == gl::COMBINE) {
      sc.primary.assign(out, out + 4 * N);
      primary_kept = true;
    }
  for (int u = 0; u < kShadeUnits; ++u) {
    if (!plan.env[u]) continue;
    const TextureObject& tex = *st.units[u].texture;
    const BaseFormat base = tex.levels[static_cast<std::size_t>(tex.params.base_level)].base;
    const TexEnvState& env = st.units[u].env;
    if (plan.sample[u] && texture_environment_span_fixed(env, base, texel_bits(u), out, sc.primary.data(),
                                                         sc.texels[u].data(), n, st.color, out))
      continue;
    // No integer kernel: texture_environment per fragment (COMBINE reads the
    // primary colour, kept aside before the first unit changes `out`).
    if (!primary_kept) {  // (units before this one may have changed `out`)
      sc.primary.resize(4 * N);
      colors(false, sc.primary.data());
      primary_kept = true;
    }
    Texel t{};
    t.base = base;
    if (plan.sample[u]) t.bits = texel_bits(u);
    for (int f = 0; f < n; ++f) {
      const std::size_t o = 4 * static_cast<std::size_t>(f);
      Rgba prev, prim;
      for (int c = 0; c < 4; ++c) {
        prev.code[c] = out[o + c];
        prim.code[c] = sc.primary[o + c];
        if (plan.sample[u]) t.code[c] = sc.texels[u][o + c];
      }
      const Rgba r = texture_environment(env, prev, prim, t, st.color);
      for (int c = 0; c < 4; ++c) out[o + c] = static_cast<std::uint16_t>(r.code[c]);
    }
  }
  if (plan.color_sum) {  // color_sum on codes of one width: min(p + s, 2^m − 1)
    const std::uint32_t m = unorm_max(bits);
    for (std::size_t i = 0; i < 4 * N; i += 4)
      for (std::size_t c = 0; c < 3; ++c)
        out[i + c] = static_cast<std::uint16_t>(std::min<std::uint32_t>(std::uint32_t{out[i + c]} + sc.secondary[i + c], m));
  }
}

}  // namespace ffsim

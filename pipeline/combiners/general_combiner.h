// One general combiner stage (RC §3.8.12.2): both portions read the stage's input
// register set, then the outputs are written (RGB outputs to R,G,B, alpha outputs
// to A of the named registers).
//
//   AB = A∘B or A·B (dot product, broadcast to R,G,B; RGB portion only)
//   CD = C∘D or C·D
//   SUM = AB + CD, or MUX = (spare0.a >= 1/2 ? CD : AB) on the input SPARE0 alpha
//   out = clamp((X + bias) * scale, -1, 1) for X in AB, CD, SUM/MUX
//
// Sum and mux combine the selected AB and CD results, dot products included
// (choice #26; RC v1.6 issue "the hardware is capable of summing the two dot
// products").
//
// Fixed point (docs/numerics.md §10): mapped variables are integers in units of
// 1/(2M), so products and dot products are exact integers in units of 1/(4M^2);
// bias -1/2 is -2M^2 of those units; the result is rounded once, half away from
// zero, to the register grid: code = round((X + bias) * 2 * scale / (8M)), then
// clamped to [-M, M]. In CombinerRounding::PerProduct every product is first
// rounded to the register grid as well.
#pragma once
#include <algorithm>
#include <cstdint>

#include "pipeline/combiners/combiner_plan.h"
#include "pipeline/number/snorm.h"

namespace ffsim::combiners {

namespace detail {

inline std::int64_t product(std::int64_t x, std::int64_t y, std::int64_t four_m, bool per_product) {
  const std::int64_t t = x * y;
  return per_product ? four_m * div_round_half_away(t, four_m) : t;
}

inline std::int32_t output_code(std::int64_t x, const PlannedPortion& p, std::int32_t M) {
  const std::int64_t m = M;
  const std::int64_t biased = p.bias ? x - 2 * m * m : x;
  return static_cast<std::int32_t>(std::clamp(div_round_half_away(biased * p.scale2, 8 * m), -m, m));
}

template <int L>
void portion_fixed(const PlannedPortion& p, const RegisterSet<std::int32_t>& in, std::int32_t M, bool per_product,
                   std::int32_t (&out)[3][3]) {
  std::int64_t mv[4][3] = {};
  for (int v = 0; v < 4; ++v) {
    if (v < 2 ? !p.need_ab : !p.need_cd) continue;
    const PlannedVar& var = p.var[static_cast<std::size_t>(v)];
    for (int l = 0; l < L; ++l) mv[v][l] = map_fixed(var.k, in.v[var.reg][var.comp[static_cast<std::size_t>(l)]]);
  }
  const std::int64_t four_m = 4 * std::int64_t{M};
  std::int64_t ab[3] = {}, cd[3] = {};
  auto products = [&](int a, int b, bool dot, std::int64_t(&r)[3]) {
    if (L == 3 && dot) {
      std::int64_t t = 0;
      for (int l = 0; l < 3; ++l) t += product(mv[a][l], mv[b][l], four_m, per_product);
      r[0] = r[1] = r[2] = t;
    } else {
      for (int l = 0; l < L; ++l) r[l] = product(mv[a][l], mv[b][l], four_m, per_product);
    }
  };
  if (p.need_ab) products(0, 1, p.ab_dot, ab);
  if (p.need_cd) products(2, 3, p.cd_dot, cd);
  const bool mux_cd = 2 * std::int64_t{in.v[kSpare0][3]} >= M;  // spare0.a >= 1/2, exact
  for (int o = 0; o < 3; ++o) {
    if (p.dest[static_cast<std::size_t>(o)] < 0) continue;
    for (int l = 0; l < L; ++l) {
      const std::int64_t x = o == 0 ? ab[l] : o == 1 ? cd[l] : p.mux ? (mux_cd ? cd[l] : ab[l]) : ab[l] + cd[l];
      out[o][l] = output_code(x, p, M);
    }
  }
}

template <class T, int L>
void portion_float(const PlannedPortion& p, const RegisterSet<T>& in, T (&out)[3][3]) {
  T mv[4][3] = {};
  for (int v = 0; v < 4; ++v) {
    if (v < 2 ? !p.need_ab : !p.need_cd) continue;
    const PlannedVar& var = p.var[static_cast<std::size_t>(v)];
    for (int l = 0; l < L; ++l) mv[v][l] = map_float(var.mapping, in.v[var.reg][var.comp[static_cast<std::size_t>(l)]]);
  }
  T ab[3] = {}, cd[3] = {};
  auto products = [&](int a, int b, bool dot, T(&r)[3]) {
    if (L == 3 && dot) {
      const T t = mv[a][0] * mv[b][0] + mv[a][1] * mv[b][1] + mv[a][2] * mv[b][2];
      r[0] = r[1] = r[2] = t;
    } else {
      for (int l = 0; l < L; ++l) r[l] = mv[a][l] * mv[b][l];
    }
  };
  if (p.need_ab) products(0, 1, p.ab_dot, ab);
  if (p.need_cd) products(2, 3, p.cd_dot, cd);
  const bool mux_cd = in.v[kSpare0][3] >= T(0.5);
  const T bias = p.bias ? T(-0.5) : T(0);
  const T scale = T(p.scale2) / T(2);
  for (int o = 0; o < 3; ++o) {
    if (p.dest[static_cast<std::size_t>(o)] < 0) continue;
    for (int l = 0; l < L; ++l) {
      const T x = o == 0 ? ab[l] : o == 1 ? cd[l] : p.mux ? (mux_cd ? cd[l] : ab[l]) : ab[l] + cd[l];
      out[o][l] = std::clamp((x + bias) * scale, T(-1), T(1));
    }
  }
}

template <class T>
void write_outputs(const PlannedStage& st, RegisterSet<T>& regs, const T (&rgb)[3][3], const T (&alpha)[3][3]) {
  if (st.rgb.run)
    for (int o = 0; o < 3; ++o)
      if (const int d = st.rgb.dest[static_cast<std::size_t>(o)]; d >= 0)
        for (int c = 0; c < 3; ++c) regs.v[d][c] = rgb[o][c];
  if (st.alpha.run)
    for (int o = 0; o < 3; ++o)
      if (const int d = st.alpha.dest[static_cast<std::size_t>(o)]; d >= 0) regs.v[d][3] = alpha[o][0];
}

}  // namespace detail

// Runs stage `st` on `regs` (input set in, output set out). Fixed point.
inline void general_combiner_fixed(const PlannedStage& st, RegisterSet<std::int32_t>& regs, std::int32_t M,
                                   bool per_product) {
  std::int32_t rgb[3][3] = {}, alpha[3][3] = {};
  if (st.rgb.run) detail::portion_fixed<3>(st.rgb, regs, M, per_product, rgb);
  if (st.alpha.run) detail::portion_fixed<1>(st.alpha, regs, M, per_product, alpha);
  detail::write_outputs(st, regs, rgb, alpha);
}

// The spec formulas in T (float for the float32 profile, double for ideal).
template <class T>
void general_combiner_float(const PlannedStage& st, RegisterSet<T>& regs) {
  T rgb[3][3] = {}, alpha[3][3] = {};
  if (st.rgb.run) detail::portion_float<T, 3>(st.rgb, regs, rgb);
  if (st.alpha.run) detail::portion_float<T, 1>(st.alpha, regs, alpha);
  detail::write_outputs(st, regs, rgb, alpha);
}

}  // namespace ffsim::combiners

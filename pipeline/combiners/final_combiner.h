// The final combiner (RC §3.8.12.3):
//
//   fcoc.rgb = min(A∘B + (1 - A)∘C + D, 1),  fcoc.a = G
//
// with every variable mapped by UNSIGNED_IDENTITY (max(0,x)) or UNSIGNED_INVERT
// (1 - clamp01(x)), and two pseudo-registers: E_TIMES_F = mapped E ∘ mapped F,
// SPARE0_PLUS_SECONDARY = max(0,spare0) + max(0,secondary), clamped to [0,1] when
// COLOR_SUM_CLAMP_NV is TRUE (alpha of both is 0; only RGB usage is legal).
//
// Fixed point (docs/numerics.md §10): exact. A..F are integers in units of 1/M^2
// (E_TIMES_F needs M^2), so the RGB sum is an integer in units of 1/M^4; it is
// clamped at 1 and rounded once, half up, to the colour width N bits:
// code = floor(x * (2^N - 1) / M^4 + 1/2). G is rounded the same way from 1/M units.
#pragma once
#include <algorithm>
#include <cstdint>

#include "pipeline/combiners/combiner_plan.h"

namespace ffsim::combiners {

__extension__ using Int128 = __int128;

namespace detail {

inline std::int64_t final_reg(const PlannedVar& v, const RegisterSet<std::int32_t>& r, int lane, std::int32_t M) {
  const std::int32_t c = r.v[v.reg][v.comp[static_cast<std::size_t>(lane)]];
  return v.mapping == Mapping::UnsignedInvert ? M - std::clamp(c, 0, M) : std::max(c, 0);
}

}  // namespace detail

// Acc: an integer type that holds 6 * M^4 * (2^N - 1) * 2 (std::int64_t up to
// M = 1023 at N = 16; Int128 beyond). final_needs_int128 tells which.
inline bool final_needs_int128(std::int32_t M, int color_bits) {
  const Int128 m4 = Int128{M} * M * M * M;
  const Int128 limit = Int128{1} << 62;
  return m4 * 6 * 2 * ((Int128{1} << color_bits) - 1) >= limit;
}

template <class Acc>
void final_combiner_fixed(const PlannedFinal& f, const RegisterSet<std::int32_t>& r, std::int32_t M, int color_bits,
                          std::uint16_t* out) {
  const std::int64_t m = M, m2 = m * m;
  const Acc n = (Acc{1} << color_bits) - 1;
  const Acc m4 = Acc{m2} * m2;
  std::int64_t ef[3] = {}, sps[3] = {};
  if (f.need_ef)
    for (int l = 0; l < 3; ++l) ef[l] = detail::final_reg(f.var[4], r, l, M) * detail::final_reg(f.var[5], r, l, M);
  if (f.need_spare0_plus_secondary)
    for (int l = 0; l < 3; ++l) {
      const std::int64_t s = std::int64_t{std::max(r.v[kSpare0][l], 0)} + std::max(r.v[kSecondaryColor][l], 0);
      sps[l] = f.color_sum_clamp ? std::min(s, m) : s;
    }
  auto wide = [&](const PlannedVar& v, int l) -> std::int64_t {  // units of 1/M^2
    const bool inv = v.mapping == Mapping::UnsignedInvert;
    if (v.reg == kETimesF) return inv ? m2 - std::clamp(ef[l], std::int64_t{0}, m2) : std::max(ef[l], std::int64_t{0});
    if (v.reg == kSpare0PlusSecondary) return inv ? m2 - std::min(sps[l] * m, m2) : sps[l] * m;
    return detail::final_reg(v, r, l, M) * m;
  };
  for (int l = 0; l < 3; ++l) {
    const Acc a = wide(f.var[0], l), b = wide(f.var[1], l), c = wide(f.var[2], l), d = wide(f.var[3], l);
    Acc x = a * b + (Acc{m2} - a) * c + d * Acc{m2};
    if (x > m4) x = m4;
    out[l] = static_cast<std::uint16_t>((2 * x * n + m4) / (2 * m4));
  }
  const std::int64_t g = detail::final_reg(f.var[6], r, 0, M);
  out[3] = static_cast<std::uint16_t>((2 * Acc{g} * n + m) / (2 * m));
}

template <class T>
void final_combiner_float(const PlannedFinal& f, const RegisterSet<T>& r, T* out) {
  T ef[3] = {}, sps[3] = {};
  auto reg = [&](const PlannedVar& v, int l) { return r.v[v.reg][v.comp[static_cast<std::size_t>(l)]]; };
  if (f.need_ef)
    for (int l = 0; l < 3; ++l) ef[l] = map_float(f.var[4].mapping, reg(f.var[4], l)) * map_float(f.var[5].mapping, reg(f.var[5], l));
  if (f.need_spare0_plus_secondary)
    for (int l = 0; l < 3; ++l) {
      const T s = std::max(T(0), r.v[kSpare0][l]) + std::max(T(0), r.v[kSecondaryColor][l]);
      sps[l] = f.color_sum_clamp ? std::min(std::max(s, T(0)), T(1)) : s;
    }
  auto value = [&](const PlannedVar& v, int l) {
    const T x = v.reg == kETimesF ? ef[l] : v.reg == kSpare0PlusSecondary ? sps[l] : reg(v, l);
    return map_float(v.mapping, x);
  };
  for (int l = 0; l < 3; ++l) {
    const T a = value(f.var[0], l), b = value(f.var[1], l), c = value(f.var[2], l), d = value(f.var[3], l);
    out[l] = std::min(a * b + (T(1) - a) * c + d, T(1));
  }
  out[3] = map_float(f.var[6].mapping, reg(f.var[6], 0));
}

}  // namespace ffsim::combiners

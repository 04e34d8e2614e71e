// Blending (GL 1.2.1 §4.1.6 with EXT_blend_color, EXT_blend_minmax,
// EXT_blend_subtract; docs/numerics.md §9.5).
//
// Per component: FUNC_ADD Cs*S + Cd*D, FUNC_SUBTRACT Cs*S - Cd*D,
// FUNC_REVERSE_SUBTRACT Cd*D - Cs*S, MIN min(Cs,Cd), MAX max(Cs,Cd) (factors
// ignored); the result is clamped to [0,1] and converted back to the buffer width.
//
// Fixed profiles (m-bit codes, M = 2^m - 1): every operand and factor is a code
// over M (the blend colour is rounded to a code when a draw starts, §9.5), so the
// exact result is n / M^2 with the integer n = cs*S +- cd*D. The stored code is
// rnd(clamp01(n/M^2) * M) = floor((2n + M) / (2M)), one rounding, half up (choice
// #29); M is odd, so no ties can occur. Float profiles evaluate the same formula in
// binary64 (Float64) or binary32 (Float32), then clamp, with no quantisation.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>

#include "pipeline/gl/enums.h"

namespace ffsim {

struct BlendState {
  bool enabled = false;
  GLenum src = gl::ONE;
  GLenum dst = gl::ZERO;
  GLenum equation = gl::FUNC_ADD;
  std::array<double, 4> color{0, 0, 0, 0};  // glBlendColor, clamped to [0,1] when specified
  bool operator==(const BlendState&) const = default;
};

// Source factors of GL 1.2.1 + EXT_blend_color (SRC_ALPHA_SATURATE included).
bool valid_blend_src_factor(GLenum f);
// Destination factors: as source with SRC_COLOR / ONE_MINUS_SRC_COLOR instead of
// the DST_COLOR pair, and without SRC_ALPHA_SATURATE (GL 1.2.1 §4.1.6 Table 4.2).
bool valid_blend_dst_factor(GLenum f);
bool valid_blend_equation(GLenum e);

// clamp to [0,1] that maps NaN and -0 to +0 (so results never depend on the sign of zero).
template <class T>
constexpr T clamp01(T v) {
  return v > T(0) ? (v < T(1) ? v : T(1)) : T(0);
}

// A blend factor for channel c (0..3) with source s, destination d and constant k
// colours, as a code over M (fixed) or a value (float types: T = float or double).
// `max` is M for codes, 1 for values.
template <class T>
constexpr T blend_factor(GLenum f, int c, const T* s, const T* d, const T* k, T max) {
  switch (f) {
    case gl::ZERO: return T(0);
    case gl::ONE: return max;
    case gl::SRC_COLOR: return s[c];
    case gl::ONE_MINUS_SRC_COLOR: return max - s[c];
    case gl::DST_COLOR: return d[c];
    case gl::ONE_MINUS_DST_COLOR: return max - d[c];
    case gl::SRC_ALPHA: return s[3];
    case gl::ONE_MINUS_SRC_ALPHA: return max - s[3];
    case gl::DST_ALPHA: return d[3];
    case gl::ONE_MINUS_DST_ALPHA: return max - d[3];
    case gl::CONSTANT_COLOR: return k[c];
    case gl::ONE_MINUS_CONSTANT_COLOR: return max - k[c];
    case gl::CONSTANT_ALPHA: return k[3];
    case gl::ONE_MINUS_CONSTANT_ALPHA: return max - k[3];
    case gl::SRC_ALPHA_SATURATE: return c == 3 ? max : std::min(s[3], max - d[3]);
    default: return T(0);
  }
}

// Fixed: the exact result code of one component. cs, cd, S, D are codes over M.
constexpr std::uint32_t blend_code(GLenum eq, std::uint32_t cs, std::uint32_t S, std::uint32_t cd, std::uint32_t D,
                                   std::uint32_t M) {
  if (eq == gl::MIN) return std::min(cs, cd);
  if (eq == gl::MAX) return std::max(cs, cd);
  const std::int64_t ps = std::int64_t{cs} * S, pd = std::int64_t{cd} * D;  // over M^2
  const std::int64_t n = eq == gl::FUNC_SUBTRACT ? ps - pd : eq == gl::FUNC_REVERSE_SUBTRACT ? pd - ps : ps + pd;
  if (n <= 0) return 0;
  const std::int64_t m2 = std::int64_t{M} * M;
  if (n >= m2) return M;
  return static_cast<std::uint32_t>((2 * n + M) / (2 * std::int64_t{M}));
}

// Float: the formula in T (float or double), then clamp01.
template <class T>
constexpr T blend_value(GLenum eq, T cs, T S, T cd, T D) {
  if (eq == gl::MIN) return std::min(cs, cd);
  if (eq == gl::MAX) return std::max(cs, cd);
  const T ps = cs * S, pd = cd * D;
  const T v = eq == gl::FUNC_SUBTRACT ? ps - pd : eq == gl::FUNC_REVERSE_SUBTRACT ? pd - ps : ps + pd;
  return clamp01(v);
}

const char* blend_factor_name(GLenum f);
const char* blend_equation_name(GLenum e);

}  // namespace ffsim

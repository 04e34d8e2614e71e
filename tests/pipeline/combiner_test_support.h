// Helpers shared by the register-combiner tests: exact rationals for expected
// values (independent of the implementation's unit scaling), and a small
// harness that sets up CombinerState the way the GL calls would.
#pragma once
#include <cstdint>
#include <cstdlib>
#include <numeric>

#include "pipeline/combiners/combiner_plan.h"
#include "pipeline/combiners/register_combiners.h"

namespace ffsim::test {

// An exact rational n/d, d > 0, reduced.
struct Q {
  std::int64_t n = 0, d = 1;
  Q() = default;
  Q(std::int64_t num, std::int64_t den = 1) : n(num), d(den) {
    if (d < 0) n = -n, d = -d;
    const std::int64_t g = std::gcd(n < 0 ? -n : n, d);
    if (g > 1) n /= g, d /= g;
  }
  friend Q operator+(Q a, Q b) { return Q(a.n * b.d + b.n * a.d, a.d * b.d); }
  friend Q operator-(Q a, Q b) { return Q(a.n * b.d - b.n * a.d, a.d * b.d); }
  friend Q operator*(Q a, Q b) { return Q(a.n * b.n, a.d * b.d); }
  friend bool operator<(Q a, Q b) { return a.n * b.d < b.n * a.d; }
  friend bool operator==(Q a, Q b) { return a.n == b.n && a.d == b.d; }
  double value() const { return static_cast<double>(n) / static_cast<double>(d); }
};
inline Q qmax(Q a, Q b) { return a < b ? b : a; }
inline Q qmin(Q a, Q b) { return a < b ? a : b; }
inline Q qclamp(Q x, Q lo, Q hi) { return qmin(qmax(x, lo), hi); }

// round(x * scale) half away from zero, for the register grid (scale = M).
inline std::int64_t round_away(Q x, std::int64_t scale) {
  const Q y = x * Q(scale);
  const std::int64_t a = std::llabs(y.n);
  const std::int64_t q = (2 * a + y.d) / (2 * y.d);
  return y.n < 0 ? -q : q;
}
// round(x * scale) half up for x >= 0 (framebuffer conversion).
inline std::int64_t round_up(Q x, std::int64_t scale) {
  const Q y = x * Q(scale);
  return (2 * y.n + y.d) / (2 * y.d);
}

// RC Table NV_register_combiners.4 on exact rationals.
inline Q spec_mapping(GLenum m, Q e) {
  const Q zero(0), one(1), half(1, 2), two(2);
  switch (m) {
    case gl::UNSIGNED_IDENTITY_NV: return qmax(zero, e);
    case gl::UNSIGNED_INVERT_NV: return one - qmin(qmax(e, zero), one);
    case gl::EXPAND_NORMAL_NV: return two * qmax(zero, e) - one;
    case gl::EXPAND_NEGATE_NV: return Q(-2) * qmax(zero, e) + one;
    case gl::HALF_BIAS_NORMAL_NV: return qmax(zero, e) - half;
    case gl::HALF_BIAS_NEGATE_NV: return Q(0) - qmax(zero, e) + half;
    case gl::SIGNED_IDENTITY_NV: return e;
    default: return Q(0) - e;
  }
}

inline constexpr GLenum kMappings[8] = {gl::UNSIGNED_IDENTITY_NV, gl::UNSIGNED_INVERT_NV, gl::EXPAND_NORMAL_NV,
                                        gl::EXPAND_NEGATE_NV,     gl::HALF_BIAS_NORMAL_NV, gl::HALF_BIAS_NEGATE_NV,
                                        gl::SIGNED_IDENTITY_NV,   gl::SIGNED_NEGATE_NV};

inline combiners::CombinerConfig geforce_config() {
  return combiners::CombinerConfig::from_profile(*find_builtin_profile("geforce256"));
}

// One fragment through shade_span (fixed profile): inputs are 8-bit codes.
struct Fragment {
  std::uint16_t primary[4] = {0, 0, 0, 0};
  std::uint16_t secondary[4] = {0, 0, 0, 0};
  std::uint16_t fog_factor = 255;
  bool fog = false;
  std::uint16_t tex[4][4] = {};
  bool tex_enabled[4] = {true, true, true, true};
};

inline std::array<std::uint16_t, 4> shade_one(const combiners::CombinerPlan& plan, const Fragment& f,
                                              std::array<double, 4> fog_color = {0, 0, 0, 0}) {
  combiners::CombinerInputsFixed in;
  in.count = 1;
  in.primary = f.primary;
  in.secondary = f.secondary;
  in.fog_factor = f.fog ? &f.fog_factor : nullptr;
  for (int u = 0; u < 4; ++u) in.texture[static_cast<std::size_t>(u)] = f.tex_enabled[u] ? f.tex[u] : nullptr;
  std::array<std::uint16_t, 4> out{};
  combiners::shade_span(plan, in, fog_color, out.data());
  return out;
}

}  // namespace ffsim::test

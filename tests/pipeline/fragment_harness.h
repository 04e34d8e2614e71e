// Test harness for the per-fragment operations: owns buffers of a FragmentTarget
// and runs a span through the planned path and the full path.
#pragma once
#include <doctest/doctest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "pipeline/fragment/fragment_plan.h"

namespace ffsim::test {

struct Buffers {
  FragmentTarget t;
  std::vector<std::uint16_t> codes;
  std::vector<double> values;
  std::vector<std::uint8_t> stencil;
  std::vector<std::uint32_t> depth;

  explicit Buffers(const FragmentTarget& target) : t(target) {
    const std::size_t n = static_cast<std::size_t>(t.width) * t.height;
    if (t.arith == Arithmetic::Fixed) codes.assign(4 * n, 0);
    else values.assign(4 * n, 0.0);
    if (t.stencil_bits > 0) stencil.assign(n, 0);
    if (t.depth_bits > 0) depth.assign(n, 0);
  }
  FragmentBuffers view() {
    FragmentBuffers b;
    b.codes = codes.empty() ? nullptr : codes.data();
    b.values = values.empty() ? nullptr : values.data();
    b.stencil = stencil.empty() ? nullptr : stencil.data();
    b.depth = depth.empty() ? nullptr : depth.data();
    return b;
  }
  std::size_t px(int x, int y) const { return static_cast<std::size_t>(y) * t.width + x; }
  std::uint16_t code(int x, int y, int c) const { return codes[4 * px(x, y) + c]; }
  // Bitwise equality (doubles compared by their bits, so -0 and +0 differ).
  bool same(const Buffers& o) const {
    return codes == o.codes && stencil == o.stencil && depth == o.depth && values.size() == o.values.size() &&
           (values.empty() || std::memcmp(values.data(), o.values.data(), values.size() * sizeof(double)) == 0);
  }
};

inline void run_plan(const FragmentOpsState& s, Buffers& b, const FragmentSpan& sp) {
  const FragmentPlan plan = build_fragment_plan(fragment_plan_key(s, b.t));
  run_fragment_plan(plan, fragment_constants(s, b.t), sp, b.view(), b.t.width);
}

inline void run_full(const FragmentOpsState& s, Buffers& b, const FragmentSpan& sp) {
  run_fragment_ops_full(s, b.t, sp, b.view());
}

// Both paths on copies of `b`; requires identical results and returns them.
inline Buffers run_both(const FragmentOpsState& s, const Buffers& b, const FragmentSpan& sp) {
  Buffers p = b, f = b;
  run_plan(s, p, sp);
  run_full(s, f, sp);
  REQUIRE(p.same(f));
  return p;
}

// A fixed-colour span: one RGBA code quadruple and one depth per fragment.
inline FragmentSpan span_codes(int y, int x0, const std::vector<std::array<std::uint16_t, 4>>& rgba,
                               const std::vector<std::uint32_t>& depth = {}) {
  FragmentSpan sp;
  sp.y = y;
  sp.x0 = x0;
  sp.count = static_cast<int>(rgba.size());
  for (const auto& c : rgba) sp.codes.insert(sp.codes.end(), c.begin(), c.end());
  sp.depth = depth;
  return sp;
}

inline FragmentTarget target8(int w, int h, int stencil_bits = 8, int depth_bits = 24) {
  return {w, h, Arithmetic::Fixed, 8, stencil_bits, depth_bits};
}

}  // namespace ffsim::test

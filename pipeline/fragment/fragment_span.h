// The unit of work between fragment producers (rasterizer, DrawPixels/CopyPixels)
// and the per-fragment operations: a run of fragments on one window row.
//
// Colour representation follows the profile: fixed profiles carry codes at the
// framebuffer's colour width (fragment colour precision m = framebuffer bits,
// GL121 §2.13.9; docs/numerics.md), float profiles carry real values. Depth is a
// code at the depth buffer's width (window z already converted, GL121 §2.10.1).
#pragma once
#include <cstdint>
#include <vector>

namespace ffsim {

struct FragmentSpan {
  int y = 0;      // window row
  int x0 = 0;     // window x of the first fragment
  int count = 0;  // fragments x0 .. x0 + count - 1
  // 4 per fragment (R, G, B, A). Exactly one of the two is used, by profile.
  std::vector<std::uint16_t> codes;  // fixed profiles: codes at color_bits
  std::vector<double> values;        // float profiles: values in [0,1]
  std::vector<std::uint32_t> depth;  // one per fragment; empty when no depth is produced
};

}  // namespace ffsim

// The final write: dithering (GL 1.2.1 §4.1.7) and the per-channel colour mask,
// stencil mask and depth mask (§4.2.2). docs/numerics.md §9.7.
//
// Dithering: fragments reach the per-fragment operations with colour codes at the
// framebuffer's width (FragmentSpan), so dithering is the identity whether enabled
// or not (choice #31). The rule for a fragment wider than the buffer (f > b bits)
// is the spec's dither-disabled rule, truncation: k_b = floor(k_f * (2^b-1) / (2^f-1)).
// ffsim uses no dither matrix, so enabling DITHER never changes a value.
#pragma once
#include <cstdint>

#include "pipeline/fragment/blend.h"
#include "pipeline/number/profile.h"

namespace ffsim {

constexpr std::uint32_t dither_code(std::uint32_t k, int fragment_bits, int buffer_bits) {
  if (fragment_bits == buffer_bits) return k;
  const std::uint64_t mb = (std::uint64_t{1} << buffer_bits) - 1, mf = (std::uint64_t{1} << fragment_bits) - 1;
  return static_cast<std::uint32_t>(std::uint64_t{k} * mb / mf);
}

// The value a float-profile framebuffer stores for a fragment colour value v:
// clamp01 for Float64, binary32 rounding then clamp01 for Float32 (numerics §4).
inline double store_float_color(double v, Arithmetic a) {
  if (a == Arithmetic::Float32) return static_cast<double>(clamp01(static_cast<float>(v)));
  return clamp01(v);
}

}  // namespace ffsim

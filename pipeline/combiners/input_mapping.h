// The eight input mappings of RC Table NV_register_combiners.4, applied to each
// component e of a register before it is assigned to a combiner variable:
//
//   UNSIGNED_IDENTITY_NV  max(0, e)            HALF_BIAS_NORMAL_NV  max(0, e) - 1/2
//   UNSIGNED_INVERT_NV    1 - min(max(e,0),1)  HALF_BIAS_NEGATE_NV  -max(0, e) + 1/2
//   EXPAND_NORMAL_NV      2 max(0, e) - 1      SIGNED_IDENTITY_NV   e
//   EXPAND_NEGATE_NV      -2 max(0, e) + 1     SIGNED_NEGATE_NV     -e
//
// Every mapping except the two SIGNED ones clamps negatives to 0 first; only
// UNSIGNED_INVERT also clamps at 1.
//
// Fixed point (docs/numerics.md §10): a register code c in [-M, M] (value c/M)
// maps to an integer in units of 1/(2M), which holds every mapping exactly (the
// HALF_BIAS mappings produce half-units). The mapping is one clamp and one
// multiply-add: mapped = mul * clamp(c, lo, hi) + add.
#pragma once
#include <algorithm>
#include <cstdint>
#include <limits>

#include "pipeline/gl/enums.h"

namespace ffsim::combiners {

enum class Mapping : std::uint8_t {
  UnsignedIdentity,
  UnsignedInvert,
  ExpandNormal,
  ExpandNegate,
  HalfBiasNormal,
  HalfBiasNegate,
  SignedIdentity,
  SignedNegate,
};

// UNSIGNED_IDENTITY_NV .. SIGNED_NEGATE_NV (must be one of them).
Mapping mapping_from_gl(GLenum mapping);
GLenum mapping_to_gl(Mapping m);

struct MappingCoeffs {
  std::int32_t lo = 0, hi = 0, mul = 0, add = 0;
};

// Coefficients of `m` for registers with M = 2^(B-1) - 1.
MappingCoeffs mapping_coeffs(Mapping m, std::int32_t M);

// Mapped value of code c, in units of 1/(2M).
constexpr std::int32_t map_fixed(const MappingCoeffs& k, std::int32_t c) {
  return k.mul * std::clamp(c, k.lo, k.hi) + k.add;
}

// The spec formula in floating point (binary32 or binary64), operations in the
// table's order.
template <class T>
constexpr T map_float(Mapping m, T e) {
  const T z = T(0), one = T(1), half = T(0.5), two = T(2);
  switch (m) {
    case Mapping::UnsignedIdentity: return std::max(z, e);
    case Mapping::UnsignedInvert: return one - std::min(std::max(e, z), one);
    case Mapping::ExpandNormal: return two * std::max(z, e) - one;
    case Mapping::ExpandNegate: return -two * std::max(z, e) + one;
    case Mapping::HalfBiasNormal: return std::max(z, e) - half;
    case Mapping::HalfBiasNegate: return -std::max(z, e) + half;
    case Mapping::SignedIdentity: return e;
    case Mapping::SignedNegate: return -e;
  }
  return e;
}

}  // namespace ffsim::combiners

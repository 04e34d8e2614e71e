#include "pipeline/combiners/input_mapping.h"

namespace ffsim::combiners {

Mapping mapping_from_gl(GLenum mapping) {
  return static_cast<Mapping>(mapping - gl::UNSIGNED_IDENTITY_NV);
}

GLenum mapping_to_gl(Mapping m) { return gl::UNSIGNED_IDENTITY_NV + static_cast<GLenum>(m); }

MappingCoeffs mapping_coeffs(Mapping m, std::int32_t M) {
  constexpr std::int32_t lo_inf = std::numeric_limits<std::int32_t>::min() / 8;
  constexpr std::int32_t hi_inf = std::numeric_limits<std::int32_t>::max() / 8;
  // Units of 1/(2M): e = c/M is 2c units; 1 is 2M units; 1/2 is M units.
  switch (m) {
    case Mapping::UnsignedIdentity: return {0, hi_inf, 2, 0};
    case Mapping::UnsignedInvert: return {0, M, -2, 2 * M};
    case Mapping::ExpandNormal: return {0, hi_inf, 4, -2 * M};
    case Mapping::ExpandNegate: return {0, hi_inf, -4, 2 * M};
    case Mapping::HalfBiasNormal: return {0, hi_inf, 2, -M};
    case Mapping::HalfBiasNegate: return {0, hi_inf, -2, M};
    case Mapping::SignedIdentity: return {lo_inf, hi_inf, 2, 0};
    case Mapping::SignedNegate: return {lo_inf, hi_inf, -2, 0};
  }
  return {lo_inf, hi_inf, 2, 0};
}

}  // namespace ffsim::combiners

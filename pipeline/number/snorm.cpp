#include "pipeline/number/snorm.h"

#include <cassert>
#include <cmath>

#include "pipeline/number/unorm.h"

namespace ffsim {

std::int32_t snorm_from_double(double x, int bits) {
  assert(bits >= kMinSnormBits && bits <= kMaxSnormBits);
  if (std::isnan(x)) return 0;
  // |x| * M rounded half up is exactly the unorm conversion of |x| at the same M
  // (M = 2^(B-1) - 1 = unorm_max(B-1)), so reuse its exact arithmetic.
  const auto mag = static_cast<std::int32_t>(unorm_from_double(std::fabs(x), bits - 1));
  return x < 0 ? -mag : mag;
}

std::int32_t snorm_from_unorm(std::uint32_t k, int unorm_bits, int snorm_bits) {
  // Non-negative, so half-away equals half-up: the unorm width conversion.
  return static_cast<std::int32_t>(unorm_convert(k, unorm_bits, snorm_bits - 1));
}

}  // namespace ffsim

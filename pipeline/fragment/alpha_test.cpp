#include "pipeline/fragment/alpha_test.h"

#include <algorithm>

#include "pipeline/number/unorm.h"

namespace ffsim {

std::uint32_t alpha_ref_code(double ref, int color_bits) { return unorm_from_double(std::clamp(ref, 0.0, 1.0), color_bits); }

double alpha_ref_value(double ref, Arithmetic a) {
  const double r = std::clamp(ref, 0.0, 1.0);
  return a == Arithmetic::Float32 ? static_cast<double>(static_cast<float>(r)) : r;
}

}  // namespace ffsim

#include "pipeline/pixel_transfer/scale_bias.h"

namespace ffsim::pixel {

bool is_identity_scale_bias(const std::array<double, 4>& scale, const std::array<double, 4>& bias) {
  for (int c = 0; c < 4; ++c)
    if (scale[c] != 1.0 || bias[c] != 0.0) return false;
  return true;
}

template <class T>
void scale_bias(RgbaImage<T>& img, const std::array<double, 4>& scale, const std::array<double, 4>& bias) {
  T s[4], b[4];
  for (int c = 0; c < 4; ++c) {
    s[c] = static_cast<T>(scale[c]);
    b[c] = static_cast<T>(bias[c]);
  }
  const std::size_t n = img.size();
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 4; ++c) {
      T& v = img.px[4 * i + c];
      const T prod = v * s[c];  // one rounding for the product, one for the sum (no FMA)
      v = prod + b[c];
    }
}

template void scale_bias<float>(RgbaImage<float>&, const std::array<double, 4>&, const std::array<double, 4>&);
template void scale_bias<double>(RgbaImage<double>&, const std::array<double, 4>&, const std::array<double, 4>&);

}  // namespace ffsim::pixel

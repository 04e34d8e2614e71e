#include "pipeline/pixel_transfer/color_matrix.h"

namespace ffsim::pixel {

bool is_identity_matrix(const Matrix4& m) {
  for (int i = 0; i < 16; ++i)
    if (m[i] != (i % 5 == 0 ? 1.0 : 0.0)) return false;
  return true;
}

template <class T>
void color_matrix(RgbaImage<T>& img, const Matrix4& m, const std::array<double, 4>& scale,
                  const std::array<double, 4>& bias) {
  T M[16], s[4], b[4];
  for (int i = 0; i < 16; ++i) M[i] = static_cast<T>(m[i]);
  for (int c = 0; c < 4; ++c) {
    s[c] = static_cast<T>(scale[c]);
    b[c] = static_cast<T>(bias[c]);
  }
  const std::size_t n = img.size();
  for (std::size_t p = 0; p < n; ++p) {
    T* v = &img.px[4 * p];
    const T in[4] = {v[0], v[1], v[2], v[3]};
    for (int r = 0; r < 4; ++r) {
      const T p0 = M[r] * in[0];
      const T p1 = M[4 + r] * in[1];
      const T p2 = M[8 + r] * in[2];
      const T p3 = M[12 + r] * in[3];
      const T sum = ((p0 + p1) + p2) + p3;
      const T scaled = sum * s[r];
      v[r] = scaled + b[r];
    }
  }
}

template void color_matrix<float>(RgbaImage<float>&, const Matrix4&, const std::array<double, 4>&,
                                  const std::array<double, 4>&);
template void color_matrix<double>(RgbaImage<double>&, const Matrix4&, const std::array<double, 4>&,
                                   const std::array<double, 4>&);

}  // namespace ffsim::pixel

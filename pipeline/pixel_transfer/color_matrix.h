// Colour matrix (SGI_color_matrix; GL121 §3.6.5 "Color Matrix Transformation"):
// with the column-major matrix m on top of the COLOR stack, each rounded to T,
//   R' = (((m0 R + m4 G) + m8 B) + m12 A) * Rs + Rb    (products rounded, summed
//   G' = (((m1 R + m5 G) + m9 B) + m13 A) * Gs + Gb     left to right, no FMA)
//   B' = (((m2 R + m6 G) + m10 B) + m14 A) * Bs + Bb
//   A' = (((m3 R + m7 G) + m11 B) + m15 A) * As + Ab
// (s, b: POST_COLOR_MATRIX_x_SCALE/BIAS). No clamp.
#pragma once
#include <array>

#include "pipeline/pixel_transfer/pixel_image.h"

namespace ffsim::pixel {

using Matrix4 = std::array<double, 16>;  // column-major, as glLoadMatrixd

bool is_identity_matrix(const Matrix4& m);

template <class T>
void color_matrix(RgbaImage<T>& img, const Matrix4& m, const std::array<double, 4>& scale,
                  const std::array<double, 4>& bias);

}  // namespace ffsim::pixel

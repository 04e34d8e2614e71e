// The working representation of the pixel transfer path: groups of four real
// components (R, G, B, A) between "final expansion to RGBA" and "final
// conversion" (GL121 §3.6.4-3.6.5). The component type T is the evaluation
// precision: float (binary32) for the fixed and float32 profiles, double
// (binary64) for the ideal profile (docs/numerics.md §7).
#pragma once
#include <cstddef>
#include <vector>

#include "pipeline/number/profile.h"

namespace ffsim::pixel {

enum class Precision { Binary32, Binary64 };

// binary64 only under the ideal profile; every other profile evaluates the
// transfer path in binary32 like Mesa (spec-notes §12 item 3).
constexpr Precision precision_for(Arithmetic a) {
  return a == Arithmetic::Float64 ? Precision::Binary64 : Precision::Binary32;
}

// A value rounded to the evaluation precision (used for parameters given as
// binary64 numbers: scale, bias, matrix entries, table and filter entries).
inline double to_precision(double v, Precision p) {
  return p == Precision::Binary32 ? static_cast<double>(static_cast<float>(v)) : v;
}

// clamp01 written with ordered comparisons: NaN -> 0, -0 -> +0.
template <class T>
constexpr T clamp01(T x) {
  return x > T(0) ? (x < T(1) ? x : T(1)) : T(0);
}

template <class T>
struct RgbaImage {
  int width = 0;
  int height = 0;
  std::vector<T> px;  // 4 per pixel (R, G, B, A), row-major from row 0

  RgbaImage() = default;
  RgbaImage(int w, int h) : width(w), height(h), px(4 * static_cast<std::size_t>(w) * static_cast<std::size_t>(h), T(0)) {}
  std::size_t size() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height); }
  T* at(int x, int y) { return &px[4 * (static_cast<std::size_t>(y) * width + x)]; }
  const T* at(int x, int y) const { return &px[4 * (static_cast<std::size_t>(y) * width + x)]; }
  bool empty() const { return width <= 0 || height <= 0; }
};

}  // namespace ffsim::pixel

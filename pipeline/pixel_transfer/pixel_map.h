// RGBA -> RGBA pixel maps (GL121 §3.6.5 "Color Index Lookup"/"RGBA to RGBA
// Lookup", MAP_COLOR): each component is clamped to [0,1], its index is
// floor(c * (size - 1) + 1/2) evaluated in T, and the component is replaced by
// entry[index] of its map (R_TO_R, G_TO_G, B_TO_B, A_TO_A).
#pragma once
#include <array>
#include <cmath>
#include <vector>

#include "pipeline/pixel_transfer/pixel_image.h"

namespace ffsim::pixel {

// The table index of a [0,1]-clamped component for a table of `size` entries:
// floor(clamp01(c) * (size - 1) + 1/2) in T (shared by pixel maps and colour tables).
template <class T>
int table_index(T c, int size) {
  const T x = clamp01(c) * static_cast<T>(size - 1);
  const T i = std::floor(x + T(0.5));
  return static_cast<int>(i);
}

template <class T>
void map_color(RgbaImage<T>& img, const std::array<std::vector<double>, 4>& maps);

}  // namespace ffsim::pixel

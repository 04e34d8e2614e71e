// What the draw path keeps per window-space vertex (sim/draw.cpp builds them,
// sim/draw_span.cpp's span path and the per-fragment path read them).
#pragma once
#include <array>
#include <cstdint>

#include "pipeline/raster/triangle.h"
#include "sim/context.h"

namespace ffsim {

struct WindowVertex {
  SnappedVertex p;
  std::array<std::uint32_t, 4> color_code{}, secondary_code{};
  std::array<double, 4> color{}, secondary{};
  std::uint32_t depth = 0;
  std::array<std::array<double, 3>, kMaxTextureUnits> tcw{};  // s/w, t/w, q/w
};

}  // namespace ffsim

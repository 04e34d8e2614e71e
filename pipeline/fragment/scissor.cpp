#include "pipeline/fragment/scissor.h"

#include <algorithm>
#include <cstdint>

namespace ffsim {

WriteRect write_rect(const ScissorBox& s, int w, int h) {
  WriteRect r{0, 0, w, h};
  if (s.enabled) {
    // 64-bit sums: x + width may exceed int range for extreme glScissor arguments.
    const auto clampi = [](std::int64_t v, int lo, int hi) { return static_cast<int>(std::clamp<std::int64_t>(v, lo, hi)); };
    r.x0 = clampi(s.x, 0, w);
    r.y0 = clampi(s.y, 0, h);
    r.x1 = clampi(std::int64_t{s.x} + s.width, 0, w);
    r.y1 = clampi(std::int64_t{s.y} + s.height, 0, h);
  }
  if (r.x1 < r.x0) r.x1 = r.x0;
  if (r.y1 < r.y0) r.y1 = r.y0;
  return r;
}

SpanRange scissor_span(const WriteRect& r, int y, int x0, int count) {
  if (count <= 0 || y < r.y0 || y >= r.y1) return {0, 0};
  const std::int64_t b = std::max<std::int64_t>(0, std::int64_t{r.x0} - x0);
  const std::int64_t e = std::min<std::int64_t>(count, std::int64_t{r.x1} - x0);
  if (e <= b) return {0, 0};
  return {static_cast<int>(b), static_cast<int>(e)};
}


}  // namespace ffsim

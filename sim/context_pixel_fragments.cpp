// Fragments of pixel rectangles (DrawPixels / CopyPixels).
//
// Interim: this writes the colour through the scissor box and colour mask only.
// The per-fragment operations (alpha, stencil, depth tests, blending) replace it
// with the full GL121 §4.1 path when they land (rasterizer/fragment issue).
#include "sim/context.h"

namespace ffsim {

void Context::pixel_fragments(FragmentSpan& span) {
  const Rect r = write_rect();
  if (span.y < r.y || span.y >= r.y + r.height) return;
  const bool fl = fb_.format().float_color();
  for (int i = 0; i < span.count; ++i) {
    const int x = span.x0 + i;
    if (x < r.x || x >= r.x + r.width) continue;
    const std::size_t dst = 4 * fb_.index(x, span.y);
    for (int c = 0; c < 4; ++c) {
      if (!masks_.color[c]) continue;
      if (fl) fb_.values()[dst + c] = span.values[4 * i + c];
      else fb_.codes()[dst + c] = span.codes[4 * i + c];
    }
  }
}

}  // namespace ffsim

// Where fragments go: pixel-rectangle fragments (DrawPixels/CopyPixels) and the
// per-fragment operations.
//
// Interim implementations, replaced by their owners:
// - pixel_fragments (texturing of pixel-rectangle fragments with the raster
//   position's texture coordinates, GL121 §3.6.4) -> rasterizer/texturing work;
// - write_fragments (scissor, alpha, stencil, depth, blend, masks, GL121 §4.1)
//   -> per-fragment operations work.
// Until then: pixel fragments go straight to write_fragments, which writes colour
// through the scissor box and the colour mask.
#include "sim/context.h"

namespace ffsim {

void Context::pixel_fragments(FragmentSpan& span) { write_fragments(span); }

void Context::write_fragments(FragmentSpan& span) {
  const Rect r = write_rect();
  if (span.y < r.y || span.y >= r.y + r.height) return;
  const bool fl = fb_.format().float_color();
  for (int i = 0; i < span.count; ++i) {
    const int x = span.x0 + i;
    if (x < r.x || x >= r.x + r.width) continue;
    const std::size_t dst = 4 * fb_.index(x, span.y);
    const bool probed = probe_.hits(x, span.y);
    std::string before;
    if (probed) before = describe_color(fb_, x, span.y);
    for (int c = 0; c < 4; ++c) {
      if (!masks_.color[c]) continue;
      if (fl) fb_.values()[dst + c] = span.values[4 * i + c];
      else fb_.codes()[dst + c] = span.codes[4 * i + c];
    }
    if (probed)
      probe_.record("write_fragments",
                    std::string("fragment ") + (fl ? describe_values(&span.values[4 * static_cast<std::size_t>(i)])
                                      : describe_codes(&span.codes[4 * static_cast<std::size_t>(i)], fb_.format().color_bits)) +
                        std::string(", framebuffer ") + before + " -> " + describe_color(fb_, x, span.y));
  }
}

}  // namespace ffsim

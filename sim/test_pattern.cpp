#include "sim/test_pattern.h"

#include "pipeline/number/unorm.h"

namespace ffsim {

void fill_test_pattern(Framebuffer& fb) {
  const int w = fb.width(), h = fb.height();
  const auto& f = fb.format();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::uint32_t c8[4] = {
          w > 1 ? 255u * x / (w - 1) : 0u,
          h > 1 ? 255u * y / (h - 1) : 0u,
          255u * static_cast<std::uint32_t>((x / 8 + y / 8) % 2),
          static_cast<std::uint32_t>(x ^ y) & 255u,
      };
      const std::size_t i = fb.index(x, y);
      for (int c = 0; c < 4; ++c) {
        if (f.float_color()) fb.values()[4 * i + c] = unorm_to_double(c8[c], 8);
        else fb.codes()[4 * i + c] = static_cast<std::uint16_t>(unorm_convert(c8[c], 8, f.color_bits));
      }
      if (fb.has_stencil()) fb.stencil()[i] = static_cast<std::uint8_t>((x + 2 * y) & fb.stencil_max());
      if (fb.has_depth())
        fb.depth()[i] = w + h > 2 ? static_cast<std::uint32_t>(div_round_half_up(
                                        std::uint64_t(x + y) * fb.depth_max(), std::uint64_t(w + h - 2)))
                                  : 0u;
    }
}

}  // namespace ffsim

// A documented procedural framebuffer fill, used by `ffsim demo` and by the
// cross-build hash test. With c8 the 8-bit code of each channel at pixel (x, y)
// of a W x H buffer (integer arithmetic, / is floor division):
//   R = 255 * x / (W - 1)          (0 when W = 1)
//   G = 255 * y / (H - 1)          (0 when H = 1)
//   B = 255 * ((x / 8 + y / 8) % 2)
//   A = (x XOR y) AND 255
// Fixed color of other widths stores unorm_convert(c8, 8, bits); float color stores
// c8 / 255. Stencil = (x + 2y) AND (2^s - 1); depth = round((x + y) / (W + H - 2)
// * (2^d - 1)) (0 when W + H = 2).
#pragma once
#include "sim/framebuffer.h"

namespace ffsim {

void fill_test_pattern(Framebuffer& fb);

}  // namespace ffsim

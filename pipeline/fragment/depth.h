// Depth buffer test (GL 1.2.1 §4.1.5; docs/numerics.md §9.4): the fragment passes
// iff "z_incoming OP z_stored", both as depth-buffer codes (the rasterizer already
// converted window z to the buffer's width). A passing fragment writes its z only
// when the depth mask is true. Depth test disabled: no comparison and no write.
// No depth buffer: the test always passes, nothing is written.
#pragma once
#include "pipeline/gl/enums.h"

namespace ffsim {

struct DepthState {
  bool enabled = false;
  GLenum func = gl::LESS;
  bool operator==(const DepthState&) const = default;
};

}  // namespace ffsim

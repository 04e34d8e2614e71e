// Where fragments go: pixel-rectangle fragments (DrawPixels/CopyPixels) and the
// per-fragment operations (GL 1.2.1 §4.1) through the current plan.
//
// pixel_fragments is interim and owned by the rasterizer/texturing work
// (texturing of pixel-rectangle fragments with the raster position's texture
// coordinates, GL121 §3.6.4); until then pixel fragments go straight to
// write_fragments.
#include "sim/context.h"

namespace ffsim {

void Context::pixel_fragments(FragmentSpan& span) { write_fragments(span); }

void Context::write_fragments(FragmentSpan& span) {
  update_fragment_plan();
  FragmentBuffers b;
  if (fb_.format().float_color()) b.values = fb_.values().data();
  else b.codes = fb_.codes().data();
  if (fb_.has_stencil()) b.stencil = fb_.stencil().data();
  if (fb_.has_depth()) b.depth = fb_.depth().data();
  run_fragment_plan(*fragment_current_plan_, fragment_current_constants_, span, b, fb_.width());
}

}  // namespace ffsim

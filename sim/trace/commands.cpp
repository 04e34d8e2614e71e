// The table of bound GL commands: one registration function per area. An area
// adds its file sim/trace/commands_<area>.cpp and one line below its marker.
#include "sim/trace/binder.h"

namespace ffsim::trace {

namespace {
CommandTable build() {
  CommandTable t;
  register_core_commands(t);  // clear, masks, scissor, enable/disable, matrices
  // ==== [issue 3] pixel transfer and pixel rectangles ====
  register_pixels_commands(t);    // pixel store/transfer/maps, tables, filters, pixel rectangles, texture images

  // ==== [issue 4a] geometry, rasterization, texturing ====
  register_draw_commands(t);      // immediate mode, viewport, raster position, textures, texture environments

  // ==== [issue 4b] per-fragment operations ====
  register_fragment_commands(t);  // alpha, stencil, depth, blend, logic op

  // ==== [issue 5] register combiners ====
  register_combiners_commands(t); // NV_register_combiners(2)

  return t;
}
}  // namespace

const CommandTable& gl_commands() {
  static const CommandTable table = build();
  return table;
}

}  // namespace ffsim::trace

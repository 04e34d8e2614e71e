// The table of bound GL commands: one registration function per area. An area
// adds its file sim/trace/commands_<area>.cpp and one line below its marker.
#include "sim/trace/binder.h"

namespace ffsim::trace {

namespace {
CommandTable build() {
  CommandTable t;
  register_core_commands(t);  // clear, masks, scissor, enable/disable, matrices
  // ==== [issue 3] pixel transfer and pixel rectangles ====

  // ==== [issue 4a] geometry, rasterization, texturing ====

  // ==== [issue 4b] per-fragment operations ====

  // ==== [issue 5] register combiners ====

  return t;
}
}  // namespace

const CommandTable& gl_commands() {
  static const CommandTable table = build();
  return table;
}

}  // namespace ffsim::trace

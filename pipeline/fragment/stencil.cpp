#include "pipeline/fragment/stencil.h"

namespace ffsim {

const char* stencil_op_name(GLenum op) {
  switch (op) {
    case gl::KEEP: return "KEEP";
    case gl::ZERO: return "ZERO";
    case gl::REPLACE: return "REPLACE";
    case gl::INCR: return "INCR";
    case gl::DECR: return "DECR";
    case gl::INVERT: return "INVERT";
    case gl::INCR_WRAP: return "INCR_WRAP";
    case gl::DECR_WRAP: return "DECR_WRAP";
    default: return "?";
  }
}

}  // namespace ffsim

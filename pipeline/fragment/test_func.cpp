#include "pipeline/fragment/test_func.h"

namespace ffsim {

const char* test_func_symbol(GLenum func) {
  switch (func) {
    case gl::NEVER: return "never";
    case gl::LESS: return "<";
    case gl::EQUAL: return "==";
    case gl::LEQUAL: return "<=";
    case gl::GREATER: return ">";
    case gl::NOTEQUAL: return "!=";
    case gl::GEQUAL: return ">=";
    case gl::ALWAYS: return "always";
    default: return "?";
  }
}

}  // namespace ffsim

// The eight comparison functions shared by the alpha, stencil and depth tests
// (GL 1.2.1 §4.1.3-§4.1.5): NEVER, LESS, EQUAL, LEQUAL, GREATER, NOTEQUAL,
// GEQUAL, ALWAYS. Each test compares "incoming OP stored/reference" in the order
// the spec states for that test; the caller passes the operands in that order.
#pragma once
#include "pipeline/gl/enums.h"

namespace ffsim {

// True for the eight comparison tokens.
constexpr bool valid_test_func(GLenum f) { return f >= gl::NEVER && f <= gl::ALWAYS; }

// a OP b. `func` must be valid (an invalid token compares false).
template <class T>
constexpr bool test_func(GLenum func, T a, T b) {
  switch (func) {
    case gl::NEVER: return false;
    case gl::LESS: return a < b;
    case gl::EQUAL: return a == b;
    case gl::LEQUAL: return a <= b;
    case gl::GREATER: return a > b;
    case gl::NOTEQUAL: return a != b;
    case gl::GEQUAL: return a >= b;
    case gl::ALWAYS: return true;
    default: return false;
  }
}

// The operator as text for plan descriptions ("<", "==", ...; "never"/"always").
const char* test_func_symbol(GLenum func);

}  // namespace ffsim

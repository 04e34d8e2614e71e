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

// f(cmp), cmp(a, b) being a OP b as a function object chosen once: a loop over
// fragments inside f then has no switch per fragment. (NEVER and an invalid
// token: false.)
template <class T, class F>
decltype(auto) with_test_func(GLenum func, F&& f) {
  switch (func) {
    case gl::LESS: return f([](T a, T b) { return a < b; });
    case gl::EQUAL: return f([](T a, T b) { return a == b; });
    case gl::LEQUAL: return f([](T a, T b) { return a <= b; });
    case gl::GREATER: return f([](T a, T b) { return a > b; });
    case gl::NOTEQUAL: return f([](T a, T b) { return a != b; });
    case gl::GEQUAL: return f([](T a, T b) { return a >= b; });
    case gl::ALWAYS: return f([](T, T) { return true; });
    default: return f([](T, T) { return false; });
  }
}

// The operator as text for plan descriptions ("<", "==", ...; "never"/"always").
const char* test_func_symbol(GLenum func);

}  // namespace ffsim

// Alpha test (GL 1.2.1 §4.1.3; docs/numerics.md §9.2): the fragment passes iff
// "A_s OP ref". Fixed profiles compare codes: ref is clamped to [0,1] and
// converted like an A component, k = floor(ref * (2^m - 1) + 1/2) (choice #30),
// and the fragment's alpha is already an m-bit code. Float profiles compare
// values (float32: ref rounded to binary32 first).
#pragma once
#include <cstdint>

#include "pipeline/gl/enums.h"
#include "pipeline/number/profile.h"

namespace ffsim {

struct AlphaTestState {
  bool enabled = false;
  GLenum func = gl::ALWAYS;
  double ref = 0.0;  // clamped to [0,1] when specified (glAlphaFunc)
  bool operator==(const AlphaTestState&) const = default;
};

// The m-bit code the fixed path compares against.
std::uint32_t alpha_ref_code(double ref, int color_bits);
// The value the float paths compare against (binary32-rounded for Float32).
double alpha_ref_value(double ref, Arithmetic a);

}  // namespace ffsim

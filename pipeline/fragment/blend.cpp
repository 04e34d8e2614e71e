#include "pipeline/fragment/blend.h"

namespace ffsim {

namespace {
bool common_factor(GLenum f) {
  switch (f) {
    case gl::ZERO: case gl::ONE:
    case gl::SRC_ALPHA: case gl::ONE_MINUS_SRC_ALPHA:
    case gl::DST_ALPHA: case gl::ONE_MINUS_DST_ALPHA:
    case gl::CONSTANT_COLOR: case gl::ONE_MINUS_CONSTANT_COLOR:
    case gl::CONSTANT_ALPHA: case gl::ONE_MINUS_CONSTANT_ALPHA: return true;
    default: return false;
  }
}
}  // namespace

bool valid_blend_src_factor(GLenum f) {
  return common_factor(f) || f == gl::DST_COLOR || f == gl::ONE_MINUS_DST_COLOR || f == gl::SRC_ALPHA_SATURATE;
}

bool valid_blend_dst_factor(GLenum f) { return common_factor(f) || f == gl::SRC_COLOR || f == gl::ONE_MINUS_SRC_COLOR; }

bool valid_blend_equation(GLenum e) {
  return e == gl::FUNC_ADD || e == gl::FUNC_SUBTRACT || e == gl::FUNC_REVERSE_SUBTRACT || e == gl::MIN || e == gl::MAX;
}

const char* blend_factor_name(GLenum f) {
  switch (f) {
    case gl::ZERO: return "ZERO";
    case gl::ONE: return "ONE";
    case gl::SRC_COLOR: return "SRC_COLOR";
    case gl::ONE_MINUS_SRC_COLOR: return "ONE_MINUS_SRC_COLOR";
    case gl::DST_COLOR: return "DST_COLOR";
    case gl::ONE_MINUS_DST_COLOR: return "ONE_MINUS_DST_COLOR";
    case gl::SRC_ALPHA: return "SRC_ALPHA";
    case gl::ONE_MINUS_SRC_ALPHA: return "ONE_MINUS_SRC_ALPHA";
    case gl::DST_ALPHA: return "DST_ALPHA";
    case gl::ONE_MINUS_DST_ALPHA: return "ONE_MINUS_DST_ALPHA";
    case gl::CONSTANT_COLOR: return "CONSTANT_COLOR";
    case gl::ONE_MINUS_CONSTANT_COLOR: return "ONE_MINUS_CONSTANT_COLOR";
    case gl::CONSTANT_ALPHA: return "CONSTANT_ALPHA";
    case gl::ONE_MINUS_CONSTANT_ALPHA: return "ONE_MINUS_CONSTANT_ALPHA";
    case gl::SRC_ALPHA_SATURATE: return "SRC_ALPHA_SATURATE";
    default: return "?";
  }
}

const char* blend_equation_name(GLenum e) {
  switch (e) {
    case gl::FUNC_ADD: return "FUNC_ADD";
    case gl::FUNC_SUBTRACT: return "FUNC_SUBTRACT";
    case gl::FUNC_REVERSE_SUBTRACT: return "FUNC_REVERSE_SUBTRACT";
    case gl::MIN: return "MIN";
    case gl::MAX: return "MAX";
    default: return "?";
  }
}

}  // namespace ffsim

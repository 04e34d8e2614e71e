#include "pipeline/fragment/logic_op.h"

namespace ffsim {

const char* logic_op_expression(GLenum op) {
  switch (op) {
    case gl::CLEAR: return "0";
    case gl::AND: return "s & d";
    case gl::AND_REVERSE: return "s & ~d";
    case gl::COPY: return "s";
    case gl::AND_INVERTED: return "~s & d";
    case gl::NOOP: return "d";
    case gl::XOR: return "s ^ d";
    case gl::OR: return "s | d";
    case gl::NOR: return "~(s | d)";
    case gl::EQUIV: return "~(s ^ d)";
    case gl::INVERT: return "~d";
    case gl::OR_REVERSE: return "s | ~d";
    case gl::COPY_INVERTED: return "~s";
    case gl::OR_INVERTED: return "~s | d";
    case gl::NAND: return "~(s & d)";
    case gl::SET: return "all ones";
    default: return "?";
  }
}

const char* logic_op_name(GLenum op) {
  switch (op) {
    case gl::CLEAR: return "CLEAR";
    case gl::AND: return "AND";
    case gl::AND_REVERSE: return "AND_REVERSE";
    case gl::COPY: return "COPY";
    case gl::AND_INVERTED: return "AND_INVERTED";
    case gl::NOOP: return "NOOP";
    case gl::XOR: return "XOR";
    case gl::OR: return "OR";
    case gl::NOR: return "NOR";
    case gl::EQUIV: return "EQUIV";
    case gl::INVERT: return "INVERT";
    case gl::OR_REVERSE: return "OR_REVERSE";
    case gl::COPY_INVERTED: return "COPY_INVERTED";
    case gl::OR_INVERTED: return "OR_INVERTED";
    case gl::NAND: return "NAND";
    case gl::SET: return "SET";
    default: return "?";
  }
}

}  // namespace ffsim

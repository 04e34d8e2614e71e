// Colour logic op (GL 1.2.1 §4.1.8): one of 16 bitwise functions of the source
// and destination codes, replacing blending when COLOR_LOGIC_OP is enabled. Only
// meaningful on fixed (code) colour; float profiles ignore it (docs/numerics.md §9.6).
#pragma once
#include <cstdint>

#include "pipeline/gl/enums.h"

namespace ffsim {

struct LogicOpState {
  bool enabled = false;
  GLenum op = gl::COPY;
  bool operator==(const LogicOpState&) const = default;
};

constexpr bool valid_logic_op(GLenum op) { return op >= gl::CLEAR && op <= gl::SET; }

// op(s, d) on m-bit codes; M = 2^m - 1 masks the result to m bits.
constexpr std::uint32_t logic_op(GLenum op, std::uint32_t s, std::uint32_t d, std::uint32_t M) {
  std::uint32_t r = 0;
  switch (op) {
    case gl::CLEAR: r = 0; break;
    case gl::AND: r = s & d; break;
    case gl::AND_REVERSE: r = s & ~d; break;
    case gl::COPY: r = s; break;
    case gl::AND_INVERTED: r = ~s & d; break;
    case gl::NOOP: r = d; break;
    case gl::XOR: r = s ^ d; break;
    case gl::OR: r = s | d; break;
    case gl::NOR: r = ~(s | d); break;
    case gl::EQUIV: r = ~(s ^ d); break;
    case gl::INVERT: r = ~d; break;
    case gl::OR_REVERSE: r = s | ~d; break;
    case gl::COPY_INVERTED: r = ~s; break;
    case gl::OR_INVERTED: r = ~s | d; break;
    case gl::NAND: r = ~(s & d); break;
    case gl::SET: r = ~0u; break;
    default: r = s; break;
  }
  return r & M;
}

// The op as an expression of s and d for plan descriptions ("s ^ d").
const char* logic_op_expression(GLenum op);
const char* logic_op_name(GLenum op);

}  // namespace ffsim

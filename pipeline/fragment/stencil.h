// Stencil test and operations (GL 1.2.1 §4.1.4, EXT_stencil_wrap; docs/numerics.md
// §9.3). With s stencil bits and smax = 2^s - 1:
//  - the reference is clamped to [0, smax] when used;
//  - the test is (ref & mask) OP (stored & mask), mask = value mask & smax;
//  - a failing fragment gets `sfail` and is discarded; a passing one gets `dpfail`
//    or `dppass` by the depth test (dppass when the depth test is disabled);
//  - INCR/DECR saturate at smax/0, INCR_WRAP/DECR_WRAP wrap modulo 2^s, INVERT is
//    the bitwise NOT of the s bits, REPLACE writes the clamped reference;
//  - every write goes through the write mask: new = (old & ~wm) | (op(old) & wm).
#pragma once
#include <cstdint>

#include "pipeline/gl/enums.h"

namespace ffsim {

struct StencilState {
  bool enabled = false;
  GLenum func = gl::ALWAYS;
  std::int32_t ref = 0;                 // as given; clamped to [0, smax] when used
  std::uint32_t value_mask = 0xFFFFFFFFu;  // low s bits used
  GLenum sfail = gl::KEEP, dpfail = gl::KEEP, dppass = gl::KEEP;
  bool operator==(const StencilState&) const = default;
};

constexpr bool valid_stencil_op(GLenum op) {
  return op == gl::KEEP || op == gl::ZERO || op == gl::REPLACE || op == gl::INCR || op == gl::DECR ||
         op == gl::INVERT || op == gl::INCR_WRAP || op == gl::DECR_WRAP;
}

// The reference clamped to [0, smax].
constexpr std::uint32_t stencil_ref_clamped(std::int32_t ref, std::uint32_t smax) {
  return ref < 0 ? 0u : (static_cast<std::uint32_t>(ref) > smax ? smax : static_cast<std::uint32_t>(ref));
}

// op(old) before the write mask. `ref` is already clamped.
constexpr std::uint32_t stencil_op(GLenum op, std::uint32_t old, std::uint32_t ref, std::uint32_t smax) {
  switch (op) {
    case gl::ZERO: return 0;
    case gl::REPLACE: return ref;
    case gl::INCR: return old < smax ? old + 1 : smax;
    case gl::DECR: return old > 0 ? old - 1 : 0;
    case gl::INVERT: return ~old & smax;
    case gl::INCR_WRAP: return (old + 1) & smax;
    case gl::DECR_WRAP: return (old - 1) & smax;
    default: return old;  // KEEP
  }
}

// The stored value after applying `op` through write mask `wm` (already & smax).
constexpr std::uint32_t stencil_write(GLenum op, std::uint32_t old, std::uint32_t ref, std::uint32_t smax,
                                      std::uint32_t wm) {
  return (old & ~wm) | (stencil_op(op, old, ref, smax) & wm);
}

const char* stencil_op_name(GLenum op);

}  // namespace ffsim

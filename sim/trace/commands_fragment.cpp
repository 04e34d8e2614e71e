// Trace commands for the per-fragment operations (GL121 §4.1.3-§4.1.8,
// EXT_blend_color, EXT_blend_minmax, EXT_blend_subtract, EXT_stencil_wrap). The
// tests and blending are enabled with glEnable (ALPHA_TEST, STENCIL_TEST,
// DEPTH_TEST, BLEND, DITHER, COLOR_LOGIC_OP).
#include "sim/trace/binder.h"

namespace ffsim::trace {

void register_fragment_commands(CommandTable& t) {
  const std::vector<GLenum> funcs = {gl::NEVER, gl::LESS, gl::EQUAL, gl::LEQUAL, gl::GREATER, gl::NOTEQUAL, gl::GEQUAL, gl::ALWAYS};
  const std::vector<GLenum> stencil_ops = {gl::KEEP, gl::ZERO, gl::REPLACE, gl::INCR, gl::DECR, gl::INVERT, gl::INCR_WRAP, gl::DECR_WRAP};
  const std::vector<GLenum> logic_ops = {gl::CLEAR, gl::AND, gl::AND_REVERSE, gl::COPY, gl::AND_INVERTED, gl::NOOP,
                                         gl::XOR, gl::OR, gl::NOR, gl::EQUIV, gl::INVERT, gl::OR_REVERSE,
                                         gl::COPY_INVERTED, gl::OR_INVERTED, gl::NAND, gl::SET};

  t.bind("glAlphaFunc", &Context::alphaFunc, {Enum("func", funcs), Float32("ref")});
  t.bind("glStencilFunc", &Context::stencilFunc, {Enum("func", funcs), Int("ref"), Int("mask", 0, 0xFFFFFFFFll)});
  t.bind("glStencilOp", &Context::stencilOp, {Enum("fail", stencil_ops), Enum("zfail", stencil_ops), Enum("zpass", stencil_ops)});
  t.bind("glDepthFunc", &Context::depthFunc, {Enum("func", funcs)});
  // Blend factors and equations: any token; the GL rejects the ones it does not take.
  t.bind("glBlendFunc", &Context::blendFunc, {Enum("sfactor"), Enum("dfactor")});
  t.bind("glBlendEquation", &Context::blendEquation, {Enum("mode")});
  t.bind("glBlendColor", &Context::blendColor, {Float32("red"), Float32("green"), Float32("blue"), Float32("alpha")});
  t.alias("glBlendEquationEXT", "glBlendEquation");
  t.alias("glBlendColorEXT", "glBlendColor");
  t.bind("glLogicOp", &Context::logicOp, {Enum("opcode", logic_ops)});
}

}  // namespace ffsim::trace

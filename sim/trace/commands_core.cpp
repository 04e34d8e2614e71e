// Trace commands for the GL entry points of the foundation: clear values and
// glClear, write masks, scissor, capabilities, matrices (GL121 §2.10.2, §4.2).
// One line per GL call; see sim/trace/binder.h and docs/trace-format.md.
#include "sim/trace/binder.h"

namespace ffsim::trace {

void register_core_commands(CommandTable& t) {
  const std::vector<GLenum> buffer_bits = {gl::COLOR_BUFFER_BIT, gl::DEPTH_BUFFER_BIT, gl::STENCIL_BUFFER_BIT,
                                           gl::ACCUM_BUFFER_BIT};
  const std::vector<GLenum> matrix_modes = {gl::MODELVIEW, gl::PROJECTION, gl::TEXTURE, gl::COLOR};

  // §4.2.3 clear values (glClearColor takes GLclampf, glClearDepth GLclampd).
  t.bind("glClearColor", &Context::clearColor, {Float32("red"), Float32("green"), Float32("blue"), Float32("alpha")});
  t.bind("glClearStencil", &Context::clearStencil, {Int("s")});
  t.bind("glClearDepth", &Context::clearDepth, {Float("depth")});
  t.bind("glClear", &Context::clear, {Bitfield("mask", buffer_bits)}).pass();

  // §4.2.2 write masks, §4.1.2 scissor.
  t.bind("glColorMask", &Context::colorMask, {Bool("red"), Bool("green"), Bool("blue"), Bool("alpha")});
  t.bind("glStencilMask", &Context::stencilMask, {Int("mask", 0, 0xFFFFFFFFll)});
  t.bind("glDepthMask", &Context::depthMask, {Bool("flag")});
  t.bind("glScissor", &Context::scissor, {Int("x"), Int("y"), Int("width"), Int("height")});

  // §2.11 capabilities: any token; the Context raises INVALID_ENUM for unknown ones.
  t.bind("glEnable", &Context::enable, {Enum("cap")});
  t.bind("glDisable", &Context::disable, {Enum("cap")});

  // §2.10.2 matrices; the f forms round their arguments to binary32 like the C call.
  t.bind("glMatrixMode", &Context::matrixMode, {Enum("mode", matrix_modes)});
  t.bind("glLoadIdentity", &Context::loadIdentity, {});
  t.bind("glLoadMatrixd", &Context::loadMatrix, {Numbers("m", 16)});
  t.bind("glLoadMatrixf", &Context::loadMatrix, {Numbers("m", 16, true)});
  t.bind("glMultMatrixd", &Context::multMatrix, {Numbers("m", 16)});
  t.bind("glMultMatrixf", &Context::multMatrix, {Numbers("m", 16, true)});
  t.bind("glPushMatrix", &Context::pushMatrix, {});
  t.bind("glPopMatrix", &Context::popMatrix, {});
  t.bind("glTranslated", &Context::translate, {Float("x"), Float("y"), Float("z")});
  t.bind("glTranslatef", &Context::translate, {Float32("x"), Float32("y"), Float32("z")});
  t.bind("glScaled", &Context::scale, {Float("x"), Float("y"), Float("z")});
  t.bind("glScalef", &Context::scale, {Float32("x"), Float32("y"), Float32("z")});
  t.bind("glRotated", &Context::rotate, {Float("angle"), Float("x"), Float("y"), Float("z")});
  t.bind("glRotatef", &Context::rotate, {Float32("angle"), Float32("x"), Float32("y"), Float32("z")});
  t.bind("glOrtho", &Context::ortho, {Float("left"), Float("right"), Float("bottom"), Float("top"), Float("near"), Float("far")});
  t.bind("glFrustum", &Context::frustum, {Float("left"), Float("right"), Float("bottom"), Float("top"), Float("near"), Float("far")});
}

}  // namespace ffsim::trace

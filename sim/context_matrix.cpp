// glMatrixMode and the matrix operations (GL121 §2.10.2), for the MODELVIEW,
// PROJECTION, TEXTURE (per active unit) and COLOR (imaging subset) stacks.
#include <glm/gtc/type_ptr.hpp>

#include "pipeline/gl/enum_names.h"
#include "sim/context.h"

namespace ffsim {

MatrixStack& Context::current_stack() {
  switch (matrix_mode_) {
    case gl::PROJECTION: return projection_;
    case gl::TEXTURE: return texture_matrix_[active_unit_];
    case gl::COLOR: return color_matrix_;
    default: return modelview_;
  }
}

void Context::matrixMode(GLenum mode) {
  if (reject_in_begin("glMatrixMode")) return;
  if (mode != gl::MODELVIEW && mode != gl::PROJECTION && mode != gl::TEXTURE && mode != gl::COLOR) {
    error(gl::INVALID_ENUM, "glMatrixMode", gl::enum_name(mode) + " is not a matrix mode");
    return;
  }
  matrix_mode_ = mode;
}

void Context::loadIdentity() {
  if (reject_in_begin("glLoadIdentity")) return;
  current_stack().top() = glm::dmat4(1.0);
}

void Context::loadMatrix(const double m[16]) {
  if (reject_in_begin("glLoadMatrix")) return;
  current_stack().top() = glm::make_mat4(m);
}

void Context::multMatrix(const double m[16]) {
  if (reject_in_begin("glMultMatrix")) return;
  current_stack().top() = current_stack().top() * glm::make_mat4(m);
}

void Context::pushMatrix() {
  if (reject_in_begin("glPushMatrix")) return;
  if (!current_stack().push())
    error(gl::STACK_OVERFLOW, "glPushMatrix", gl::enum_name(matrix_mode_) + " stack is full (depth " +
                                                  std::to_string(current_stack().max_depth()) + ")");
}

void Context::popMatrix() {
  if (reject_in_begin("glPopMatrix")) return;
  if (!current_stack().pop())
    error(gl::STACK_UNDERFLOW, "glPopMatrix", gl::enum_name(matrix_mode_) + " stack has only one matrix");
}

void Context::translate(double x, double y, double z) {
  if (reject_in_begin("glTranslate")) return;
  current_stack().top() *= translate_matrix(x, y, z);
}
void Context::scale(double x, double y, double z) {
  if (reject_in_begin("glScale")) return;
  current_stack().top() *= scale_matrix(x, y, z);
}
void Context::rotate(double angle, double x, double y, double z) {
  if (reject_in_begin("glRotate")) return;
  current_stack().top() *= rotate_matrix(angle, x, y, z);
}

void Context::ortho(double l, double r, double b, double t, double n, double f) {
  if (reject_in_begin("glOrtho")) return;
  if (l == r || b == t || n == f) {
    error(gl::INVALID_VALUE, "glOrtho", "left = right, bottom = top or near = far");
    return;
  }
  current_stack().top() *= ortho_matrix(l, r, b, t, n, f);
}

void Context::frustum(double l, double r, double b, double t, double n, double f) {
  if (reject_in_begin("glFrustum")) return;
  if (n <= 0 || f <= 0 || l == r || b == t || n == f) {
    error(gl::INVALID_VALUE, "glFrustum", "near and far must be positive and left/right, bottom/top, near/far distinct");
    return;
  }
  current_stack().top() *= frustum_matrix(l, r, b, t, n, f);
}

}  // namespace ffsim

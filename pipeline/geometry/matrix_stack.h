// Matrix stacks (GL121 §2.10.2): MODELVIEW, PROJECTION, TEXTURE (one per unit)
// and COLOR (imaging subset, SGI_color_matrix). Matrices are binary64, column-major
// as in GL (m[col][row] in GLM), so glLoadMatrix data maps one to one.
#pragma once
#include <glm/mat4x4.hpp>
#include <vector>

namespace ffsim {

// GL121 Table 6.5 minimum depths: modelview 32, projection 2, texture 2; COLOR 2
// (SGI_color_matrix MAX_COLOR_MATRIX_STACK_DEPTH minimum).
inline constexpr int kModelviewStackDepth = 32;
inline constexpr int kProjectionStackDepth = 2;
inline constexpr int kTextureStackDepth = 2;
inline constexpr int kColorStackDepth = 2;

class MatrixStack {
 public:
  explicit MatrixStack(int max_depth) : max_depth_(max_depth), stack_{glm::dmat4(1.0)} {}
  const glm::dmat4& top() const { return stack_.back(); }
  glm::dmat4& top() { return stack_.back(); }
  int depth() const { return static_cast<int>(stack_.size()); }
  int max_depth() const { return max_depth_; }
  bool push() {  // false on overflow (caller raises STACK_OVERFLOW)
    if (depth() >= max_depth_) return false;
    stack_.push_back(stack_.back());
    return true;
  }
  bool pop() {  // false on underflow (caller raises STACK_UNDERFLOW)
    if (depth() <= 1) return false;
    stack_.pop_back();
    return true;
  }

 private:
  int max_depth_;
  std::vector<glm::dmat4> stack_;
};

// The matrices GL121 §2.10.2 defines, as column-major binary64 (exact spec formulas).
glm::dmat4 rotate_matrix(double angle_degrees, double x, double y, double z);  // axis normalised; zero axis -> identity
glm::dmat4 translate_matrix(double x, double y, double z);
glm::dmat4 scale_matrix(double x, double y, double z);
glm::dmat4 ortho_matrix(double l, double r, double b, double t, double n, double f);
glm::dmat4 frustum_matrix(double l, double r, double b, double t, double n, double f);

}  // namespace ffsim

#include "pipeline/geometry/matrix_stack.h"

#include <cmath>
#include <numbers>

namespace ffsim {

glm::dmat4 rotate_matrix(double angle_degrees, double x, double y, double z) {
  const double len = std::sqrt(x * x + y * y + z * z);
  if (len == 0.0) return glm::dmat4(1.0);
  x /= len;
  y /= len;
  z /= len;
  const double a = angle_degrees * std::numbers::pi / 180.0;
  const double c = std::cos(a), s = std::sin(a), t = 1.0 - c;
  // GL121 §2.10.2: R = u u^T + cos(θ)(I - u u^T) + sin(θ) S, written row by row.
  glm::dmat4 m(1.0);
  m[0][0] = x * x * t + c;     m[1][0] = x * y * t - z * s; m[2][0] = x * z * t + y * s;
  m[0][1] = y * x * t + z * s; m[1][1] = y * y * t + c;     m[2][1] = y * z * t - x * s;
  m[0][2] = z * x * t - y * s; m[1][2] = z * y * t + x * s; m[2][2] = z * z * t + c;
  return m;
}

glm::dmat4 translate_matrix(double x, double y, double z) {
  glm::dmat4 m(1.0);
  m[3][0] = x;
  m[3][1] = y;
  m[3][2] = z;
  return m;
}

glm::dmat4 scale_matrix(double x, double y, double z) {
  glm::dmat4 m(1.0);
  m[0][0] = x;
  m[1][1] = y;
  m[2][2] = z;
  return m;
}

glm::dmat4 ortho_matrix(double l, double r, double b, double t, double n, double f) {
  glm::dmat4 m(1.0);
  m[0][0] = 2.0 / (r - l);
  m[1][1] = 2.0 / (t - b);
  m[2][2] = -2.0 / (f - n);
  m[3][0] = -(r + l) / (r - l);
  m[3][1] = -(t + b) / (t - b);
  m[3][2] = -(f + n) / (f - n);
  return m;
}

glm::dmat4 frustum_matrix(double l, double r, double b, double t, double n, double f) {
  glm::dmat4 m(0.0);
  m[0][0] = 2.0 * n / (r - l);
  m[1][1] = 2.0 * n / (t - b);
  m[2][0] = (r + l) / (r - l);
  m[2][1] = (t + b) / (t - b);
  m[2][2] = -(f + n) / (f - n);
  m[2][3] = -1.0;
  m[3][2] = -2.0 * f * n / (f - n);
  return m;
}

}  // namespace ffsim

// Matrix formulas of GL121 §2.10.2, checked against hand-derived entries.
#include <doctest/doctest.h>

#include "pipeline/geometry/matrix_stack.h"

using namespace ffsim;

TEST_CASE("matrix: rotate 90 degrees about z maps x to y") {
  const glm::dmat4 r = rotate_matrix(90, 0, 0, 2);  // axis need not be unit length
  const glm::dvec4 v = r * glm::dvec4(1, 0, 0, 1);
  CHECK(v.x == doctest::Approx(0.0).epsilon(1e-15));
  CHECK(v.y == doctest::Approx(1.0));
  CHECK(rotate_matrix(30, 0, 0, 0) == glm::dmat4(1.0));
}

TEST_CASE("matrix: ortho maps the box corners to the NDC cube, frustum maps near to -1") {
  const glm::dmat4 o = ortho_matrix(0, 4, 0, 2, -1, 1);
  const glm::dvec4 a = o * glm::dvec4(4, 2, 1, 1);
  CHECK(a.x == 1.0);
  CHECK(a.y == 1.0);
  CHECK(a.z == -1.0);  // z_eye = +1 is the near plane (z_eye = -near, near = -1): NDC -1
  const glm::dmat4 f = frustum_matrix(-1, 1, -1, 1, 1, 10);
  const glm::dvec4 n = f * glm::dvec4(0, 0, -1, 1);
  CHECK(n.z / n.w == doctest::Approx(-1.0));
  const glm::dvec4 fa = f * glm::dvec4(0, 0, -10, 1);
  CHECK(fa.z / fa.w == doctest::Approx(1.0));
}

TEST_CASE("matrix stack: push/pop limits") {
  MatrixStack s(2);
  CHECK(s.push());
  s.top() = translate_matrix(1, 2, 3);
  CHECK_FALSE(s.push());
  CHECK(s.pop());
  CHECK(s.top() == glm::dmat4(1.0));
  CHECK_FALSE(s.pop());
}

// Matrix formulas of GL121 §2.10.2, checked against hand-derived entries.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>

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

TEST_CASE("matrix: identity_times is GLM's identity product bit for bit") {
  // Exhaustive over every combination of per-component classes (+0, −0, ±small,
  // ±large, ±inf, NaN): 12^4 vectors, compared as bits with glm::dmat4(1.0) * v
  // (signed zeros included).
  const double values[] = {0.0, -0.0, 0.75, -0.75, 3e-310, -3e-310, 1e300, -1e300,
                           INFINITY, -INFINITY, NAN, -NAN};
  const glm::dmat4 identity(1.0);
  int compared = 0;
  for (double a : values)
    for (double b : values)
      for (double c : values)
        for (double d : values) {
          const glm::dvec4 v(a, b, c, d);
          const glm::dvec4 want = identity * v, got = identity_times(v);
          for (int k = 0; k < 4; ++k) {
            CAPTURE(a);
            CAPTURE(b);
            CAPTURE(c);
            CAPTURE(d);
            CAPTURE(k);
            // (A NaN's sign and payload follow the compiler's operand order, which
            // GLM's own product does not fix either: any NaN for a NaN.)
            CHECK(((std::isnan(got[k]) && std::isnan(want[k])) || std::memcmp(&got[k], &want[k], sizeof(double)) == 0));
          }
          ++compared;
        }
  CHECK(compared == 12 * 12 * 12 * 12);
}

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "bumpshadow/detmath.h"

using namespace ffsim::bumpshadow;

// The deterministic functions against the C library (which glibc documents as
// accurate to about 1 ulp): both must agree to a few ulp over the ranges used.
TEST_CASE("detmath: sin, cos, tan, atan, atan2, asin match the C library to a few ulp") {
  double worst = 0;
  auto check = [&](double got, double want) {
    const double err = std::abs(got - want) / std::max(1.0, std::abs(want));
    worst = std::max(worst, err);
    CHECK(err <= 1e-15);  // relative (absolute below 1): about 4 ulp
  };
  for (int i = -20000; i <= 20000; ++i) {
    const double x = i * 0.00137;  // about -27.4 .. 27.4
    check(det::sin(x), std::sin(x));
    check(det::cos(x), std::cos(x));
    check(det::atan(x), std::atan(x));
    check(det::atan(x * 1e3), std::atan(x * 1e3));
    const double y = 0.75 * std::sin(3.1 * x) + 0.01;
    check(det::atan2(y, std::cos(x)), std::atan2(y, std::cos(x)));
    if (std::abs(x) < 1.4) check(det::tan(x), std::tan(x));
    if (std::abs(x) <= 1) check(det::asin(x), std::asin(x));
  }
  CHECK(det::sin(0.0) == 0.0);
  CHECK(det::cos(0.0) == 1.0);
  CHECK(det::atan2(0.0, 0.0) == 0.0);
  CHECK(det::atan2(1.0, 0.0) == doctest::Approx(std::numbers::pi / 2));
  CHECK(det::atan2(-1.0, -1.0) == doctest::Approx(-3 * std::numbers::pi / 4));
  CHECK(det::asin(1.0) == doctest::Approx(std::numbers::pi / 2));
  CHECK(det::atan(std::numeric_limits<double>::infinity()) == doctest::Approx(std::numbers::pi / 2));
  CHECK(worst > 0);  // the comparison ran on real values
}

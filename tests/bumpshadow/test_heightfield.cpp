#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "bumpshadow/heightfield.h"

using namespace ffsim::bumpshadow;

TEST_CASE("heightfield: border rules wrap and clamp") {
  HeightField h(3, 2, {0, 1, 2, 3, 4, 5}, Border::Wrap);
  CHECK(h.at(-1, 0) == 2);
  CHECK(h.at(3, 1) == 3);
  CHECK(h.at(0, -1) == 3);
  HeightField c(3, 2, {0, 1, 2, 3, 4, 5}, Border::Clamp);
  CHECK(c.at(-5, 0) == 0);
  CHECK(c.at(9, 9) == 5);
}

TEST_CASE("heightfield: bad input is rejected with a reason") {
  CHECK_THROWS_AS(HeightField(0, 1, {}, Border::Wrap), HeightFieldError);
  CHECK_THROWS_AS(HeightField(2, 2, {0, 0, 0}, Border::Wrap), HeightFieldError);
  CHECK_THROWS_WITH_AS(HeightField(2, 1, {0, std::numeric_limits<double>::quiet_NaN()}, Border::Wrap),
                       "non-finite height at x=1 y=0", HeightFieldError);
}

TEST_CASE("heightfield: hemisphere bump peaks at its radius in the centre") {
  const HeightField h = hemisphere_bump(9, 9, 3.0);
  CHECK(h.at(4, 4) == doctest::Approx(std::sqrt(9.0 - 0.0)).epsilon(1e-12));  // centre texel at offset (0,0)
  CHECK(h.at(0, 0) == 0.0);
}

#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "bumpshadow/generators.h"
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

TEST_CASE("heightfield: bilinear sampling between texel centres") {
  HeightField h(2, 2, {0, 1, 2, 3}, Border::Clamp);
  CHECK(h.sample(0.5, 0) == 0.5);       // halfway between 0 and 1
  CHECK(h.sample(0.5, 0.5) == 1.5);     // mean of the four
  CHECK(h.sample(0.25, 1) == 2.25);     // along the top row 2 -> 3
  CHECK(h.sample(-3, -3) == 0);         // clamp plateau
  HeightField w(2, 2, {0, 1, 2, 3}, Border::Wrap);
  CHECK(w.sample(1.5, 0) == 0.5);       // between x=1 (1) and x=2 == x=0 (0)
  CHECK(w.max_height() == 3);
  CHECK(w.min_height() == 0);
}

TEST_CASE("heightfield: bad input is rejected with a reason") {
  CHECK_THROWS_AS(HeightField(0, 1, {}, Border::Wrap), HeightFieldError);
  CHECK_THROWS_WITH_AS(HeightField(0, 5, {}, Border::Wrap),
                       "height field size 0x5 is out of range (1..16384 per side, at most 2^26 texels)",
                       HeightFieldError);
  CHECK_NOTHROW(HeightField(1, 5, {0, 0, 0, 0, 0}, Border::Wrap));  // one texel per side is valid
  CHECK_THROWS_AS(HeightField(20000, 2, {}, Border::Wrap), HeightFieldError);
  CHECK_THROWS_AS(HeightField(2, 2, {0, 0, 0}, Border::Wrap), HeightFieldError);
  CHECK_THROWS_WITH_AS(HeightField(2, 2, {0, std::numeric_limits<double>::quiet_NaN(), 0, 0}, Border::Wrap),
                       "non-finite height at x=1 y=0", HeightFieldError);
  CHECK_THROWS_WITH_AS(HeightField(2, 2, {0, 0, 0, std::numeric_limits<double>::infinity()}, Border::Wrap),
                       "non-finite height at x=1 y=1", HeightFieldError);
  const HeightField ok(2, 2, {0, 1, 2, 3}, Border::Wrap);
  CHECK_THROWS_AS(ok.scaled(0), HeightFieldError);
  CHECK(ok.scaled(2).at(1, 1) == 6);
}

TEST_CASE("heightfield: content hash sees every height, the size and the border") {
  const HeightField a(2, 2, {0, 1, 2, 3}, Border::Wrap);
  CHECK(a.hash() == HeightField(2, 2, {0, 1, 2, 3}, Border::Wrap).hash());
  CHECK(a.hash() != HeightField(2, 2, {0, 1, 2, 3}, Border::Clamp).hash());
  CHECK(a.hash() != HeightField(2, 2, {0, 1, 2, 3.0000000000000004}, Border::Wrap).hash());
  CHECK(HeightField(2, 2, {0, 0, 0, 0}, Border::Wrap).hash() == HeightField(2, 2, {-0.0, 0, 0, 0}, Border::Wrap).hash());
}

TEST_CASE("heightfield: hemisphere bump peaks at its radius on the centre texel") {
  const HeightField h = hemisphere_bump(9, 9, 3.0);
  CHECK(h.at(4, 4) == 3.0);                             // centre texel floor(9/2) = 4, sqrt(9 - 0)
  CHECK(h.at(5, 4) == doctest::Approx(std::sqrt(8.0)));  // one texel off: sqrt(9 - 1)
  CHECK(h.at(0, 0) == 0.0);
}

TEST_CASE("generators: every registered generator is deterministic and seed-dependent") {
  for (const auto& g : generators()) {
    CAPTURE(g.name);
    const GeneratorParams p{{"w", "24"}, {"h", "20"}};
    const HeightField a = generate(g.name, p), b = generate(g.name, p);
    CHECK(a.width() == 24);
    CHECK(a.height() == 20);
    CHECK(a.data() == b.data());
    CHECK(a.max_height() > a.min_height());  // not flat
    if (g.name == "craters" || g.name == "fractal") {
      const GeneratorParams q{{"w", "24"}, {"h", "20"}, {"seed", "2"}};
      CHECK(generate(g.name, q).data() != a.data());
    }
    CHECK(describe_generator(g.name, p).find("w=24") != std::string::npos);
  }
}

TEST_CASE("generators: wrap fields tile") {
  // fractal lattices are periodic over the field, so the sample just past the
  // right edge (wrap) continues the left column smoothly: compare the jump across
  // the seam with the largest jump inside the field.
  const HeightField f = generate("fractal", {{"w", "32"}, {"octaves", "2"}});
  CHECK(f.border() == Border::Wrap);
  double inner = 0, seam = 0;
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x + 1 < 32; ++x) inner = std::max(inner, std::abs(f.at(x + 1, y) - f.at(x, y)));
    seam = std::max(seam, std::abs(f.at(0, y) - f.at(31, y)));
  }
  CHECK(seam <= inner);
  // ridges at angle 0 with a period dividing the width tile exactly.
  const HeightField r = generate("ridges", {{"w", "32"}, {"period", "8"}});
  for (int x = 0; x < 32; ++x) CHECK(r.at(x, 0) == r.at(x + 8, 0));
}

TEST_CASE("generators: registry errors name the generator, key and accepted values") {
  CHECK_THROWS_WITH_AS(generate("nope"), "unknown height field generator `nope` (known: bump, bumps, ridges, craters, fractal)",
                       HeightFieldError);
  CHECK_THROWS_WITH_AS(generate("bump", {{"radius", "3"}}),
                       "generator `bump`: unknown parameter `radius` (accepted: w, h, border, seed, r, cx, cy)",
                       HeightFieldError);
  CHECK_THROWS_WITH_AS(generate("bump", {{"r", "abc"}}), "generator `bump`: r=`abc` is not a finite number",
                       HeightFieldError);
  CHECK_THROWS_WITH_AS(generate("bump", {{"r", "nan"}}), "generator `bump`: r=`nan` is not a finite number",
                       HeightFieldError);
  CHECK_THROWS_WITH_AS(generate("bump", {{"w", "1"}}), "generator `bump`: w=1 is out of range [2, 16384]",
                       HeightFieldError);
  CHECK_THROWS_WITH_AS(generate("bump", {{"border", "mirror"}}), "generator `bump`: border=`mirror` must be wrap or clamp",
                       HeightFieldError);
  CHECK_THROWS_AS(generate("fractal", {{"w", "16384"}, {"h", "16384"}}), HeightFieldError);  // > 2^26 texels
  CHECK_THROWS_AS(generate("craters", {{"rmin", "5"}, {"rmax", "3"}}), HeightFieldError);
  CHECK_THROWS_AS(parse_generator_params({"w"}), HeightFieldError);
  CHECK(parse_generator_params({"w=8", "seed=3"}).at("seed") == "3");
}

// Issue 9, numerical stability: light directions over the whole upper hemisphere
// including grazing ones (elevation 1 degree and exactly 0) and lx^2 + ly^2 -> 1,
// where lz computed as sqrt(1 - lx^2 - ly^2) is the sqrt of a tiny negative
// number (NaN). No function of the precomputation may turn such a light into NaN.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "bumpshadow/ellipse_fit.h"
#include "bumpshadow/ellipse_test.h"
#include "bumpshadow/encodings.h"
#include "bumpshadow/generators.h"
#include "bumpshadow/horizon.h"
#include "bumpshadow/reference.h"
#include "bumpshadow/rng.h"

using namespace ffsim::bumpshadow;

namespace {

// The light at `elev` degrees, azimuth `az`, with lz computed the naive way.
Vec3 naive_light(double elev, double az) {
  const double e = elev * std::numbers::pi / 180;
  Vec3 l{std::cos(e) * std::cos(az), std::cos(e) * std::sin(az), 0};
  l.z = std::sqrt(1 - l.x * l.x - l.y * l.y);
  return l;
}

}  // namespace

TEST_CASE("stress lights: lx^2 + ly^2 rounding above 1 really gives a NaN lz (the input exists)") {
  // 0.6^2 + 0.8^2 rounds to 1 + 2^-52 in binary64: the radicand is -1.1e-16.
  const double lx = 0.6, ly = 0.8;
  CHECK(1 - lx * lx - ly * ly < 0);
  CHECK(std::isnan(std::sqrt(1 - lx * lx - ly * ly)));
}

TEST_CASE("stress lights: project_light is finite for a NaN lz, a zero vector and grazing lights") {
  double lx = 0, ly = 0;
  // lz = sqrt(tiny negative) = NaN: its intended value is 0 (a light on the horizon).
  project_light({0.6, 0.8, std::sqrt(1 - 0.6 * 0.6 - 0.8 * 0.8)}, lx, ly);
  CHECK(std::isfinite(lx));
  CHECK(std::isfinite(ly));
  CHECK(lx == doctest::Approx(0.6).epsilon(1e-15));
  CHECK(ly == doctest::Approx(0.8).epsilon(1e-15));
  // The zero vector has no direction: (0, 0), the zenith's projection.
  project_light({0, 0, 0}, lx, ly);
  CHECK(lx == 0);
  CHECK(ly == 0);
  // Unchanged for ordinary lights: normalize(L).xy.
  project_light({3, 0, 4}, lx, ly);
  CHECK(lx == 0.6);
  CHECK(ly == 0);
  for (double elev : {0.0, 1e-9, 0.01, 0.5, 1.0, 45.0, 90.0})
    for (int k = 0; k < 16; ++k) {
      project_light(naive_light(elev, k * std::numbers::pi / 8), lx, ly);
      CAPTURE(elev);
      CHECK(std::isfinite(lx));
      CHECK(std::isfinite(ly));
      CHECK(lx * lx + ly * ly <= 1 + 1e-15);
    }
}

TEST_CASE("stress lights: shadow tests and references stay finite and in range down to elevation 0") {
  const HeightField hf = generate("craters", {{"w", "12"}, {"seed", "3"}});
  const HorizonMap hm = compute_horizon_map(hf, 8, {}, 1);
  SplitMix64 rng(91);
  std::vector<Ellipse> ell;
  for (int i = 0; i < 16; ++i) {
    Ellipse e;
    const double th = rng.uniform(-1.5, 1.5);
    e.ax = std::cos(th);
    e.ay = std::sin(th);
    e.cx = rng.uniform(-1.5, 1.5);  // beyond |C| = 1 too
    e.cy = rng.uniform(-1.5, 1.5);
    e.rx = i == 0 ? 0.0 : rng.uniform(0, 2);
    e.ry = i == 0 ? 0.0 : e.rx + rng.uniform(0, 2);
    ell.push_back(e);
  }
  EllipseMap map;
  map.width = static_cast<int>(ell.size());
  map.height = 1;
  map.ellipse = ell;
  map.kind.assign(ell.size(), TexelKind::Fitted);
  map.agree.assign(ell.size(), 0);
  long long lights = 0, lit_at_zero = 0;
  for (double elev : {0.0, 1e-12, 1e-6, 0.25, 0.5, 1.0, 2.0, 10.0, 45.0, 89.0, 90.0})
    for (int k = 0; k < 12; ++k) {
      const Vec3 L = naive_light(elev, k * std::numbers::pi / 6 + 0.01);
      ++lights;
      double lx = 0, ly = 0;
      project_light(L, lx, ly);
      for (const Ellipse& e : ell) {
        const TexelEncoding t = encode_texel(e);
        CHECK(std::isfinite(ellipse_test(e, lx, ly)));
        CHECK(std::isfinite(eq41(t.t1r, t.t2r, t.rx2, lx, ly)));
        CHECK(std::isfinite(eq51(t.t1n, t.t2n, t.rx2, lx, ly)));
        CHECK(std::isfinite(quantisation_bound41(t.t1r, t.t2r, lx, ly)));
      }
      for (int y = 0; y < hf.height(); y += 3)
        for (int x = 0; x < hf.width(); x += 3) {
          const bool lit = reference_lit(hf, x, y, L);
          // Lights at or below the tangent plane (z <= 0 or NaN) are shadowed.
          if (!(L.z > 0)) lit_at_zero += lit;
          const double f = reference_visible_fraction(hf, x, y, L, 0.2, 8);
          CHECK(std::isfinite(f));
          CHECK(f >= 0);
          CHECK(f <= 1);
          const double h = horizon_light(hm, x, y, L, 0.2);
          CHECK(std::isfinite(h));
          CHECK(h >= 0);
          CHECK(h <= 1);
        }
      for (double d : ellipse_test_map(map, L)) CHECK(std::isfinite(d));
    }
  CHECK(lights == 132);
  CHECK(lit_at_zero == 0);
}

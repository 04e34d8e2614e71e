// Analytic visibility tests: flat field, a ridge's shadow length, a
// hemisphere's shadow boundary, the horizon angle of a ridge.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "bumpshadow/ellipse_test.h"
#include "bumpshadow/generators.h"
#include "bumpshadow/horizon.h"
#include "bumpshadow/reference.h"
#include "bumpshadow/visibility.h"

using namespace ffsim::bumpshadow;

namespace {
constexpr double kPi = std::numbers::pi;
Vec3 dir(double azimuth, double elevation) {
  return {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth), std::sin(elevation)};
}
// Flat ground with a one-texel-wide wall of height h along column x0 (constant in y).
HeightField ridge_field(int w, int h, int x0, double height) {
  std::vector<double> z(static_cast<std::size_t>(w) * h, 0.0);
  for (int y = 0; y < h; ++y) z[static_cast<std::size_t>(y) * w + x0] = height;
  return HeightField(w, h, std::move(z), Border::Clamp);
}
}  // namespace

TEST_CASE("visibility: a flat field is lit from every direction above the horizon") {
  const HeightField flat(16, 16, std::vector<double>(256, 1.5), Border::Wrap);
  for (int i = 0; i < 16; i += 5)
    for (int j = 0; j < 16; j += 5) {
      for (double az = 0; az < 2 * kPi; az += kPi / 12)
        for (double el : {0.001, 0.01, 0.1, 0.5, 1.0, 1.5, kPi / 2}) CHECK(reference_lit(flat, i, j, dir(az, el)));
      CHECK_FALSE(reference_lit(flat, i, j, dir(0.3, 0.0)));    // in the plane: not above the horizon
      CHECK_FALSE(reference_lit(flat, i, j, dir(0.3, -0.2)));   // below
    }
  for (RayDistribution d : {RayDistribution::Cosine, RayDistribution::Uniform}) {
    RayOptions o = rays_for_count(400);
    o.distribution = d;
    const RaySet rays = make_ray_set(o);
    std::vector<double> hz;
    std::vector<std::uint8_t> lit;
    CHECK(texel_visibility(flat, 3, 7, rays, o.march, hz, lit) == rays.size());
  }
}

TEST_CASE("visibility: ray sets are stratified over the hemisphere and deterministic") {
  RayOptions o = rays_for_count(256);
  CHECK(o.azimuths == 16);
  CHECK(o.elevations == 16);
  const RaySet a = make_ray_set(o), b = make_ray_set(o);
  CHECK(a.px == b.px);
  // Cosine: elevation stratum e holds projected radius^2 in [e/16, (e+1)/16).
  for (int az = 0; az < 16; ++az) {
    const double phi = std::atan2(a.sin_az[az], a.cos_az[az]);
    const double lo = 2 * kPi * az / 16, u = phi < 0 ? phi + 2 * kPi : phi;
    CHECK(u >= lo);
    CHECK(u < lo + 2 * kPi / 16);
    for (int e = 0; e < 16; ++e) {
      const int k = az * 16 + e;
      const double r2 = a.px[k] * a.px[k] + a.py[k] * a.py[k];
      CHECK(r2 >= e / 16.0 - 1e-15);
      CHECK(r2 < (e + 1) / 16.0 + 1e-15);
      CHECK(a.tan_elev[k] == doctest::Approx(std::sqrt(1 - r2) / std::sqrt(r2)));
    }
  }
  o.seed = 2;
  CHECK(make_ray_set(o).px != a.px);
  o.azimuths = 0;
  CHECK_THROWS_AS(make_ray_set(o), HeightFieldError);
}

TEST_CASE("visibility: a ridge of height h casts a shadow of length h/tan(e) within half a texel") {
  const double h = 4;
  const int x0 = 8;
  const HeightField f = ridge_field(64, 4, x0, h);
  for (double e_deg : {12.0, 20.0, 30.0, 45.0, 60.0, 75.0}) {
    CAPTURE(e_deg);
    const double e = e_deg * kPi / 180, expected = h / std::tan(e);
    const Vec3 L = dir(kPi, e);  // light toward -x: the shadow falls on +x
    int last_shadowed = 0;       // distance d of the last shadowed texel beyond the ridge
    bool monotone = true, seen_lit = false;
    for (int d = 1; x0 + d < 64; ++d) {
      const bool lit = reference_lit(f, x0 + d, 1, L);
      if (!lit) {
        last_shadowed = d;
        monotone = monotone && !seen_lit;
      } else {
        seen_lit = true;
      }
    }
    CHECK(monotone);
    // The shadow edge lies between the last shadowed and the first lit centre.
    CHECK(std::abs((last_shadowed + 0.5) - expected) <= 0.5);
    for (int d = 1; d <= x0; ++d) CHECK(reference_lit(f, x0 - d, 1, L));  // the lit side
  }
}

TEST_CASE("visibility: horizon angle of a ridge equals atan(h/d)") {
  const double h = 5;
  const int x0 = 20;
  const HeightField f = ridge_field(48, 3, x0, h);
  const HorizonMap hm = compute_horizon_map(f, 8, {}, 1);
  for (int d = 1; d <= 20; ++d) {
    CAPTURE(d);
    // azimuth index 4 = pi (toward -x, the ridge); march samples land on x0 exactly.
    CHECK(hm.at(x0 + d, 1, 4) == doctest::Approx(std::atan(h / d)).epsilon(1e-12));
    CHECK(hm.at(x0 + d, 1, 0) == 0.0);  // toward +x: flat ground, horizon at 0
    CHECK(hm.at(x0 - d, 1, 0) == doctest::Approx(std::atan(h / d)).epsilon(1e-12));
  }
  // The tabulated angle is interpolated linearly in azimuth (Max section 2).
  const double mid = horizon_elevation(hm, x0 + 3, 1, 7 * kPi / 8);  // halfway between k = 3 and k = 4
  CHECK(mid == doctest::Approx(0.5 * (hm.at(x0 + 3, 1, 3) + hm.at(x0 + 3, 1, 4))));
}

TEST_CASE("visibility: a hemispherical bump's shadow boundary matches the analytic one") {
  // Analytic: a ground point p is in the shadow of the sphere (centre c on the
  // ground, radius R) iff the ray p + tL passes within R of c for some t > 0:
  // (c - p).L > 0 and |p - c|^2 - ((c - p).L)^2 < R^2. The height field samples
  // the hemisphere at texel centres with bilinear facets in between, so texels
  // within one texel of the analytic boundary are not judged.
  const int n = 40;
  const double R = 7, cx = 20, cy = 20;
  const HeightField f = hemisphere_bump(n, n, R, cx, cy, Border::Clamp);
  int judged = 0, shadowed = 0;
  for (double az : {0.3, 2.0, 4.1})
    for (double el_deg : {25.0, 40.0, 60.0}) {
      const Vec3 L = dir(az, el_deg * kPi / 180);
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const double px = x - cx, py = y - cy;
          if (std::hypot(px, py) < R + 1) continue;  // on the bump itself
          const double along = -(px * L.x + py * L.y);
          const double dist = std::sqrt(std::max(0.0, px * px + py * py - along * along));
          if (along > 0 && std::abs(dist - R) < 1.0) continue;  // near the boundary
          const bool analytic_lit = !(along > 0 && dist < R);
          CAPTURE(x);
          CAPTURE(y);
          CHECK(reference_lit(f, x, y, L) == analytic_lit);
          ++judged;
          shadowed += !analytic_lit;
        }
    }
  CHECK(judged > 3000);
  CHECK(shadowed > 150);  // the test sees real shadows (182 judged shadowed pairs at the time of writing)
}

TEST_CASE("visibility: Max's penumbra fraction is the visible area of a disc cut by a line") {
  // Independent check: fraction of a 2000 x 2000 grid over the unit disc lying below the chord y = alpha.
  for (double a : {-1.0, -0.6, -0.2, 0.0, 0.35, 0.8, 1.0}) {
    long in = 0, below = 0;
    for (int iy = 0; iy < 2000; ++iy)
      for (int ix = 0; ix < 2000; ++ix) {
        const double x = -1 + (ix + 0.5) / 1000, y = -1 + (iy + 0.5) / 1000;
        if (x * x + y * y > 1) continue;
        ++in;
        below += y < a;
      }
    CHECK(penumbra_fraction(a) == doctest::Approx(static_cast<double>(below) / in).epsilon(2e-3));
  }
  CHECK(penumbra_fraction(-3) == 0.0);
  CHECK(penumbra_fraction(3) == 1.0);
  CHECK(penumbra_fraction(0.3) + penumbra_fraction(-0.3) == doctest::Approx(1.0));
}

TEST_CASE("visibility: soft reference and Max's penumbra agree on a long ridge") {
  // Max section 5: f(alpha) "will give an accurate answer for the case of a shadow
  // cast by a horizontal ridge". A disc light of 8 degrees near the shadow edge.
  const double h = 4, delta = 8 * kPi / 180;
  const int x0 = 8;
  const HeightField f = ridge_field(40, 3, x0, h);
  const HorizonMap hm = compute_horizon_map(f, 8, {}, 1);
  const double e = 30 * kPi / 180;
  const Vec3 L = dir(kPi, e);
  int partial = 0;
  for (int d = 1; d < 16; ++d) {
    const double soft = reference_visible_fraction(f, x0 + d, 1, L, delta, 256);
    const double max = horizon_light(hm, x0 + d, 1, L, delta);
    CAPTURE(d);
    CHECK(std::abs(soft - max) <= 0.03);
    partial += soft > 0 && soft < 1;
  }
  CHECK(partial >= 1);  // the edge was sampled
  // Hard horizon test equals the binary reference on the tabulated azimuth.
  for (int d = 1; d < 16; ++d) CHECK((horizon_light(hm, x0 + d, 1, L) == 1.0) == reference_lit(f, x0 + d, 1, L));
}

TEST_CASE("visibility: the block-skipping march gives bit-identical horizons") {
  const HeightField fields[] = {generate("fractal", {{"w", "40"}, {"h", "24"}}),
                                generate("craters", {{"w", "32"}, {"border", "clamp"}}),
                                generate("bumps", {{"w", "24"}, {"spacing", "8"}, {"r", "3"}}),
                                generate("ridges", {{"w", "30"}, {"border", "clamp"}, {"angle", "30"}})};
  for (const HeightField& f : fields) {
    long checked = 0, positive = 0;
    for (int y = 0; y < f.height(); ++y)
      for (int x = 0; x < f.width(); ++x)
        for (double phi = 0.05; phi < 2 * kPi; phi += 0.61) {
          const double c = std::cos(phi), s = std::sin(phi);
          const double a = horizon_tan(f, x, y, c, s, {}), b = horizon_tan_unaccelerated(f, x, y, c, s, {});
          if (a != b) CHECK(a == b);  // only report mismatches (there are ~10^4 comparisons)
          ++checked;
          positive += a > 0;
        }
    CHECK(checked > 5000);
    CHECK(positive > checked / 4);
  }
}

TEST_CASE("visibility: uniform rays are stratified in cos(zenith)") {
  RayOptions o = rays_for_count(64);
  o.distribution = RayDistribution::Uniform;
  const RaySet r = make_ray_set(o);
  for (int a = 0; a < r.azimuths; ++a)
    for (int e = 0; e < r.elevations; ++e) {
      const int k = a * r.elevations + e;
      const double rad = std::hypot(r.px[k], r.py[k]), z = std::sqrt(1 - rad * rad);
      CHECK(z <= 1 - e / 8.0 + 1e-12);
      CHECK(z > 1 - (e + 1) / 8.0 - 1e-12);
      CHECK(r.tan_elev[k] == doctest::Approx(z / rad));
    }
}

TEST_CASE("visibility: per-ray verdicts equal the exact reference along each ray") {
  // Independent path: reference_lit re-derives azimuth and elevation from the
  // ray's 3D direction. Rounding of the re-derived azimuth may move a ray lying
  // exactly on a horizon, so 99.9% agreement is required (all agree in practice).
  const HeightField f = generate("craters", {{"w", "24"}});
  const RayOptions o = rays_for_count(100);
  const RaySet rays = make_ray_set(o);
  std::vector<double> hz;
  std::vector<std::uint8_t> lit;
  long same = 0, total = 0, shadowed = 0;
  for (int j = 0; j < 24; j += 3)
    for (int i = 0; i < 24; i += 3) {
      texel_visibility(f, i, j, rays, o.march, hz, lit);
      for (int k = 0; k < rays.size(); ++k) {
        const double rad = std::hypot(rays.px[k], rays.py[k]);
        const Vec3 d{rays.px[k], rays.py[k], std::sqrt(1 - rad * rad)};
        same += reference_lit(f, i, j, d) == (lit[k] != 0);
        shadowed += !lit[k];
        ++total;
      }
    }
  CHECK(same >= 0.999 * total);
  CHECK(shadowed > total / 50);  // real shadows were tested
}

TEST_CASE("visibility: the horizon lit map equals the reference on tabulated azimuths") {
  // On an azimuth that the horizon map tabulates, interpolation returns the
  // tabulated angle, which is the reference's own march: no texel may differ.
  const HeightField f = generate("craters", {{"w", "24"}});
  const HorizonMap hm = compute_horizon_map(f, 16, {}, 2);
  const Vec3 L = dir(2 * kPi * 3 / 16, 0.35);
  const std::vector<std::uint8_t> ref = reference_lit_map(f, L, {}, 2);
  const ShadowErrorStats s = compare_lit_maps(horizon_lit_map(hm, L), ref);
  CHECK(s.texels == 24 * 24);
  CHECK(s.false_lit + s.false_shadow <= 2);  // atan/tan round trip of a texel exactly on its horizon
  long shadowed = 0;
  for (auto v : ref) shadowed += !v;
  CHECK(shadowed > 20);
  // Between tabulated azimuths the interpolation costs something, but stays small on craters.
  const Vec3 M = dir(2 * kPi * 3.5 / 16, 0.35);
  CHECK(compare_lit_maps(horizon_lit_map(hm, M), reference_lit_map(f, M, {}, 2)).error_fraction() < 0.1);
}

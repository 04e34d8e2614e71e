#include "bumpshadow/horizon.h"

#include "bumpshadow/detmath.h"

#include <cmath>
#include <numbers>

namespace ffsim::bumpshadow {

HorizonMap compute_horizon_map(const HeightField& hf, int azimuths, const MarchOptions& m, int threads,
                               const Progress& progress) {
  if (azimuths < 1 || azimuths > 4096) throw HeightFieldError("horizon map: azimuth count must be 1..4096");
  if (!(m.step > 0) || !std::isfinite(m.step)) throw HeightFieldError("horizon map: march step must be > 0");
  HorizonMap h;
  h.width = hf.width();
  h.height = hf.height();
  h.azimuths = azimuths;
  h.elevation.resize(static_cast<std::size_t>(h.width) * h.height * azimuths);
  std::vector<double> c(azimuths), s(azimuths);
  for (int k = 0; k < azimuths; ++k) {
    const double phi = 2 * std::numbers::pi * k / azimuths;
    c[k] = det::cos(phi);
    s[k] = det::sin(phi);
  }
  parallel_rows(
      h.height, threads,
      [&](int y) {
        for (int x = 0; x < h.width; ++x)
          for (int k = 0; k < azimuths; ++k)
            h.elevation[(static_cast<std::size_t>(y) * h.width + x) * azimuths + k] =
                det::atan(horizon_tan(hf, x, y, c[k], s[k], m));
      },
      progress);
  return h;
}

double horizon_elevation(const HorizonMap& h, int x, int y, double phi) {
  const double twopi = 2 * std::numbers::pi;
  double u = phi / twopi;
  u -= std::floor(u);
  const double pos = u * h.azimuths;
  int k0 = static_cast<int>(std::floor(pos));
  const double f = pos - k0;
  k0 %= h.azimuths;
  const int k1 = (k0 + 1) % h.azimuths;
  return h.at(x, y, k0) + (h.at(x, y, k1) - h.at(x, y, k0)) * f;
}

double penumbra_fraction(double a) {
  if (a <= -1) return 0.0;
  if (a >= 1) return 1.0;
  return 0.5 + (det::asin(a) + a * std::sqrt(1 - a * a)) / std::numbers::pi;
}

double horizon_light(const HorizonMap& h, int x, int y, const Vec3& l, double diameter) {
  if (!(l.z > 0)) return 0.0;
  const double r = std::sqrt(l.x * l.x + l.y * l.y);
  if (r == 0) return 1.0;
  const double elev = det::atan2(l.z, r);
  const double beta = horizon_elevation(h, x, y, det::atan2(l.y, l.x));
  if (diameter <= 0) return elev >= beta ? 1.0 : 0.0;
  return penumbra_fraction((elev - beta) / (0.5 * diameter));
}

std::vector<std::uint8_t> horizon_lit_map(const HorizonMap& h, const Vec3& light) {
  std::vector<std::uint8_t> out(static_cast<std::size_t>(h.width) * h.height);
  for (int y = 0; y < h.height; ++y)
    for (int x = 0; x < h.width; ++x)
      out[static_cast<std::size_t>(y) * h.width + x] = horizon_light(h, x, y, light) == 1.0;
  return out;
}

}  // namespace ffsim::bumpshadow

#include "bumpshadow/reference.h"

#include "bumpshadow/detmath.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "bumpshadow/parallel.h"

namespace ffsim::bumpshadow {

void project_light(const Vec3& l, double& lx, double& ly) {
  // A grazing light's z computed as sqrt(1 - x^2 - y^2) is NaN when rounding makes
  // the radicand a tiny negative number (e.g. x = 0.6, y = 0.8); its intended value
  // is 0. The zero vector has no direction: it projects to (0, 0).
  const double z = std::isnan(l.z) ? 0.0 : l.z;
  const double n = std::sqrt(l.x * l.x + l.y * l.y + z * z);
  if (n == 0) {
    lx = ly = 0;
    return;
  }
  lx = l.x / n;
  ly = l.y / n;
}

bool reference_lit(const HeightField& hf, int i, int j, const Vec3& l, const MarchOptions& m) {
  if (!(l.z > 0)) return false;
  const double r = std::sqrt(l.x * l.x + l.y * l.y);
  if (r == 0) return true;
  return l.z / r >= horizon_tan(hf, i, j, l.x / r, l.y / r, m);
}

double reference_visible_fraction(const HeightField& hf, int i, int j, const Vec3& l, double diameter, int samples,
                                  const MarchOptions& m) {
  if (!(diameter > 0 && diameter < std::numbers::pi) || samples < 1)
    throw HeightFieldError("disc light: angular diameter must be in (0, pi) and samples >= 1");
  const double n = std::sqrt(l.x * l.x + l.y * l.y + l.z * l.z);
  const Vec3 L{l.x / n, l.y / n, l.z / n};
  // U: perpendicular to L in the plane of L and the normal (toward the zenith side); V = L x U.
  Vec3 U;
  const double r = std::sqrt(L.x * L.x + L.y * L.y);
  if (r > 1e-12) U = {-L.z * L.x / r, -L.z * L.y / r, r};
  else U = {1, 0, 0};
  const Vec3 V{L.y * U.z - L.z * U.y, L.z * U.x - L.x * U.z, L.x * U.y - L.y * U.x};
  const double R = det::tan(0.5 * diameter);
  const double golden = std::numbers::pi * (3 - std::sqrt(5.0));
  int lit = 0;
  for (int k = 0; k < samples; ++k) {
    const double rad = R * std::sqrt((k + 0.5) / samples), ang = k * golden;
    const double a = rad * det::cos(ang), b = rad * det::sin(ang);
    lit += reference_lit(hf, i, j, {L.x + a * U.x + b * V.x, L.y + a * U.y + b * V.y, L.z + a * U.z + b * V.z}, m);
  }
  return static_cast<double>(lit) / samples;
}

std::vector<std::uint8_t> reference_lit_map(const HeightField& hf, const Vec3& light, const MarchOptions& m,
                                            int threads) {
  const int w = hf.width();
  std::vector<std::uint8_t> out(static_cast<std::size_t>(w) * hf.height());
  parallel_rows(hf.height(), threads, [&](int j) {
    for (int i = 0; i < w; ++i) out[static_cast<std::size_t>(j) * w + i] = reference_lit(hf, i, j, light, m);
  });
  return out;
}

std::vector<double> reference_soft_map(const HeightField& hf, const Vec3& light, double diameter, int samples,
                                       const MarchOptions& m, int threads) {
  const int w = hf.width();
  std::vector<double> out(static_cast<std::size_t>(w) * hf.height());
  parallel_rows(hf.height(), threads, [&](int j) {
    for (int i = 0; i < w; ++i)
      out[static_cast<std::size_t>(j) * w + i] = reference_visible_fraction(hf, i, j, light, diameter, samples, m);
  });
  return out;
}

}  // namespace ffsim::bumpshadow

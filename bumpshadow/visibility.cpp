#include "bumpshadow/visibility.h"

#include "bumpshadow/detmath.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "bumpshadow/rng.h"

namespace ffsim::bumpshadow {

const char* distribution_name(RayDistribution d) { return d == RayDistribution::Cosine ? "cosine" : "uniform"; }

namespace {

// The march of horizon_tan; with skip, stretches whose block bound cannot raise
// the maximum are jumped over. Skipping never changes the result: every skipped
// sample z satisfies (z - z0)/t <= H (block_max is an upper bound, widened by a
// tolerance that covers bilinear rounding), so the maximum is the same.
double march(const HeightField& hf, int i, int j, double c, double s, const MarchOptions& m, bool skip) {
  const double z0 = hf.at(i, j);
  const double headroom = hf.max_height() - z0;
  double best = 0.0;
  if (headroom <= 0) return best;
  const int w = hf.width(), h = hf.height();
  const double maxd = m.max_distance > 0 ? m.max_distance : static_cast<double>(std::max(w, h));
  const bool clamp = hf.border() == Border::Clamp;
  const bool moves_x = std::abs(c) > 1e-12, moves_y = std::abs(s) > 1e-12;
  const double reach = HeightField::kBlockRadius - 1;  // samples within this distance share the bound
  for (long k = 1;; ++k) {
    const double t = static_cast<double>(k) * m.step;
    if (t > maxd) break;
    const double x = i + c * t, y = j + s * t;
    if (clamp) {
      // Beyond the last sample in every moving coordinate the surface is a
      // constant plateau: the slope only decays toward 0 from here on.
      const bool out_x = x < 0 || x > w - 1, out_y = y < 0 || y > h - 1;
      if ((out_x || !moves_x) && (out_y || !moves_y) && (out_x || out_y)) {
        best = std::max(best, (hf.sample(x, y) - z0) / t);
        break;
      }
    }
    if (skip) {
      const double bound = hf.block_max(static_cast<int>(std::floor(x)), static_cast<int>(std::floor(y)));
      if ((bound + 1e-9 * (1 + std::abs(bound)) - z0) / t <= best) {
        k = std::max(k, static_cast<long>(std::floor((t + reach) / m.step)));  // next k samples beyond t + reach
        continue;
      }
    }
    best = std::max(best, (hf.sample(x, y) - z0) / t);
    if (headroom / t <= best) break;
  }
  return best;
}

}  // namespace

double horizon_tan_unaccelerated(const HeightField& hf, int i, int j, double c, double s, const MarchOptions& m) {
  return march(hf, i, j, c, s, m, false);
}

double horizon_tan(const HeightField& hf, int i, int j, double c, double s, const MarchOptions& m) {
  return march(hf, i, j, c, s, m, true);
}

RayOptions rays_for_count(int n) {
  RayOptions o;
  const int k = std::max(2, static_cast<int>(std::lround(std::sqrt(std::max(n, 0)))));
  o.azimuths = o.elevations = k;
  return o;
}

RaySet make_ray_set(const RayOptions& o) {
  if (o.azimuths < 1 || o.elevations < 1 || o.azimuths > 4096 || o.elevations > 4096)
    throw HeightFieldError("ray counts " + std::to_string(o.azimuths) + " azimuths x " +
                           std::to_string(o.elevations) + " elevations out of range (1..4096 each)");
  if (!(o.march.step > 0) || !std::isfinite(o.march.step) || !(o.march.max_distance >= 0))
    throw HeightFieldError("march step must be finite and > 0, max distance >= 0");
  RaySet r;
  r.azimuths = o.azimuths;
  r.elevations = o.elevations;
  const int n = o.azimuths * o.elevations;
  r.tan_elev.resize(n);
  r.px.resize(n);
  r.py.resize(n);
  for (int a = 0; a < o.azimuths; ++a) {
    const double phi = 2 * std::numbers::pi * (a + u01(hash_u64(o.seed, 0xA2u, static_cast<std::uint64_t>(a)))) / o.azimuths;
    const double c = det::cos(phi), s = det::sin(phi);
    r.cos_az.push_back(c);
    r.sin_az.push_back(s);
    for (int e = 0; e < o.elevations; ++e) {
      const double q = (e + u01(hash_u64(o.seed, 0xE1u, static_cast<std::uint64_t>(a), static_cast<std::uint64_t>(e)))) /
                       o.elevations;
      double rad, z;
      if (o.distribution == RayDistribution::Cosine) {
        rad = std::sqrt(q);
        z = std::sqrt(std::max(0.0, 1 - q));
      } else {
        z = 1 - q;
        rad = std::sqrt(std::max(0.0, 1 - z * z));
      }
      const int k = a * o.elevations + e;
      r.tan_elev[k] = rad > 0 ? z / rad : std::numeric_limits<double>::infinity();
      r.px[k] = rad * c;
      r.py[k] = rad * s;
    }
  }
  return r;
}

int texel_visibility(const HeightField& hf, int i, int j, const RaySet& rays, const MarchOptions& m,
                     std::vector<double>& horizon, std::vector<std::uint8_t>& lit) {
  horizon.resize(rays.azimuths);
  lit.resize(rays.size());
  int n = 0;
  for (int a = 0; a < rays.azimuths; ++a) {
    const double H = horizon_tan(hf, i, j, rays.cos_az[a], rays.sin_az[a], m);
    horizon[a] = H;
    for (int e = 0; e < rays.elevations; ++e) {
      const int k = a * rays.elevations + e;
      const bool l = rays.tan_elev[k] >= H;
      lit[k] = l;
      n += l;
    }
  }
  return n;
}

}  // namespace ffsim::bumpshadow

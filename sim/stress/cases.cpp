#include "sim/stress/cases.h"

#include <cmath>
#include <numbers>

#include "bumpshadow/detmath.h"

namespace ffsim::stress {

namespace bs = ffsim::bumpshadow;
namespace det = ffsim::bumpshadow::det;

double LightDir::elevation_deg() const {
  if (!(lz >= 0)) return 0.0;
  return det::asin(std::min(1.0, lz)) * 180 / std::numbers::pi;
}

const char* light_kind_name(LightKind k) {
  switch (k) {
    case LightKind::Hemisphere: return "hemisphere";
    case LightKind::Grazing: return "grazing";
    case LightKind::Rim: return "rim";
    case LightKind::Zenith: return "zenith";
    case LightKind::Count: break;
  }
  return "?";
}

LightDir light_at(double elevation_deg, double azimuth) {
  const double e = elevation_deg * std::numbers::pi / 180;
  const double r = det::cos(e);
  LightDir l;
  l.lx = r * det::cos(azimuth);
  l.ly = r * det::sin(azimuth);
  l.lz = std::sqrt(1 - l.lx * l.lx - l.ly * l.ly);  // naive on purpose (may be NaN)
  return l;
}

LightDir make_light(LightKind k, bs::SplitMix64& rng) {
  const double az = 2 * std::numbers::pi * rng.uniform();
  switch (k) {
    case LightKind::Hemisphere: {
      const double z = rng.uniform();  // uniform in solid angle: cos(zenith) uniform
      return light_at(det::asin(z) * 180 / std::numbers::pi, az);
    }
    case LightKind::Grazing:
      return light_at(rng.uniform() < 0.25 ? 0.0 : rng.uniform(), az);
    case LightKind::Rim: {
      const double u = rng.uniform(4, 17);
      const double r = std::sqrt(1 - std::pow(10.0, -u));
      LightDir l;
      l.lx = r * det::cos(az);
      l.ly = r * det::sin(az);
      l.lz = std::sqrt(1 - l.lx * l.lx - l.ly * l.ly);
      return l;
    }
    case LightKind::Zenith: {
      if (rng.uniform() < 0.5) return LightDir{0, 0, 1};
      const double r = 1e-9 * rng.uniform();
      return light_at(90 - r * 180 / std::numbers::pi, az);
    }
    case LightKind::Count: break;
  }
  return {};
}

const char* ellipse_kind_name(EllipseKind k) {
  switch (k) {
    case EllipseKind::Paper: return "paper";
    case EllipseKind::CenterToOne: return "center-to-1";
    case EllipseKind::CenterBeyond: return "center-beyond-1";
    case EllipseKind::RxToZero: return "rx-to-0";
    case EllipseKind::RxBig: return "rx-above-sqrt2";
    case EllipseKind::Circle: return "circle";
    case EllipseKind::Eccentric: return "eccentric";
    case EllipseKind::Count: break;
  }
  return "?";
}

bs::Ellipse make_ellipse(EllipseKind k, bs::SplitMix64& rng) {
  bs::Ellipse e;
  // Axis: a unit vector with the canonical sign (ax > 0, or ax == 0 and ay > 0).
  const double th = std::numbers::pi * (rng.uniform() - 0.5);  // (-pi/2, pi/2]
  e.ax = det::cos(th);
  e.ay = det::sin(th);
  if (rng.uniform() < 0.05) {  // exact axis directions
    e.ax = 1;
    e.ay = 0;
  }
  double cr = std::sqrt(rng.uniform());  // |C|, uniform in the unit disc
  double rx = rng.uniform(0.02, 1.0), ry = rng.uniform(0.02, 1.0);
  switch (k) {
    case EllipseKind::Paper: break;
    case EllipseKind::CenterToOne: cr = rng.uniform() < 0.2 ? 1.0 : 1 - std::pow(10.0, -rng.uniform(1, 16)); break;
    case EllipseKind::CenterBeyond: cr = rng.uniform(1, 3); break;
    case EllipseKind::RxToZero:
      rx = rng.uniform() < 0.2 ? 0.0 : std::pow(10.0, -rng.uniform(2, 300));
      if (rx == 0 && rng.uniform() < 0.5) ry = 0;
      break;
    case EllipseKind::RxBig:
      rx = rng.uniform(std::sqrt(2.0), 4.0);
      ry = rng.uniform(rx, 4.0);
      break;
    case EllipseKind::Circle: ry = rx; break;
    case EllipseKind::Eccentric:
      ry = rng.uniform(0.5, 2.0);
      rx = ry * std::pow(10.0, -rng.uniform(3, 12));
      break;
    case EllipseKind::Count: break;
  }
  if (rx > ry) std::swap(rx, ry);
  const double ph = 2 * std::numbers::pi * rng.uniform();
  e.cx = cr * det::cos(ph);
  e.cy = cr * det::sin(ph);
  e.rx = rx;
  e.ry = ry;
  return e;
}

const char* field_kind_name(FieldKind k) {
  switch (k) {
    case FieldKind::Flat: return "flat";
    case FieldKind::Spike: return "spike";
    case FieldKind::Cliff: return "cliff";
    case FieldKind::Noise: return "noise";
    case FieldKind::Count: break;
  }
  return "?";
}

bs::HeightField make_field(FieldKind k, int w, int h, double scale, bs::Border border, std::uint64_t seed) {
  std::vector<double> z(static_cast<std::size_t>(std::max(w, 0)) * static_cast<std::size_t>(std::max(h, 0)), 0.0);
  bs::SplitMix64 rng(seed);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double v = 0;
      switch (k) {
        case FieldKind::Flat: v = scale; break;
        case FieldKind::Spike: v = (x == w / 2 && y == h / 2) ? scale : 0.0; break;
        case FieldKind::Cliff: v = 2 * x >= w ? scale : 0.0; break;
        case FieldKind::Noise: v = scale * rng.uniform(); break;
        case FieldKind::Count: break;
      }
      z[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)] = v;
    }
  return bs::HeightField(w, h, std::move(z), border);
}

std::uint64_t case_seed(std::uint64_t master, std::uint64_t index) { return bs::hash_u64(master, index, 0x5752455353ull); }

}  // namespace ffsim::stress

#include "bumpshadow/shadow_map.h"

#include <sstream>

namespace ffsim::bumpshadow {

double EllipseMap::agreement() const {
  long double a = 0;
  for (auto v : agree) a += v;
  const long double n = static_cast<long double>(agree.size()) * rays_per_texel;
  return n > 0 ? static_cast<double>(a / n) : 1.0;
}

bool EllipseMap::operator==(const EllipseMap& o) const {
  if (width != o.width || height != o.height || rays_per_texel != o.rays_per_texel || kind != o.kind ||
      agree != o.agree || kind_count != o.kind_count || ellipse.size() != o.ellipse.size())
    return false;
  for (std::size_t i = 0; i < ellipse.size(); ++i) {
    const Ellipse &a = ellipse[i], &b = o.ellipse[i];
    if (a.cx != b.cx || a.cy != b.cy || a.ax != b.ax || a.ay != b.ay || a.rx != b.rx || a.ry != b.ry) return false;
  }
  return true;
}

EllipseMap compute_ellipse_map(const HeightField& hf, const ShadowMapOptions& o) {
  const RaySet rays = make_ray_set(o.rays);
  EllipseMap m;
  m.width = hf.width();
  m.height = hf.height();
  m.rays_per_texel = rays.size();
  const std::size_t n = static_cast<std::size_t>(m.width) * m.height;
  m.ellipse.resize(n);
  m.kind.resize(n);
  m.agree.resize(n);
  parallel_rows(
      m.height, o.threads,
      [&](int j) {
        std::vector<double> horizon;
        std::vector<std::uint8_t> lit;
        for (int i = 0; i < m.width; ++i) {
          texel_visibility(hf, i, j, rays, o.rays.march, horizon, lit);
          const FitResult f = fit_ellipse(rays.px.data(), rays.py.data(), lit.data(), rays.size(), o.fit);
          const std::size_t t = static_cast<std::size_t>(j) * m.width + i;
          m.ellipse[t] = f.e;
          m.kind[t] = f.kind;
          m.agree[t] = static_cast<std::uint32_t>(f.agree);
        }
      },
      o.progress);
  for (TexelKind k : m.kind) ++m.kind_count[static_cast<int>(k)];
  return m;
}

std::string describe_options(const ShadowMapOptions& o) {
  std::ostringstream s;
  s.precision(17);
  s << "azimuths=" << o.rays.azimuths << " elevations=" << o.rays.elevations
    << " distribution=" << distribution_name(o.rays.distribution) << " ray_seed=" << o.rays.seed
    << " step=" << o.rays.march.step << " max_distance=" << o.rays.march.max_distance
    << " shadow_weight=" << o.fit.shadow_weight << " min_lit=" << o.fit.min_lit << " min_radius=" << o.fit.min_radius
    << " levels=" << o.fit.levels << " max_moves=" << o.fit.max_moves;
  return s.str();
}

}  // namespace ffsim::bumpshadow

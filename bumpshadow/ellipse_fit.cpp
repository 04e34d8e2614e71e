#include "bumpshadow/ellipse_fit.h"

#include "bumpshadow/detmath.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace ffsim::bumpshadow {

const char* texel_kind_name(TexelKind k) {
  switch (k) {
    case TexelKind::Fitted: return "fitted";
    case TexelKind::AllLit: return "all_lit";
    case TexelKind::NoneLit: return "none_lit";
    case TexelKind::FewLit: return "few_lit";
    case TexelKind::Collinear: return "collinear";
  }
  return "?";
}

double radius_ratio(const Ellipse& e) { return e.ry > 0 ? e.rx / e.ry : 1.0; }

double ellipse_test(const Ellipse& e, double lx, double ly) {
  const double q = radius_ratio(e);
  // T1^r = (ax, ay, ax Cx + ay Cy); T2^r = q (-ay, ax, -ay Cx + ax Cy); L = (lx, ly, -1).
  const double s1 = e.ax * lx + e.ay * ly - (e.ax * e.cx + e.ay * e.cy);
  const double s2 = (-e.ay * q) * lx + (e.ax * q) * ly - (-e.ay * e.cx + e.ax * e.cy) * q;
  return e.rx * e.rx - s1 * s1 - s2 * s2;
}

namespace {

// Parameters of the search: centre, axis angle, radii.
using P = std::array<double, 5>;

struct Scorer {
  const double* px;
  const double* py;
  const std::uint8_t* lit;
  int n;
  double w;
  double operator()(const P& p) const {
    const double c = det::cos(p[2]), s = det::sin(p[2]);
    const double irx = 1 / (p[3] * p[3]), iry = 1 / (p[4] * p[4]);
    // Branch-free counts (the inside test is unpredictable); integer counts
    // make the score exact.
    int in = 0, lit_in = 0;
    for (int k = 0; k < n; ++k) {
      const double dx = px[k] - p[0], dy = py[k] - p[1];
      const double u = c * dx + s * dy, v = -s * dx + c * dy;
      const int inside = u * u * irx + v * v * iry <= 1;
      in += inside;
      lit_in += inside & static_cast<int>(lit[k] != 0);
    }
    return lit_in - w * (in - lit_in);
  }
};

Ellipse to_ellipse(const P& p) {
  Ellipse e;
  e.cx = p[0];
  e.cy = p[1];
  e.ax = det::cos(p[2]);
  e.ay = det::sin(p[2]);
  e.rx = p[3];
  e.ry = p[4];
  return e;
}

// Section 4.1: r_x <= r_y (swap a with a*), then a canonical sign of a.
Ellipse canonical(Ellipse e) {
  if (e.rx > e.ry) {
    std::swap(e.rx, e.ry);
    const double ax = e.ax;
    e.ax = -e.ay;
    e.ay = ax;
  }
  if (e.ax < 0 || (e.ax == 0 && e.ay < 0)) {
    e.ax = -e.ax;
    e.ay = -e.ay;
  }
  return e;
}

}  // namespace

FitResult fit_ellipse(const double* px, const double* py, const std::uint8_t* lit, int n, const FitOptions& o) {
  FitResult r;
  for (int k = 0; k < n; ++k) r.n_lit += lit[k] != 0;
  auto finish = [&](Ellipse e) {
    r.e = e;
    r.agree = 0;
    for (int k = 0; k < n; ++k) r.agree += (ellipse_test(e, px[k], py[k]) >= 0) == (lit[k] != 0);
    return r;
  };
  if (r.n_lit == n) {
    r.kind = TexelKind::AllLit;
    return finish(Ellipse{});
  }
  if (r.n_lit == 0) {
    r.kind = TexelKind::NoneLit;
    Ellipse e;
    e.rx = e.ry = 0;
    return finish(e);
  }
  // Mean and covariance of the lit points.
  double mx = 0, my = 0;
  for (int k = 0; k < n; ++k)
    if (lit[k]) mx += px[k], my += py[k];
  mx /= r.n_lit;
  my /= r.n_lit;
  double sxx = 0, sxy = 0, syy = 0;
  for (int k = 0; k < n; ++k)
    if (lit[k]) {
      const double dx = px[k] - mx, dy = py[k] - my;
      sxx += dx * dx, sxy += dx * dy, syy += dy * dy;
    }
  sxx /= r.n_lit, sxy /= r.n_lit, syy /= r.n_lit;
  const double mid = 0.5 * (sxx + syy), rad = std::sqrt(0.25 * (sxx - syy) * (sxx - syy) + sxy * sxy);
  const double l1 = mid + rad, l2 = std::max(0.0, mid - rad);
  const double ang = (sxy == 0 && sxx == syy) ? 0.0 : 0.5 * det::atan2(2 * sxy, sxx - syy);  // major axis
  const double rmin = o.min_radius;
  P p{mx, my, ang, std::max(2 * std::sqrt(l1), rmin), std::max(2 * std::sqrt(l2), rmin)};
  if (r.n_lit < o.min_lit) r.kind = TexelKind::FewLit;
  else if (2 * std::sqrt(l2) < rmin) r.kind = TexelKind::Collinear;

  const Scorer score{px, py, lit, n, o.shadow_weight};
  double best = score(p);
  P step{0.1, 0.1, 0.2, 0.1, 0.1};
  for (int level = 0; level < o.levels; ++level) {
    for (int moves = 0; moves < o.max_moves; ++moves) {
      bool improved = false;
      for (int d = 0; d < 5; ++d)
        for (int sgn = -1; sgn <= 1; sgn += 2) {
          P q = p;
          q[d] += sgn * step[d];
          if (d >= 3 && q[d] < rmin) continue;
          const double s = score(q);
          if (s > best) {
            best = s;
            p = q;
            improved = true;
          }
        }
      if (!improved) break;
    }
    for (double& s : step) s *= 0.5;
  }
  return finish(canonical(to_ellipse(p)));
}

}  // namespace ffsim::bumpshadow

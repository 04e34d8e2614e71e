// The ellipse of paper section 2, fitted to the projected light and shadow
// directions of one texel, and the shadow test evaluated exactly in float64.
// docs/bumpshadow.md §4 states the objective, the optimiser and the degenerate
// cases.
#pragma once
#include <cstdint>

namespace ffsim::bumpshadow {

// Centre C, unit major-axis direction a (paper: vector a, minor axis a* = (-ay, ax)),
// radii rx along a and ry along a*. After fit_ellipse: rx <= ry (section 4.1) and
// a canonical sign (ax > 0, or ax == 0 and ay > 0).
struct Ellipse {
  double cx = 0, cy = 0;
  double ax = 1, ay = 0;
  double rx = 1, ry = 1;
};

// rx / ry as used by T2^r; defined as 1 when ry == 0 (the "none lit" ellipse).
double radius_ratio(const Ellipse& e);

// The paper's shadow test (eq. 4.1) in float64, no hardware:
//   d = rx^2 - (L . T1^r)^2 - (L . T2^r)^2,  L = (lx, ly, -1),
// with T1^r, T2^r built from e as in section 4.1. d >= 0 means lit.
double ellipse_test(const Ellipse& e, double lx, double ly);

enum class TexelKind : std::uint8_t {
  Fitted = 0,     // ordinary fit
  AllLit = 1,     // every ray lit: the unit circle, no optimisation
  NoneLit = 2,    // no ray lit: rx = ry = 0 at C = 0 (d = -|l|^2 < 0 off the zenith)
  FewLit = 3,     // fewer than min_lit lit rays: seeded at their mean, then optimised
  Collinear = 4,  // lit rays on (nearly) a line: minor radius floored, then optimised
};
const char* texel_kind_name(TexelKind k);
inline constexpr int kTexelKinds = 5;

struct FitOptions {
  double shadow_weight = 1.0;  // w in  score = lit_inside - w * shadowed_inside
  int min_lit = 3;             // fewer lit rays than this: FewLit
  double min_radius = 0.02;    // floor of both radii during the optimisation
  int levels = 6;              // step halvings of the compass search
  int max_moves = 40;          // accepted moves per level (a safety cap)
};

struct FitResult {
  Ellipse e;
  TexelKind kind = TexelKind::Fitted;
  int n_lit = 0;
  int agree = 0;  // rays whose ellipse_test verdict (d >= 0) equals their visibility
};

// Fits the ellipse to n projected directions (px, py) with visibility lit.
// Start: centre = mean of the lit points, axes = eigenvectors of their
// covariance, radii = 2 sqrt(eigenvalue) (exact for points uniform inside an
// ellipse). Then a deterministic compass search over (cx, cy, angle, rx, ry)
// maximising the score; only strict improvements are taken.
FitResult fit_ellipse(const double* px, const double* py, const std::uint8_t* lit, int n, const FitOptions& o);

}  // namespace ffsim::bumpshadow

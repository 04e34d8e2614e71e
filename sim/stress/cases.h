// Stress inputs (issue 9): light directions over the whole upper hemisphere
// including grazing ones, ellipses at and beyond the paper's assumptions, and
// height fields with extreme shapes, scales and sizes. Every generator is a pure
// function of its kind and a splitmix64 stream (bumpshadow/rng.h), so a case is
// reproduced from its seed alone (docs/stress.md).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "bumpshadow/ellipse_fit.h"
#include "bumpshadow/heightfield.h"
#include "bumpshadow/rng.h"

namespace ffsim::stress {

// A light in the tangent frame. lz is computed the naive way,
// sqrt(1 - lx^2 - ly^2), which is NaN when rounding makes the radicand a tiny
// negative number (lx^2 + ly^2 -> 1): exactly the input the pipeline must survive.
struct LightDir {
  double lx = 0, ly = 0, lz = 1;
  double elevation_deg() const;  // asin(lz) in degrees (0 when lz is NaN)
};

enum class LightKind {
  Hemisphere,  // uniform in solid angle over the upper hemisphere
  Grazing,     // elevation in [0, 1] degree, a quarter of them exactly 0
  Rim,         // lx^2 + ly^2 = 1 - 10^-u, u in [4, 17] (lz -> 0, radicand may round negative)
  Zenith,      // (0, 0, 1) or within 1e-9 of it
  Count
};
const char* light_kind_name(LightKind k);
LightDir make_light(LightKind k, bumpshadow::SplitMix64& rng);
// The light with the given elevation (degrees) and azimuth (radians); lz naive as above.
LightDir light_at(double elevation_deg, double azimuth);

enum class EllipseKind {
  Paper,         // |C| <= 1, 0.02 <= rx <= ry <= 1 (the paper's setting)
  CenterToOne,   // |C| = 1 - 10^-u (u in [1, 16]) or exactly 1
  CenterBeyond,  // 1 < |C| <= 3
  RxToZero,      // rx = 10^-u (u in [2, 300]) or exactly 0 (with ry = 0 too: the none-lit ellipse)
  RxBig,         // sqrt 2 < rx <= ry <= 4
  Circle,        // rx = ry
  Eccentric,     // ry / rx between 10^3 and 10^12
  Count
};
const char* ellipse_kind_name(EllipseKind k);
// Axes unit, canonical sign and rx <= ry as fit_ellipse returns them.
bumpshadow::Ellipse make_ellipse(EllipseKind k, bumpshadow::SplitMix64& rng);

enum class FieldKind {
  Flat,   // constant height
  Spike,  // one texel raised by `scale`
  Cliff,  // the right half raised by `scale`
  Noise,  // every texel uniform in [0, scale] (noise at the texel scale)
  Count
};
const char* field_kind_name(FieldKind k);
// Throws bumpshadow::HeightFieldError for sizes the library refuses (1x1, 1xN).
bumpshadow::HeightField make_field(FieldKind k, int w, int h, double scale, bumpshadow::Border border,
                                   std::uint64_t seed);

// Seed of case `index` of a run with master seed `master` (splitmix64 hash).
std::uint64_t case_seed(std::uint64_t master, std::uint64_t index);

}  // namespace ffsim::stress

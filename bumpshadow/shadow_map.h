// The ellipse shadow map of a whole height field (paper section 2): visibility
// and fit for every texel, multithreaded, with per-map counts of degenerate
// texels and the agreement of the fitted ellipses with the ray-cast visibility.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "bumpshadow/ellipse_fit.h"
#include "bumpshadow/heightfield.h"
#include "bumpshadow/parallel.h"
#include "bumpshadow/visibility.h"

namespace ffsim::bumpshadow {

struct ShadowMapOptions {
  RayOptions rays;
  FitOptions fit;
  int threads = 0;    // 0: all hardware threads; the result does not depend on it
  Progress progress;  // optional
};

struct EllipseMap {
  int width = 0, height = 0;
  int rays_per_texel = 0;
  std::vector<Ellipse> ellipse;          // row-major
  std::vector<TexelKind> kind;           // row-major
  std::vector<std::uint32_t> agree;      // rays where the ellipse test matches visibility
  std::array<long long, kTexelKinds> kind_count{};  // texels of each kind
  // Fraction of all (texel, ray) pairs on which the float64 ellipse test agrees.
  double agreement() const;
  bool operator==(const EllipseMap&) const;
};

EllipseMap compute_ellipse_map(const HeightField& hf, const ShadowMapOptions& o);

// Canonical text of every option that changes the result (for cache keys and reports).
std::string describe_options(const ShadowMapOptions& o);

}  // namespace ffsim::bumpshadow

// The paper's shadow test evaluated in float64 for a whole map (no hardware,
// no quantisation), and its comparison with the exact ray-cast reference: this
// separates the error of the ellipse approximation itself from the error of any
// hardware path that evaluates eq. 4.1 or 5.1 in fixed point.
#pragma once
#include <cstdint>
#include <vector>

#include "bumpshadow/encodings.h"
#include "bumpshadow/shadow_map.h"

namespace ffsim::bumpshadow {

// d = rx^2 - (L.T1^r)^2 - (L.T2^r)^2 per texel (row-major), (lx, ly) the
// projection of the normalised light direction; d >= 0 means lit.
std::vector<double> ellipse_test_map(const EllipseMap& m, const Vec3& light);

struct ShadowErrorStats {
  long long texels = 0;
  long long false_lit = 0;     // ellipse says lit, the reference says shadow
  long long false_shadow = 0;  // ellipse says shadow, the reference says lit
  double error_fraction() const {
    return texels ? static_cast<double>(false_lit + false_shadow) / static_cast<double>(texels) : 0.0;
  }
};

// Compares the hard verdicts (d >= 0) with a reference lit map of the same size
// (reference_lit_map). Throws HeightFieldError on a size mismatch.
ShadowErrorStats compare_with_reference(const std::vector<double>& d, const std::vector<std::uint8_t>& reference_lit);
// The same for any binary lit map (e.g. horizon_lit_map of horizon.h).
ShadowErrorStats compare_lit_maps(const std::vector<std::uint8_t>& lit, const std::vector<std::uint8_t>& reference_lit);

}  // namespace ffsim::bumpshadow

// Max's horizon map ("Horizon mapping", 1988; docs/bumpshadow.md §7): for every
// texel the horizon elevation angle toward n equally spaced azimuths
// theta_k = 2 pi k / n (k = 0 is +x, counter-clockwise), computed with the same
// march as the visibility rays. At render time the horizon angle is linearly
// interpolated between the two tabulated azimuths around the light's azimuth
// (Max section 2), then compared with the light's elevation; a disc light of
// angular diameter delta gets the visible fraction f(alpha) of Max section 5.
#pragma once
#include <cstdint>
#include <vector>

#include "bumpshadow/encodings.h"
#include "bumpshadow/heightfield.h"
#include "bumpshadow/parallel.h"
#include "bumpshadow/visibility.h"

namespace ffsim::bumpshadow {

struct HorizonMap {
  int width = 0, height = 0, azimuths = 0;
  std::vector<double> elevation;  // radians >= 0, ((y * width + x) * azimuths + k)
  double at(int x, int y, int k) const {
    return elevation[(static_cast<std::size_t>(y) * width + x) * azimuths + k];
  }
};

// azimuths >= 1 (8, 16, 32 ... in Max's usage).
HorizonMap compute_horizon_map(const HeightField& hf, int azimuths, const MarchOptions& m = {}, int threads = 0,
                               const Progress& progress = {});

// Horizon elevation at azimuth phi (radians), linear in phi between the two
// neighbouring tabulated directions (wrapping around 2 pi).
double horizon_elevation(const HorizonMap& h, int x, int y, double phi);

// Max's penumbra fraction: 0 for alpha <= -1, 1 for alpha >= 1, else
// 1/2 + (asin(alpha) + alpha sqrt(1 - alpha^2)) / pi.
double penumbra_fraction(double alpha);

// Light reaching texel (x, y) per the horizon map: with diameter == 0, 1 if the
// light's elevation >= the interpolated horizon, else 0; with diameter > 0,
// f(alpha), alpha = (elevation - horizon) / (diameter / 2) (Max's alpha with
// beta - phi written in elevations). Lights with z <= 0 give 0.
double horizon_light(const HorizonMap& h, int x, int y, const Vec3& light, double diameter = 0);

// horizon_light with diameter 0 for every texel, as 0/1 (row-major).
std::vector<std::uint8_t> horizon_lit_map(const HorizonMap& h, const Vec3& light);

}  // namespace ffsim::bumpshadow

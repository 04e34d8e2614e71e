// The exact shadow references (docs/bumpshadow.md §6): what every variant's
// error is measured against. Light directions are unit vectors in the tangent
// frame (x along u, y along v, z the polygon normal), pointing toward the light.
#pragma once
#include <cstdint>
#include <vector>

#include "bumpshadow/encodings.h"
#include "bumpshadow/heightfield.h"
#include "bumpshadow/visibility.h"

namespace ffsim::bumpshadow {

// Binary: march from the texel centre toward the light (same surface, samples
// and rule as the visibility rays): lit iff tan(elevation) >= horizon tan along
// the light's azimuth. Lights at or below the tangent plane (z <= 0) are shadowed;
// the zenith is always lit. L need not be normalised (only its direction counts).
bool reference_lit(const HeightField& hf, int i, int j, const Vec3& light, const MarchOptions& m = {});

// Soft: the visible fraction of a disc light of angular diameter `diameter`
// (radians, 0 < diameter < pi) centred on `light`: the mean of reference_lit over
// `samples` directions L + a U + b V with (a, b) on a Vogel (golden-angle) spiral
// filling the disc of radius tan(diameter/2) (U, V orthonormal, perpendicular to L).
double reference_visible_fraction(const HeightField& hf, int i, int j, const Vec3& light, double diameter,
                                  int samples = 64, const MarchOptions& m = {});

// Whole-field versions (row-major, multithreaded, thread-count independent).
std::vector<std::uint8_t> reference_lit_map(const HeightField& hf, const Vec3& light, const MarchOptions& m = {},
                                            int threads = 0);
std::vector<double> reference_soft_map(const HeightField& hf, const Vec3& light, double diameter, int samples = 64,
                                       const MarchOptions& m = {}, int threads = 0);

// The light's projection into the tangent plane, the (lx, ly) of the paper's
// shadow test: normalize(L).xy. A NaN z (sqrt of a tiny negative radicand at a
// grazing light) counts as 0; the zero vector gives (0, 0).
void project_light(const Vec3& light, double& lx, double& ly);

}  // namespace ffsim::bumpshadow

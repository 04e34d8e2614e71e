// Hemisphere visibility by ray marching (paper section 2; docs/bumpshadow.md §3).
//
// Rays leave the texel centre (i, j, z(i, j)) over the upper hemisphere. A ray is
// a *shadow* ray if it passes below the bilinear surface at any march sample
// (z_surface > z_ray), otherwise a *light* ray. Along one azimuth the ray height
// rises linearly, so a ray at elevation e is shadowed exactly when
//   tan e < H = max_k (z(p_k) - z0) / t_k       (t_k = k * step)
// over the same march samples: one march per azimuth classifies every elevation
// at that azimuth, with results identical to marching each ray (docs §3.2).
#pragma once
#include <cstdint>
#include <vector>

#include "bumpshadow/heightfield.h"

namespace ffsim::bumpshadow {

struct MarchOptions {
  double step = 0.5;         // horizontal distance between samples, texels (> 0)
  double max_distance = 0;   // horizontal cut-off in texels; 0 = max(width, height)
};

// tan of the horizon elevation from texel (i, j) toward the horizontal direction
// (c, s) (unit): max(0, max_k (z(p_k) - z0) / t_k). Marching stops early once no
// sample can raise the maximum ((zmax - z0) / t <= H), at max_distance, or (clamp
// borders) once the march has left the sampled area in every moving coordinate.
// Stretches of the march that HeightField::block_max proves unable to raise the
// maximum are skipped; the result is bit-identical to the plain march
// (horizon_tan_unaccelerated, kept as the reference and tested against it).
double horizon_tan(const HeightField& hf, int i, int j, double c, double s, const MarchOptions& m);
double horizon_tan_unaccelerated(const HeightField& hf, int i, int j, double c, double s, const MarchOptions& m);

enum class RayDistribution {
  Cosine,   // uniform over the projected unit disc (cosine-weighted solid angle), default
  Uniform,  // uniform over solid angle
};
const char* distribution_name(RayDistribution d);

struct RayOptions {
  int azimuths = 16;    // strata in azimuth
  int elevations = 16;  // strata in elevation per azimuth; rays = azimuths * elevations
  RayDistribution distribution = RayDistribution::Cosine;
  std::uint64_t seed = 1;  // jitter inside the strata
  MarchOptions march;
};

// "about n rays": azimuths = elevations = max(2, round(sqrt(n))).
RayOptions rays_for_count(int n);

// The directions of a stratified jittered ray set, shared by every texel.
// Azimuth stratum a: phi_a = 2 pi (a + u_a) / A (one jitter per azimuth, so one
// march serves the column); elevation stratum e in azimuth a: q = (e + u_ae) / E,
// Cosine: projected radius r = sqrt(q); Uniform: cos(zenith angle) = 1 - q.
// Ray k = a * E + e. px, py: the unit direction projected into the tangent plane.
struct RaySet {
  int azimuths = 0, elevations = 0;
  std::vector<double> cos_az, sin_az;  // per azimuth
  std::vector<double> tan_elev;        // per ray (+inf at the zenith)
  std::vector<double> px, py;          // per ray
  int size() const { return azimuths * elevations; }
};
RaySet make_ray_set(const RayOptions& o);  // throws HeightFieldError on bad counts/step

// Visibility of every ray of `rays` from texel (i, j): lit[k] = 1 for a light ray.
// horizon receives the per-azimuth tan of the horizon. Returns the number lit.
int texel_visibility(const HeightField& hf, int i, int j, const RaySet& rays, const MarchOptions& m,
                     std::vector<double>& horizon, std::vector<std::uint8_t>& lit);

}  // namespace ffsim::bumpshadow

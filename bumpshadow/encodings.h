// Texture encodings of the ellipse shadow map (paper sections 4.1 and 5.1) and a
// normal map for dot-product bump mapping. docs/bumpshadow.md §5, numerics §11.
//
// Float maps hold the biased values exactly (binary64 here, binary32 in EXR
// files) and are NOT clamped, so out-of-range texels stay visible; 8-bit maps
// clamp to [0,1] and round half up (numerics §1.2). Every map reports the texels
// that break the paper's range assumptions and the components its 8-bit form
// clamps.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "bumpshadow/ellipse_fit.h"
#include "bumpshadow/heightfield.h"
#include "bumpshadow/shadow_map.h"

namespace ffsim::bumpshadow {

struct Vec3 {
  double x = 0, y = 0, z = 0;
};

// Unbiased per-texel vectors.
//   T1^r = (ax, ay, ax Cx + ay Cy)                     (section 4.1)
//   T2^r = q (-ay, ax, -ay Cx + ax Cy),  q = rx / ry
//   T1^n = (T1x^2 + T2x^2, 2 T1x T1y + 2 T2x T2y, -2 T1x T1z - 2 T2x T2z)   (5.1)
//   T2^n = (-2 T1y T1z - 2 T2y T2z, T1y^2 + T2y^2, T1z^2 + T2z^2)
struct TexelEncoding {
  Vec3 t1r, t2r, t1n, t2n;
  double rx2 = 0;  // r_x^2
};
TexelEncoding encode_texel(const Ellipse& e);

// Which constant vector multiplies T2^n. Consistent: L2^n = (ly, ly^2, 1), the
// pairing that reproduces eq. 4.1 (papers/README.md erratum). Printed: the
// paper's (ly^2, ly, 1), kept as a named variant to show its wrong shadows.
enum class L2Pairing { Consistent, Printed };

// Eq. 4.1: rx2 - (L.T1^r)^2 - (L.T2^r)^2 with L = (lx, ly, -1).
double eq41(const Vec3& t1r, const Vec3& t2r, double rx2, double lx, double ly);
// Eq. 5.1: rx2 - L1^n.T1^n - L2^n.T2^n with L1^n = (lx^2, lx ly, lx).
double eq51(const Vec3& t1n, const Vec3& t2n, double rx2, double lx, double ly,
            L2Pairing pairing = L2Pairing::Consistent);

struct FloatMap {
  std::string name;
  int width = 0, height = 0, channels = 0;
  std::vector<double> v;  // (y * width + x) * channels + c, row 0 at v = 0
};
struct ByteMap {
  std::string name;
  int width = 0, height = 0, channels = 0;
  std::vector<std::uint8_t> v;
};
// 8-bit codes: clamp to [0,1], k = round_half_up(255 x) (pipeline/number/unorm.h).
ByteMap quantise(const FloatMap& m, long long* clamped_components = nullptr);

struct RangeReport {
  std::string map;
  long long texels_out_of_range = 0;      // texels with a component outside its assumed range before biasing
  long long components_out_of_range = 0;  // such components
  long long components_clamped = 0;       // components the 8-bit map clamped to 0 or 255
};

struct EncodedMaps {
  // t1r, t2r: RGBA biased (c+1)/2, alpha 1 (section 4.1.2). t3r: one channel,
  // rx^2/2 (4.1.1). t1n: RGBA biased, alpha rx^2 unbiased (5.1.1). t2n: RGBA
  // biased, alpha 1.
  FloatMap t1r, t2r, t3r, t1n, t2n;
  ByteMap t1r8, t2r8, t3r8, t1n8, t2n8;
  std::vector<RangeReport> ranges;  // one per map, in the order above
  long long center_outside_unit = 0;  // |C| > 1 (section 4.1's assumption)
  long long rx_above_sqrt2 = 0;       // rx > sqrt 2: T3^r alpha > 1 (4.1.1)
  long long rx_above_1 = 0;           // rx > 1: T1^n alpha > 1 (5.1.1)
};
EncodedMaps encode_maps(const EllipseMap& m);

// Normal map from the height field by central differences with the border rule:
// n = normalize(-(z(x+1)-z(x-1))/2, -(z(y+1)-z(y-1))/2, 1), RGB biased (n+1)/2.
FloatMap normal_map(const HeightField& hf);

// Decoding of 8-bit codes: biased component 2k/255 - 1; T3^r alpha 2k/255 (= rx^2);
// T1^n alpha k/255 (= rx^2).
inline double decode_biased(std::uint8_t k) { return 2.0 * k / 255.0 - 1.0; }
Vec3 decode_rgb(const ByteMap& m, int x, int y);

// Quantisation bounds (docs/numerics.md §11): |d(decoded 8-bit) - d(float)| for
// in-range texels, plus 1e-12 for binary64 rounding.
//   eq. 4.1: 1/255 + sum_k (2|s_k| delta + delta^2),  delta = (|lx| + |ly| + 1)/255,
//            s_k = L.T_k^r of the float map.
//   eq. 5.1: 1/510 + (lx^2 + |lx ly| + |lx| + |ly| + ly^2 + 1)/255.
double quantisation_bound41(const Vec3& t1r, const Vec3& t2r, double lx, double ly);
double quantisation_bound51(double lx, double ly);

}  // namespace ffsim::bumpshadow

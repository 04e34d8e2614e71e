// Height fields: the bump maps whose shadows bumpshadow precomputes.
//
// Coordinates (docs/bumpshadow.md §1): texel (i, j) is the sample at the
// continuous point (x, y) = (i, j); x runs along u (columns), y along v (rows,
// row 0 at v = 0, the bottom row of a GL image). Heights are in texel units: a
// height of 1 equals one texel spacing. Between samples the surface is the
// bilinear interpolation of the four surrounding samples; outside the field the
// border rule supplies samples (Wrap: periodic tiling; Clamp: the nearest edge
// sample, i.e. a constant plateau continuing each edge).
#pragma once
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace ffsim::bumpshadow {

enum class Border { Wrap, Clamp };
const char* border_name(Border b);  // "wrap" / "clamp"

struct HeightFieldError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline constexpr int kMaxHeightFieldSide = 16384;
inline constexpr long long kMaxHeightFieldTexels = 1ll << 26;

// Row-major heights. Construction validates: 1..16384 texels per side, at most
// 2^26 texels (a 1-texel side has no neighbour to cast or receive a shadow), the
// sample count, and finiteness; every error names the offending value.
class HeightField {
 public:
  HeightField(int width, int height, std::vector<double> heights, Border border);
  int width() const { return w_; }
  int height() const { return h_; }
  Border border() const { return border_; }
  // Sample at integer texel (x, y) with the border rule applied.
  double at(int x, int y) const;
  // Bilinear interpolation at the continuous point (x, y), border rule applied.
  double sample(double x, double y) const;
  double max_height() const { return zmax_; }
  // Upper bound of every bilinear sample whose floor coordinates (fx, fy) lie
  // within kBlockRadius of (x, y) in each coordinate: the maximum height of the
  // texels [x - R, x + R + 1] x [y - R, y + R + 1] (border rule applied). Lets the
  // horizon march skip stretches that cannot raise the horizon (visibility.cpp).
  static constexpr int kBlockRadius = 8;
  double block_max(int x, int y) const;
  double min_height() const { return zmin_; }
  const std::vector<double>& data() const { return z_; }
  // Content hash (FNV-1a 64 over size, border and the binary64 heights, -0 as +0).
  std::uint64_t hash() const;
  // Heights multiplied by s (s must be finite and > 0).
  HeightField scaled(double s) const;

 private:
  // Row-major index of (x, y) after the border rule (wrap or clamp).
  std::size_t border_index(int x, int y) const;
  int w_, h_;
  std::vector<double> z_;
  Border border_;
  double zmax_ = 0, zmin_ = 0;
  std::vector<double> block_;  // block_max of every texel, row-major
};

// FNV-1a 64 (offset basis 0xcbf29ce484222325, prime 0x100000001b3): the same
// algorithm as sim/hash.h, repeated here because bumpshadow may not depend on sim.
struct Fnv64 {
  std::uint64_t state = 0xcbf29ce484222325ull;
  void byte(std::uint8_t b) { state = (state ^ b) * 0x100000001b3ull; }
  void u64(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) byte(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void f64(double d);  // bit pattern, little-endian, -0 written as +0
  void str(const std::string& s) {
    u64(s.size());
    for (unsigned char c : s) byte(c);
  }
};

}  // namespace ffsim::bumpshadow

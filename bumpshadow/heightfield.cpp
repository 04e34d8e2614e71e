#include "bumpshadow/heightfield.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>

namespace ffsim::bumpshadow {

const char* border_name(Border b) { return b == Border::Wrap ? "wrap" : "clamp"; }

void Fnv64::f64(double d) {
  if (d == 0.0) d = 0.0;  // -0 hashes like +0
  u64(std::bit_cast<std::uint64_t>(d));
}

HeightField::HeightField(int width, int height, std::vector<double> heights, Border border)
    : w_(width), h_(height), z_(std::move(heights)), border_(border) {
  if (w_ < 1 || h_ < 1 || w_ > kMaxHeightFieldSide || h_ > kMaxHeightFieldSide ||
      static_cast<long long>(w_) * h_ > kMaxHeightFieldTexels)
    throw HeightFieldError("height field size " + std::to_string(w_) + "x" + std::to_string(h_) +
                           " is out of range (1..16384 per side, at most 2^26 texels)");
  if (z_.size() != static_cast<std::size_t>(w_) * h_)
    throw HeightFieldError("height field has " + std::to_string(z_.size()) + " samples, expected " +
                           std::to_string(static_cast<std::size_t>(w_) * h_));
  for (std::size_t i = 0; i < z_.size(); ++i)
    if (!std::isfinite(z_[i]))
      throw HeightFieldError("non-finite height at x=" + std::to_string(i % w_) + " y=" + std::to_string(i / w_));
  zmax_ = *std::max_element(z_.begin(), z_.end());
  zmin_ = *std::min_element(z_.begin(), z_.end());
  // Separable sliding maximum over [-R, R + 1] in x, then in y.
  constexpr int R = kBlockRadius;
  std::vector<double> mx(z_.size());
  for (int y = 0; y < h_; ++y)
    for (int x = 0; x < w_; ++x) {
      double m = at(x - R, y);
      for (int d = -R + 1; d <= R + 1; ++d) m = std::max(m, at(x + d, y));
      mx[static_cast<std::size_t>(y) * w_ + x] = m;
    }
  auto mx_at = [&](int x, int y) {
    if (border_ == Border::Wrap) y = ((y % h_) + h_) % h_;
    else y = std::clamp(y, 0, h_ - 1);
    return mx[static_cast<std::size_t>(y) * w_ + x];
  };
  block_.resize(z_.size());
  for (int y = 0; y < h_; ++y)
    for (int x = 0; x < w_; ++x) {
      double m = mx_at(x, y - R);
      for (int d = -R + 1; d <= R + 1; ++d) m = std::max(m, mx_at(x, y + d));
      block_[static_cast<std::size_t>(y) * w_ + x] = m;
    }
}

double HeightField::block_max(int x, int y) const {
  // Wrap: the window of x mod w holds the same texels. Clamp: the window of the
  // clamped coordinate contains the clamped image of the window of x.
  return block_[border_index(x, y)];
}

std::size_t HeightField::border_index(int x, int y) const {
  if (border_ == Border::Wrap) {
    x = ((x % w_) + w_) % w_;
    y = ((y % h_) + h_) % h_;
  } else {
    x = std::clamp(x, 0, w_ - 1);
    y = std::clamp(y, 0, h_ - 1);
  }
  return static_cast<std::size_t>(y) * w_ + x;
}

double HeightField::at(int x, int y) const { return z_[border_index(x, y)]; }

double HeightField::sample(double x, double y) const {
  const double fx0 = std::floor(x), fy0 = std::floor(y);
  const double fx = x - fx0, fy = y - fy0;
  const int x0 = static_cast<int>(fx0), y0 = static_cast<int>(fy0);
  double z00, z10, z01, z11;
  if (x0 >= 0 && y0 >= 0 && x0 + 1 < w_ && y0 + 1 < h_) {
    const double* r0 = &z_[static_cast<std::size_t>(y0) * w_ + x0];
    const double* r1 = r0 + w_;
    z00 = r0[0], z10 = r0[1], z01 = r1[0], z11 = r1[1];
  } else {
    z00 = at(x0, y0), z10 = at(x0 + 1, y0), z01 = at(x0, y0 + 1), z11 = at(x0 + 1, y0 + 1);
  }
  const double a = z00 + (z10 - z00) * fx;
  const double b = z01 + (z11 - z01) * fx;
  return a + (b - a) * fy;
}

std::uint64_t HeightField::hash() const {
  Fnv64 f;
  f.str("ffsim-heightfield-1");
  f.u64(static_cast<std::uint64_t>(w_));
  f.u64(static_cast<std::uint64_t>(h_));
  f.byte(border_ == Border::Wrap ? 'W' : 'C');
  for (double v : z_) f.f64(v);
  return f.state;
}

HeightField HeightField::scaled(double s) const {
  if (!std::isfinite(s) || s <= 0)
    throw HeightFieldError("height scale " + std::to_string(s) + " must be finite and > 0");
  std::vector<double> z(z_);
  for (double& v : z) v *= s;
  return HeightField(w_, h_, std::move(z), border_);
}

}  // namespace ffsim::bumpshadow

#include "bumpshadow/heightfield.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace ffsim::bumpshadow {

HeightField::HeightField(int width, int height, std::vector<double> heights, Border border)
    : w_(width), h_(height), z_(std::move(heights)), border_(border) {
  if (w_ < 1 || h_ < 1 || w_ > 16384 || h_ > 16384)
    throw HeightFieldError("height field size " + std::to_string(w_) + "x" + std::to_string(h_) +
                           " is out of range (1..16384 per side)");
  if (z_.size() != static_cast<std::size_t>(w_) * h_)
    throw HeightFieldError("height field has " + std::to_string(z_.size()) + " samples, expected " +
                           std::to_string(static_cast<std::size_t>(w_) * h_));
  for (std::size_t i = 0; i < z_.size(); ++i)
    if (!std::isfinite(z_[i]))
      throw HeightFieldError("non-finite height at x=" + std::to_string(i % w_) + " y=" + std::to_string(i / w_));
}

double HeightField::at(int x, int y) const {
  if (border_ == Border::Wrap) {
    x = ((x % w_) + w_) % w_;
    y = ((y % h_) + h_) % h_;
  } else {
    x = std::clamp(x, 0, w_ - 1);
    y = std::clamp(y, 0, h_ - 1);
  }
  return z_[static_cast<std::size_t>(y) * w_ + x];
}

HeightField hemisphere_bump(int width, int height, double radius, Border border) {
  std::vector<double> z(static_cast<std::size_t>(std::max(width, 0)) * std::max(height, 0), 0.0);
  const double cx = 0.5 * width, cy = 0.5 * height;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double dx = x + 0.5 - cx, dy = y + 0.5 - cy, r2 = radius * radius - dx * dx - dy * dy;
      z[static_cast<std::size_t>(y) * width + x] = r2 > 0 ? std::sqrt(r2) : 0.0;
    }
  return HeightField(width, height, std::move(z), border);
}

}  // namespace ffsim::bumpshadow

// Height fields: the bump maps whose shadows bumpshadow precomputes.
#pragma once
#include <cstddef>
#include <stdexcept>
#include <vector>

namespace ffsim::bumpshadow {

// How samples outside [0, width) x [0, height) are found.
enum class Border { Wrap, Clamp };

struct HeightFieldError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Heights in texel units (a height of 1 equals one texel spacing), row-major,
// row 0 at v = 0. Construction validates size (1..16384 per side) and finiteness.
class HeightField {
 public:
  HeightField(int width, int height, std::vector<double> heights, Border border);
  int width() const { return w_; }
  int height() const { return h_; }
  Border border() const { return border_; }
  // Sample at integer texel (x, y) with the border rule applied.
  double at(int x, int y) const;
  const std::vector<double>& data() const { return z_; }

 private:
  int w_, h_;
  std::vector<double> z_;
  Border border_;
};

// A single hemispherical bump of the given radius (texels) centred in the field.
HeightField hemisphere_bump(int width, int height, double radius, Border border = Border::Clamp);

}  // namespace ffsim::bumpshadow

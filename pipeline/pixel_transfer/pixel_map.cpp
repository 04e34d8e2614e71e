#include "pipeline/pixel_transfer/pixel_map.h"

namespace ffsim::pixel {

template <class T>
void map_color(RgbaImage<T>& img, const std::array<std::vector<double>, 4>& maps) {
  std::array<std::vector<T>, 4> m;
  for (int c = 0; c < 4; ++c)
    for (double e : maps[c]) m[c].push_back(static_cast<T>(e));
  const std::size_t n = img.size();
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 4; ++c) {
      T& v = img.px[4 * i + c];
      v = m[c][table_index(v, static_cast<int>(m[c].size()))];
    }
}

template void map_color<float>(RgbaImage<float>&, const std::array<std::vector<double>, 4>&);
template void map_color<double>(RgbaImage<double>&, const std::array<std::vector<double>, 4>&);

}  // namespace ffsim::pixel

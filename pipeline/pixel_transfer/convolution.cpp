#include "pipeline/pixel_transfer/convolution.h"

#include <algorithm>

namespace ffsim::pixel {

template <class T>
std::vector<double> make_filter_taps(const RgbaImage<T>& groups, const ConvolutionFilter& f) {
  const std::array<bool, 4> used = replaced_components(f.base);
  std::vector<double> taps(groups.px.size(), 0.0);
  for (std::size_t i = 0; i < groups.size(); ++i) {
    T scaled[4];
    for (int c = 0; c < 4; ++c) {
      const T prod = groups.px[4 * i + c] * static_cast<T>(f.filter_scale[c]);
      scaled[c] = prod + static_cast<T>(f.filter_bias[c]);
    }
    for (int c = 0; c < 4; ++c) {
      if (!used[c]) continue;
      // L and I come from R (Table 3.15); A of LUMINANCE_ALPHA from A.
      const int from = (f.base == BaseFormat::Luminance || f.base == BaseFormat::Intensity ||
                        (f.base == BaseFormat::LuminanceAlpha && c < 3))
                           ? 0
                           : c;
      taps[4 * i + c] = static_cast<double>(scaled[from]);
    }
  }
  return taps;
}

void convolved_size(const ConvolutionFilter& f, FilterKind kind, int width, int height, int& out_w, int& out_h) {
  out_w = width;
  out_h = height;
  if (f.border_mode != BorderMode::Reduce) return;
  out_w = width - (f.width - 1);
  out_h = kind == FilterKind::OneD ? height : height - (f.height - 1);
}

template <class T>
RgbaImage<T> convolve(const RgbaImage<T>& img, const ConvolutionFilter& f, FilterKind kind) {
  int ow = 0, oh = 0;
  convolved_size(f, kind, img.width, img.height, ow, oh);
  if (ow <= 0 || oh <= 0) return RgbaImage<T>(0, 0);
  RgbaImage<T> out(ow, oh);
  const int wf = f.width;
  const int hf = kind == FilterKind::OneD ? 1 : f.height;
  const int cw = wf / 2, ch = hf / 2;
  const bool reduce = f.border_mode == BorderMode::Reduce;
  const std::array<bool, 4> used = replaced_components(f.base);
  // Taps in T.
  std::vector<T> taps, row, col;
  if (kind == FilterKind::Separable) {
    for (double v : f.row) row.push_back(static_cast<T>(v));
    for (double v : f.column) col.push_back(static_cast<T>(v));
  } else {
    for (double v : f.taps) taps.push_back(static_cast<T>(v));
  }
  T border[4];
  for (int c = 0; c < 4; ++c) border[c] = static_cast<T>(f.border_color[c]);
  // Source pixel (x, y) or its border substitute.
  const auto source = [&](int x, int y) -> const T* {
    if (x >= 0 && x < img.width && y >= 0 && y < img.height) return img.at(x, y);
    if (f.border_mode == BorderMode::ReplicateBorder)
      return img.at(std::clamp(x, 0, img.width - 1), std::clamp(y, 0, img.height - 1));
    return border;  // CONSTANT_BORDER (REDUCE never reads outside)
  };
  const int ox = reduce ? 0 : -cw, oy = reduce ? 0 : -ch;
  for (int j = 0; j < oh; ++j)
    for (int i = 0; i < ow; ++i) {
      T acc[4] = {T(0), T(0), T(0), T(0)};
      for (int n = 0; n < wf; ++n)
        for (int m = 0; m < hf; ++m) {
          const T* s = source(i + n + ox, j + m + oy);
          for (int c = 0; c < 4; ++c) {
            if (!used[c]) continue;
            T prod;
            if (kind == FilterKind::Separable) {
              const T p1 = s[c] * row[4 * static_cast<std::size_t>(n) + c];
              prod = p1 * col[4 * static_cast<std::size_t>(m) + c];
            } else {
              prod = s[c] * taps[4 * (static_cast<std::size_t>(m) * wf + n) + c];
            }
            acc[c] = acc[c] + prod;
          }
        }
      const T* centre = reduce ? img.at(i + cw, j + ch) : img.at(i, j);
      T* o = out.at(i, j);
      for (int c = 0; c < 4; ++c) o[c] = used[c] ? acc[c] : centre[c];
    }
  return out;
}

template std::vector<double> make_filter_taps<float>(const RgbaImage<float>&, const ConvolutionFilter&);
template std::vector<double> make_filter_taps<double>(const RgbaImage<double>&, const ConvolutionFilter&);
template RgbaImage<float> convolve<float>(const RgbaImage<float>&, const ConvolutionFilter&, FilterKind);
template RgbaImage<double> convolve<double>(const RgbaImage<double>&, const ConvolutionFilter&, FilterKind);

}  // namespace ffsim::pixel

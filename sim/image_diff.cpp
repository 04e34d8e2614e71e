#include "sim/image_diff.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ffsim {

ImageDiff diff_images(const Image& a, const Image& b) {
  ImageDiff d;
  if (a.width != b.width || a.height != b.height || a.channels != b.channels) {
    d.same_shape = false;
    d.shape_note = std::string("shapes differ: ") + std::to_string(a.width) + "x" + std::to_string(a.height) + "x" +
                   std::to_string(a.channels) + " vs " + std::to_string(b.width) + "x" + std::to_string(b.height) +
                   std::string("x") + std::to_string(b.channels);
    return d;
  }
  d.width = a.width;
  d.height = a.height;
  d.channels = a.channels;
  d.total_pixels = static_cast<long long>(a.width) * a.height;
  d.lsb_bits = (a.type == SampleType::U16 && b.type == SampleType::U16) ? 16 : 8;
  const double lsb = static_cast<double>((1u << d.lsb_bits) - 1u);
  d.max_lsb.assign(static_cast<std::size_t>(a.channels), 0.0);
  d.is_mask = a.channels == 1;
  std::vector<double> pixel_max(static_cast<std::size_t>(d.total_pixels), 0.0);
  double sum_sq = 0, overall_max = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      bool differs = false;
      double pm = 0;
      for (int c = 0; c < a.channels; ++c) {
        const double va = a.value(x, y, c), vb = b.value(x, y, c);
        const double e = std::fabs(va - vb);
        if (va != vb) differs = true;
        sum_sq += e * e;
        const double l = e * lsb;
        d.max_lsb[static_cast<std::size_t>(c)] = std::max(d.max_lsb[static_cast<std::size_t>(c)], l);
        pm = std::max(pm, l);
      }
      if (differs) ++d.differing_pixels;
      if (d.is_mask && ((a.value(x, y, 0) > 0) != (b.value(x, y, 0) > 0))) ++d.lit_shadow_disagreements;
      pixel_max[static_cast<std::size_t>(y) * a.width + x] = pm;
      overall_max = std::max(overall_max, pm);
    }
  const double samples = static_cast<double>(d.total_pixels) * a.channels;
  d.rmse = std::sqrt(sum_sq / samples);
  d.psnr = d.rmse == 0 ? std::numeric_limits<double>::infinity() : 20 * std::log10(1 / d.rmse);
  d.heatmap = Image::make(a.width, a.height, 3, SampleType::U8);
  for (std::size_t i = 0; i < pixel_max.size(); ++i) {
    if (pixel_max[i] == 0) continue;
    const double t = 0.25 + 0.75 * (overall_max > 0 ? pixel_max[i] / overall_max : 1);  // any difference is visible
    const double rgb[3] = {std::min(1.0, 3 * t), std::clamp(3 * t - 1, 0.0, 1.0), std::clamp(3 * t - 2, 0.0, 1.0)};
    for (int c = 0; c < 3; ++c) d.heatmap.u8[i * 3 + static_cast<std::size_t>(c)] = static_cast<std::uint8_t>(std::lround(rgb[c] * 255));
  }
  return d;
}

}  // namespace ffsim

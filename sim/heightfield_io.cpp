#include "sim/heightfield_io.h"

#include <cmath>

namespace ffsim {

bumpshadow::HeightField load_heightfield(const std::string& path, double scale, bumpshadow::Border border) {
  if (!std::isfinite(scale) || scale <= 0)
    throw bumpshadow::HeightFieldError(path + ": height scale must be finite and > 0");
  const Image im = read_image(path);
  if (im.width < 2 || im.height < 2)
    throw bumpshadow::HeightFieldError(path + ": " + std::to_string(im.width) + "x" + std::to_string(im.height) +
                                       " image is too small for a height field (at least 2x2)");
  std::vector<double> z(static_cast<std::size_t>(im.width) * im.height);
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) z[static_cast<std::size_t>(y) * im.width + x] = im.value(x, y, 0) * scale;
  try {
    return bumpshadow::HeightField(im.width, im.height, std::move(z), border);
  } catch (const bumpshadow::HeightFieldError& e) {
    throw bumpshadow::HeightFieldError(path + ": " + e.what());
  }
}

Image float_map_image(const bumpshadow::FloatMap& m) {
  Image im = Image::make(m.width, m.height, m.channels, SampleType::F32);
  for (std::size_t i = 0; i < m.v.size(); ++i) im.f32[i] = static_cast<float>(m.v[i]);
  return im;
}

Image byte_map_image(const bumpshadow::ByteMap& m) {
  Image im = Image::make(m.width, m.height, m.channels, SampleType::U8);
  im.u8 = m.v;
  return im;
}

Image heightfield_image(const bumpshadow::HeightField& hf) {
  Image im = Image::make(hf.width(), hf.height(), 1, SampleType::F32);
  for (std::size_t i = 0; i < hf.data().size(); ++i) im.f32[i] = static_cast<float>(hf.data()[i]);
  return im;
}

Image horizon_group_image(const bumpshadow::HorizonMap& h, int group) {
  Image im = Image::make(h.width, h.height, 4, SampleType::F32);
  for (int y = 0; y < h.height; ++y)
    for (int x = 0; x < h.width; ++x)
      for (int c = 0; c < 4; ++c) {
        const int k = 4 * group + c;
        im.f32[im.index(x, y, c)] = k < h.azimuths ? static_cast<float>(h.at(x, y, k)) : 0.0f;
      }
  return im;
}

}  // namespace ffsim

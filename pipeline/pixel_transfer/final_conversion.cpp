#include "pipeline/pixel_transfer/final_conversion.h"

#include <type_traits>

#include "pipeline/number/unorm.h"
#include "pipeline/pixel_transfer/pixel_state.h"

namespace ffsim::pixel {

template <class T>
std::uint16_t final_code(T v, int bits) {
  // unorm_from_double clamps to [0,1] (NaN -> 0) and rounds the exact value half
  // up; unorm_from_float is the same function on binary32 values, in 64 bits.
  if constexpr (std::is_same_v<T, float>) return static_cast<std::uint16_t>(unorm_from_float(v, bits));
  else return static_cast<std::uint16_t>(unorm_from_double(static_cast<double>(v), bits));
}

template <class T>
double final_value(T v, Arithmetic a) {
  const T c = clamp01(v);
  return a == Arithmetic::Float32 ? static_cast<double>(static_cast<float>(c)) : static_cast<double>(c);
}

int texture_storage_bits(const InternalFormat& f, const Profile& p) {
  return f.sized_bits > 0 ? f.sized_bits : p.texture_bits;
}

template <class T>
void store_texels(const RgbaImage<T>& img, TextureImage& dst, int x0, int y0, const Profile& p) {
  const int nc = component_count(dst.base);
  const bool fixed = p.is_fixed();
  // Per-component rounding width (mixed-width sized formats, formats.h).
  int cbits[4] = {dst.bits, dst.bits, dst.bits, dst.bits};
  if (const auto f = texture_internal_format(dst.internal_format); f && f->sized_bits == dst.bits)
    for (int k = 0; k < 4; ++k)
      if (f->component_bits[k] > 0) cbits[k] = f->component_bits[k];
  // The common case (a fixed profile, every component of the level's width): the
  // same final_code per component, the components' RGBA slots found once.
  int slot[4] = {0, 0, 0, 0};
  bool uniform = fixed;
  for (int k = 0; k < nc; ++k) {
    slot[k] = rgba_component_for(dst.base, k);
    uniform = uniform && cbits[k] == dst.bits;
  }
  if (uniform) {
    if (img.empty()) return;
    const std::size_t row = static_cast<std::size_t>(img.width) * static_cast<std::size_t>(nc);
    for (int y = 0; y < img.height; ++y) {
      const T* c = img.at(0, y);
      std::uint16_t* out = dst.codes.data() + (static_cast<std::size_t>(y0 + y) * static_cast<std::size_t>(dst.width) +
                                               static_cast<std::size_t>(x0)) * static_cast<std::size_t>(nc);
      for (std::size_t i = 0, x4 = 0; i < row; i += static_cast<std::size_t>(nc), x4 += 4)
        for (int k = 0; k < nc; ++k) out[i + static_cast<std::size_t>(k)] = final_code(c[x4 + static_cast<std::size_t>(slot[k])], dst.bits);
    }
    return;
  }
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const T* c = img.at(x, y);
      const std::size_t t = (static_cast<std::size_t>(y0 + y) * dst.width + (x0 + x)) * nc;
      for (int k = 0; k < nc; ++k) {
        const T v = c[rgba_component_for(dst.base, k)];
        if (fixed)
          dst.codes[t + k] = cbits[k] == dst.bits
                                 ? final_code(v, dst.bits)
                                 : static_cast<std::uint16_t>(unorm_convert(final_code(v, cbits[k]), cbits[k], dst.bits));
        else dst.values[t + k] = final_value(v, p.arithmetic);
      }
    }
}

TextureImage texture_level(int width, int height, GLenum internal_format, const InternalFormat& f, int border,
                           const Profile& p) {
  TextureImage t;
  t.width = width;
  t.height = height;
  t.border = border;
  t.internal_format = internal_format;
  t.base = f.base;
  t.bits = texture_storage_bits(f, p);
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) *
                        static_cast<std::size_t>(component_count(f.base));
  if (p.is_fixed()) t.codes.assign(n, 0);
  else t.values.assign(n, 0.0);
  return t;
}

template <class T>
TextureImage make_texture_image(const RgbaImage<T>& img, GLenum internal_format, const InternalFormat& f,
                                int border, const Profile& p) {
  TextureImage t = texture_level(img.width, img.height, internal_format, f, border, p);
  store_texels(img, t, 0, 0, p);
  return t;
}

template std::uint16_t final_code<float>(float, int);
template std::uint16_t final_code<double>(double, int);
template double final_value<float>(float, Arithmetic);
template double final_value<double>(double, Arithmetic);
template TextureImage make_texture_image<float>(const RgbaImage<float>&, GLenum, const InternalFormat&, int,
                                                const Profile&);
template TextureImage make_texture_image<double>(const RgbaImage<double>&, GLenum, const InternalFormat&, int,
                                                 const Profile&);
template void store_texels<float>(const RgbaImage<float>&, TextureImage&, int, int, const Profile&);
template void store_texels<double>(const RgbaImage<double>&, TextureImage&, int, int, const Profile&);

}  // namespace ffsim::pixel

#include "pipeline/pixel_transfer/unpack.h"

#include <array>
#include <cmath>
#include <cstring>

#include "pipeline/pixel_transfer/formats.h"

namespace ffsim::pixel {

__extension__ typedef unsigned __int128 u128;

std::size_t ClientLayout::extent(int width, int height) const {
  if (width <= 0 || height <= 0) return 0;
  return offset(width - 1, height - 1) + static_cast<std::size_t>(group_bytes);
}

ClientLayout client_layout(const PixelStoreModes& m, int width, int /*height*/, int components, int elem_size) {
  // GL121 §3.6.4: l = ROW_LENGTH or width; k = n*l elements when s >= a, else
  // (a/s) * ceil(s*n*l / a); the skips advance by whole groups and rows.
  const std::size_t n = static_cast<std::size_t>(components);
  const std::size_t s = static_cast<std::size_t>(elem_size);
  const std::size_t a = static_cast<std::size_t>(m.alignment);
  const std::size_t l = static_cast<std::size_t>(m.row_length > 0 ? m.row_length : width);
  const std::size_t k = s >= a ? n * l : (a / s) * ((s * n * l + a - 1) / a);
  ClientLayout L;
  L.elem_size = elem_size;
  L.group_bytes = components * elem_size;
  L.row_stride = k * s;
  L.first = static_cast<std::size_t>(m.skip_rows) * L.row_stride + static_cast<std::size_t>(m.skip_pixels) * n * s;
  return L;
}

namespace {

void read_bytes(const unsigned char* p, int size, bool swap, unsigned char* out) {
  for (int i = 0; i < size; ++i) out[i] = p[swap ? size - 1 - i : i];
}

// One element as an integer (integer types) or binary32 (FLOAT).
struct Element {
  bool is_float = false;
  std::int64_t i = 0;
  float f = 0;
};

Element read_element(const unsigned char* p, GLenum type, bool swap) {
  unsigned char b[4];
  Element e;
  switch (type) {
    case gl::UNSIGNED_BYTE: e.i = p[0]; break;
    case gl::BYTE: e.i = static_cast<std::int8_t>(p[0]); break;
    case gl::UNSIGNED_SHORT: { std::uint16_t v; read_bytes(p, 2, swap, b); std::memcpy(&v, b, 2); e.i = v; break; }
    case gl::SHORT: { std::int16_t v; read_bytes(p, 2, swap, b); std::memcpy(&v, b, 2); e.i = v; break; }
    case gl::UNSIGNED_INT: { std::uint32_t v; read_bytes(p, 4, swap, b); std::memcpy(&v, b, 4); e.i = v; break; }
    case gl::INT: { std::int32_t v; read_bytes(p, 4, swap, b); std::memcpy(&v, b, 4); e.i = v; break; }
    case gl::FLOAT: { read_bytes(p, 4, swap, b); std::memcpy(&e.f, b, 4); e.is_float = true; break; }
    default: break;
  }
  return e;
}

// Table 2.6 conversion to a real in T. For 8- and 16-bit types numerator and
// denominator are exact in binary32, so one T division is correctly rounded; for
// 32-bit types the quotient is formed in binary64 and then rounded to T.
template <class T>
T element_to_real(const Element& e, GLenum type) {
  switch (type) {
    case gl::UNSIGNED_BYTE: return static_cast<T>(e.i) / T(255);
    case gl::BYTE: return static_cast<T>(2 * e.i + 1) / T(255);
    case gl::UNSIGNED_SHORT: return static_cast<T>(e.i) / T(65535);
    case gl::SHORT: return static_cast<T>(2 * e.i + 1) / T(65535);
    case gl::UNSIGNED_INT: return static_cast<T>(static_cast<double>(e.i) / 4294967295.0);
    case gl::INT: return static_cast<T>(static_cast<double>(2 * e.i + 1) / 4294967295.0);
    case gl::FLOAT: return static_cast<T>(e.f);
    default: return T(0);
  }
}

// For each client element position of `format`, the RGBA slot it fills; L fills 0..2.
struct FormatMap {
  int n = 0;
  int slot[4] = {0, 0, 0, 0};
  bool luminance = false;  // element 0 is L
};
FormatMap format_map(GLenum format) {
  switch (format) {
    case gl::RED: return {1, {0}, false};
    case gl::GREEN: return {1, {1}, false};
    case gl::BLUE: return {1, {2}, false};
    case gl::ALPHA: return {1, {3}, false};
    case gl::LUMINANCE: return {1, {0}, true};
    case gl::LUMINANCE_ALPHA: return {2, {0, 3}, true};
    case gl::RGB: return {3, {0, 1, 2}, false};
    case gl::BGR: return {3, {2, 1, 0}, false};
    case gl::RGBA: return {4, {0, 1, 2, 3}, false};
    case gl::BGRA: return {4, {2, 1, 0, 3}, false};
    default: return {};
  }
}

void write_bytes(unsigned char* p, const unsigned char* v, int size, bool swap) {
  for (int i = 0; i < size; ++i) p[swap ? size - 1 - i : i] = v[i];
}

void write_element(unsigned char* p, GLenum type, bool swap, double f01) {
  unsigned char b[4];
  switch (type) {
    case gl::UNSIGNED_BYTE: p[0] = static_cast<unsigned char>(pack_unsigned(f01, 8)); break;
    case gl::BYTE: p[0] = static_cast<unsigned char>(static_cast<std::int8_t>(pack_signed(f01, 8))); break;
    case gl::UNSIGNED_SHORT: { auto v = static_cast<std::uint16_t>(pack_unsigned(f01, 16)); std::memcpy(b, &v, 2); write_bytes(p, b, 2, swap); break; }
    case gl::SHORT: { auto v = static_cast<std::int16_t>(pack_signed(f01, 16)); std::memcpy(b, &v, 2); write_bytes(p, b, 2, swap); break; }
    case gl::UNSIGNED_INT: { std::uint32_t v = pack_unsigned(f01, 32); std::memcpy(b, &v, 4); write_bytes(p, b, 4, swap); break; }
    case gl::INT: { std::int32_t v = pack_signed(f01, 32); std::memcpy(b, &v, 4); write_bytes(p, b, 4, swap); break; }
    case gl::FLOAT: { float v = static_cast<float>(clamp01(f01)); std::memcpy(b, &v, 4); write_bytes(p, b, 4, swap); break; }
    default: break;
  }
}

void write_integer(unsigned char* p, GLenum type, bool swap, std::uint32_t v) {
  unsigned char b[4];
  switch (type) {
    case gl::UNSIGNED_BYTE:
    case gl::BYTE: p[0] = static_cast<unsigned char>(v); break;
    case gl::UNSIGNED_SHORT:
    case gl::SHORT: { auto s = static_cast<std::uint16_t>(v); std::memcpy(b, &s, 2); write_bytes(p, b, 2, swap); break; }
    case gl::UNSIGNED_INT:
    case gl::INT: { std::memcpy(b, &v, 4); write_bytes(p, b, 4, swap); break; }
    case gl::FLOAT: { float f = static_cast<float>(v); std::memcpy(b, &f, 4); write_bytes(p, b, 4, swap); break; }
    default: break;
  }
}

// For f in (0,1) exactly (f = mant * 2^-s0): floor(f*m + 1/2) when round_half,
// floor(f*m/2) otherwise, in 128-bit integers (m < 2^32, mant < 2^53).
std::uint64_t floor_scaled(double f, std::uint64_t m, bool round_half) {
  int e = 0;
  const double fr = std::frexp(f, &e);  // f = fr * 2^e, fr in [0.5, 1), e <= 0
  const auto mant = static_cast<std::uint64_t>(std::ldexp(fr, 53));
  const int s0 = 53 - e;
  if (s0 > 100) return 0;  // f*m < 2^(85-100): both results are 0
  const u128 p = static_cast<u128>(mant) * m;
  if (round_half) return static_cast<std::uint64_t>((2 * p + (static_cast<u128>(1) << s0)) >> (s0 + 1));
  return static_cast<std::uint64_t>(p >> (s0 + 1));
}

}  // namespace

int format_element_for(GLenum format, int rgba) {
  const FormatMap fm = format_map(format);
  for (int k = 0; k < fm.n; ++k)
    if (fm.slot[k] == rgba || (fm.luminance && k == 0 && rgba < 3)) return k;
  return -1;
}

std::uint32_t pack_unsigned(double f, int bits) {
  const std::uint64_t m = (std::uint64_t{1} << bits) - 1;
  if (!(f > 0.0)) return 0;  // clamp (and NaN -> 0)
  if (f >= 1.0) return static_cast<std::uint32_t>(m);
  return static_cast<std::uint32_t>(floor_scaled(f, m, true));
}

std::int32_t pack_signed(double f, int bits) {
  // Table 4.7: c = ((2^b - 1) f - 1) / 2, rounded half up: floor(c + 1/2) = floor((2^b - 1) f / 2).
  const std::uint64_t m = (std::uint64_t{1} << bits) - 1;
  if (!(f > 0.0)) return 0;  // f = 0: c = -1/2 rounds up to 0
  if (f >= 1.0) return static_cast<std::int32_t>((m - 1) / 2);
  return static_cast<std::int32_t>(floor_scaled(f, m, false));
}

template <class T>
RgbaImage<T> unpack_rgba(const void* data, int width, int height, GLenum format, GLenum type,
                         const PixelStoreModes& modes) {
  RgbaImage<T> img(width, height);
  const FormatMap fm = format_map(format);
  const int s = type_size(type);
  const ClientLayout L = client_layout(modes, width, height, fm.n, s);
  const auto* base = static_cast<const unsigned char*>(data);
  const bool swap = modes.swap_bytes && s > 1;
  if (s == 1) {
    // One-byte elements: each value a function of its byte alone (Table 2.6),
    // computed once for the 256 bytes and looked up.
    std::array<T, 256> real;
    for (int b = 0; b < 256; ++b) {
      const auto c = static_cast<unsigned char>(b);
      real[static_cast<std::size_t>(b)] = element_to_real<T>(read_element(&c, type, false), type);
    }
    // RGB and RGBA (each element to its own slot, alpha 1 where there is none):
    // the same values without the defaults written first.
    const bool rgb_order = !fm.luminance && fm.n >= 3 && fm.slot[0] == 0 && fm.slot[1] == 1 && fm.slot[2] == 2 &&
                           (fm.n == 3 || fm.slot[3] == 3);
    if (rgb_order) {
      for (int y = 0; y < height; ++y) {
        const unsigned char* g = base + L.offset(0, y);
        T* o = img.at(0, y);
        if (fm.n == 4) {
          for (int x = 0; x < width; ++x, g += 4, o += 4)
            for (int k = 0; k < 4; ++k) o[k] = real[g[k]];
        } else {
          for (int x = 0; x < width; ++x, g += 3, o += 4) {
            for (int k = 0; k < 3; ++k) o[k] = real[g[k]];
            o[3] = T(1);
          }
        }
      }
      return img;
    }
    for (int y = 0; y < height; ++y) {
      const unsigned char* g = base + L.offset(0, y);  // (group x at g + x·n)
      for (int x = 0; x < width; ++x, g += fm.n) {
        T* o = img.at(x, y);
        o[0] = o[1] = o[2] = T(0);
        o[3] = T(1);
        for (int k = 0; k < fm.n; ++k) {
          const T v = real[g[k]];
          if (fm.luminance && k == 0) o[0] = o[1] = o[2] = v;
          else o[fm.slot[k]] = v;
        }
      }
    }
    return img;
  }
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      T* o = img.at(x, y);
      o[0] = o[1] = o[2] = T(0);
      o[3] = T(1);
      const unsigned char* g = base + L.offset(x, y);
      for (int k = 0; k < fm.n; ++k) {
        const T v = element_to_real<T>(read_element(g + k * s, type, swap), type);
        if (fm.luminance && k == 0) o[0] = o[1] = o[2] = v;
        else o[fm.slot[k]] = v;
      }
    }
  return img;
}

std::vector<std::int64_t> unpack_indices(const void* data, int width, int height, GLenum type,
                                         const PixelStoreModes& modes) {
  std::vector<std::int64_t> out(static_cast<std::size_t>(width) * height);
  const int s = type_size(type);
  const ClientLayout L = client_layout(modes, width, height, 1, s);
  const auto* base = static_cast<const unsigned char*>(data);
  const bool swap = modes.swap_bytes && s > 1;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Element e = read_element(base + L.offset(x, y), type, swap);
      std::int64_t v = e.i;
      if (e.is_float) {
        const double r = std::floor(static_cast<double>(e.f) + 0.5);
        v = std::isnan(r) || r < 0 ? 0 : (r > 4294967295.0 ? 4294967295LL : static_cast<std::int64_t>(r));
      }
      out[static_cast<std::size_t>(y) * width + x] = v;
    }
  return out;
}

template <class T>
std::vector<T> unpack_depth(const void* data, int width, int height, GLenum type, const PixelStoreModes& modes) {
  std::vector<T> out(static_cast<std::size_t>(width) * height);
  const int s = type_size(type);
  const ClientLayout L = client_layout(modes, width, height, 1, s);
  const auto* base = static_cast<const unsigned char*>(data);
  const bool swap = modes.swap_bytes && s > 1;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      out[static_cast<std::size_t>(y) * width + x] =
          element_to_real<T>(read_element(base + L.offset(x, y), type, swap), type);
  return out;
}

template <class T>
void pack_rgba(const RgbaImage<T>& img, GLenum format, GLenum type, const PixelStoreModes& modes, void* data) {
  const FormatMap fm = format_map(format);
  const int s = type_size(type);
  const ClientLayout L = client_layout(modes, img.width, img.height, fm.n, s);
  auto* base = static_cast<unsigned char*>(data);
  const bool swap = modes.swap_bytes && s > 1;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const T* c = img.at(x, y);
      unsigned char* g = base + L.offset(x, y);
      for (int k = 0; k < fm.n; ++k) {
        // §4.3.2 "Conversion to L": L = R + G + B, evaluated in T before the clamp.
        const T v = fm.luminance && k == 0 ? (c[0] + c[1]) + c[2] : c[fm.slot[k]];
        write_element(g + k * s, type, swap, static_cast<double>(clamp01(v)));
      }
    }
}

void pack_indices(const std::vector<std::uint32_t>& v, int width, int height, GLenum type,
                  const PixelStoreModes& modes, void* data) {
  const int s = type_size(type);
  const ClientLayout L = client_layout(modes, width, height, 1, s);
  auto* base = static_cast<unsigned char*>(data);
  const bool swap = modes.swap_bytes && s > 1;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      write_integer(base + L.offset(x, y), type, swap, v[static_cast<std::size_t>(y) * width + x]);
}

void pack_depth(const std::vector<double>& v, int width, int height, GLenum type, const PixelStoreModes& modes,
                void* data) {
  const int s = type_size(type);
  const ClientLayout L = client_layout(modes, width, height, 1, s);
  auto* base = static_cast<unsigned char*>(data);
  const bool swap = modes.swap_bytes && s > 1;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      write_element(base + L.offset(x, y), type, swap, v[static_cast<std::size_t>(y) * width + x]);
}

template RgbaImage<float> unpack_rgba<float>(const void*, int, int, GLenum, GLenum, const PixelStoreModes&);
template RgbaImage<double> unpack_rgba<double>(const void*, int, int, GLenum, GLenum, const PixelStoreModes&);
template std::vector<float> unpack_depth<float>(const void*, int, int, GLenum, const PixelStoreModes&);
template std::vector<double> unpack_depth<double>(const void*, int, int, GLenum, const PixelStoreModes&);
template void pack_rgba<float>(const RgbaImage<float>&, GLenum, GLenum, const PixelStoreModes&, void*);
template void pack_rgba<double>(const RgbaImage<double>&, GLenum, GLenum, const PixelStoreModes&, void*);

}  // namespace ffsim::pixel

// unpack_rgba's one-byte RGB and RGBA loop (pipeline/pixel_transfer/unpack.cpp,
// docs/performance.md 25.2) writes each element to its own slot and alpha 1
// where there is none, without writing the defaults first. Checked against the
// one-element path: every texel of random RGB / RGBA images of both one-byte
// types, under random unpack modes, must hold the value that unpacking its
// byte alone as GL_RED / GL_GREEN / GL_BLUE / GL_ALPHA gives (and 0 / 1 where
// the format has no element: GL121 §3.6.4, Table 3.6 and the conversion to RGBA).
#include <doctest/doctest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "pipeline/pixel_transfer/unpack.h"

using namespace ffsim;
using namespace ffsim::pixel;

namespace {

template <class T>
void check_format(GLenum format, GLenum type, std::mt19937& g) {
  const int n = format == gl::RGBA ? 4 : 3;
  const GLenum one[4] = {gl::RED, gl::GREEN, gl::BLUE, gl::ALPHA};
  auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(g); };
  PixelStoreModes m;
  m.alignment = 1 << pick(0, 3);
  m.skip_pixels = pick(0, 3);
  m.skip_rows = pick(0, 2);
  const int w = pick(1, 19), h = pick(1, 6);
  m.row_length = pick(0, 1) ? 0 : w + m.skip_pixels + pick(0, 3);
  const int row_groups = m.row_length > 0 ? m.row_length : w;
  const int row_bytes = (row_groups * n + m.alignment - 1) / m.alignment * m.alignment;
  // (with ROW_LENGTH 0 a row holds `w` groups: the skipped pixels of the last row lie past it)
  std::vector<unsigned char> data(static_cast<std::size_t>(row_bytes) * (h + m.skip_rows) +
                                  static_cast<std::size_t>(n) * m.skip_pixels);
  for (unsigned char& b : data) b = static_cast<unsigned char>(pick(0, 255));
  const RgbaImage<T> img = unpack_rgba<T>(data.data(), w, h, format, type, m);
  REQUIRE(img.width == w);
  REQUIRE(img.height == h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 4; ++c) {
        T want = c == 3 ? T(1) : T(0);
        if (c < n) {
          const unsigned char* b = data.data() + static_cast<std::size_t>(row_bytes) * (y + m.skip_rows) +
                                   static_cast<std::size_t>(n) * (x + m.skip_pixels) + c;
          want = unpack_rgba<T>(b, 1, 1, one[c], type, {}).at(0, 0)[c];
        }
        INFO("format ", format, " type ", type, " x ", x, " y ", y, " c ", c);
        REQUIRE(img.at(x, y)[c] == want);
      }
}

}  // namespace

TEST_CASE("unpack_rgba: one-byte RGB and RGBA == element by element, under random unpack modes") {
  std::mt19937 g(2026);
  for (int k = 0; k < 200; ++k) {
    for (GLenum type : {gl::UNSIGNED_BYTE, gl::BYTE}) {
      check_format<float>(gl::RGB, type, g);
      check_format<float>(gl::RGBA, type, g);
      check_format<double>(gl::RGBA, type, g);
      check_format<double>(gl::RGB, type, g);
    }
  }
}

// Texture uploads in row bands on the pool (Context::upload_in_bands,
// docs/performance.md 24.2): a context on one thread and contexts on two and
// three take the same random pixel-transfer states and glTexImage2D /
// glTexSubImage2D / glTexImage1D calls of client data; every level must be
// equal bit for bit. The states are the ones the banded path takes (colour
// matrix, colour tables, scale/bias, colour maps: per pixel) and sometimes a
// convolution (which it must refuse); the unpack modes move the rows (skip
// rows and pixels, row length, alignment, byte swapping); sizes reach past
// kSplitUploadTexels with odd row counts and borders. The split must happen.
#include <doctest/doctest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "fast_scene.h"

using namespace ffsim;
using namespace ffsim::test;

namespace {

void set_unpack(Context& c, int alignment, int skip_rows, int skip_pixels, int row_length, bool swap) {
  c.pixelStorei(gl::UNPACK_ALIGNMENT, alignment);
  c.pixelStorei(gl::UNPACK_SKIP_ROWS, skip_rows);
  c.pixelStorei(gl::UNPACK_SKIP_PIXELS, skip_pixels);
  c.pixelStorei(gl::UNPACK_ROW_LENGTH, row_length);
  c.pixelStorei(gl::UNPACK_SWAP_BYTES, swap ? 1 : 0);
}

void random_transfer_state(Context& c, SceneRng& r) {
  set_unpack(c, 4, 0, 0, 0, false);  // the tables and filters below read their arrays with the unpack modes too
  double m[16];
  for (double& x : m) x = r.d(-0.6, 0.9);
  c.matrixMode(gl::COLOR);
  if (r.b(70)) c.loadMatrix(m);
  else c.loadIdentity();
  c.matrixMode(gl::MODELVIEW);
  c.pixelTransferf(gl::RED_SCALE, r.b(30) ? r.d(0.5, 1.5) : 1.0);
  c.pixelTransferf(gl::ALPHA_BIAS, r.b(30) ? r.d(-0.2, 0.2) : 0.0);
  c.pixelTransferf(gl::POST_COLOR_MATRIX_GREEN_BIAS, r.b(30) ? r.d(-0.3, 0.3) : 0.0);
  std::vector<float> table(4 * 32);
  for (float& x : table) x = static_cast<float>(r.d(0, 1));
  c.colorTable(gl::POST_COLOR_MATRIX_COLOR_TABLE, r.b(50) ? gl::RGBA : gl::ALPHA, 32, gl::RGBA, gl::FLOAT,
               table.data());
  if (r.b(60)) c.enable(gl::POST_COLOR_MATRIX_COLOR_TABLE);
  else c.disable(gl::POST_COLOR_MATRIX_COLOR_TABLE);
  c.colorTable(gl::COLOR_TABLE, gl::RGB, 16, gl::RGBA, gl::FLOAT, table.data());
  if (r.b(25)) c.enable(gl::COLOR_TABLE);
  else c.disable(gl::COLOR_TABLE);
  std::vector<double> map(8);
  for (double& x : map) x = r.d(0, 1);
  c.pixelMapfv(gl::PIXEL_MAP_B_TO_B, 8, map.data());
  c.pixelTransferf(gl::MAP_COLOR, r.b(20) ? 1.0 : 0.0);
  // A 3 x 3 convolution now and then: the banded path must leave it to the
  // whole-image path (its pixels read their neighbours).
  std::vector<float> taps(4 * 9);
  for (float& x : taps) x = static_cast<float>(r.d(0, 0.2));
  c.convolutionFilter2D(gl::CONVOLUTION_2D, gl::RGBA, 3, 3, gl::RGBA, gl::FLOAT, taps.data());
  c.convolutionParameteri(gl::CONVOLUTION_2D, gl::CONVOLUTION_BORDER_MODE, gl::REPLICATE_BORDER);
  if (r.b(15)) c.enable(gl::CONVOLUTION_2D);
  else c.disable(gl::CONVOLUTION_2D);
  const int alignment = 1 << r.i(0, 3), skip_rows = r.b(40) ? r.i(1, 5) : 0, skip_pixels = r.b(40) ? r.i(1, 3) : 0;
  const int row_length = r.b(30) ? 140 : 0;
  set_unpack(c, alignment, skip_rows, skip_pixels, row_length, r.b(30));
}

void check_same_levels(Context& a, Context& b, GLenum target) {
  const TextureObject& ta = a.bound_texture(0, target);
  const TextureObject& tb = b.bound_texture(0, target);
  REQUIRE(ta.levels.size() == tb.levels.size());
  CHECK(ta.version == tb.version);
  for (std::size_t l = 0; l < ta.levels.size(); ++l) {
    CAPTURE(l);
    CHECK(ta.levels[l].width == tb.levels[l].width);
    CHECK(ta.levels[l].height == tb.levels[l].height);
    CHECK(ta.levels[l].codes == tb.levels[l].codes);
    CHECK(ta.levels[l].values == tb.levels[l].values);
  }
}

}  // namespace

TEST_CASE("upload bands: uploads split over 2 and 3 threads equal one thread's, in every profile") {
  std::uint64_t split = 0;
  for (const char* name : {"geforce256", "rgba12", "float32", "ideal"}) {
    for (std::uint32_t seed = 1; seed <= 6; ++seed) {
      const std::string profile_name = name;
      CAPTURE(profile_name);
      CAPTURE(seed);
      Context one(profile_named(name), 4, 4), two(profile_named(name), 4, 4), three(profile_named(name), 4, 4);
      two.set_threads(2);
      three.set_threads(3);
      Context* all[] = {&one, &two, &three};
      SceneRng r(seed * 7919u);
      // Client bytes for the largest call: 140-pixel rows (ROW_LENGTH), 4
      // components, 4-byte elements, 136 rows with the skips.
      std::vector<std::uint8_t> client(140 * 4 * 4 * 136 + 64);
      for (auto& b : client) b = static_cast<std::uint8_t>(r.i(0, 255));
      // FLOAT client data must be finite: every fourth byte's top bits cleared
      // keeps each 4-byte element a modest number, whatever the byte order.
      std::vector<std::uint8_t> floats(client);
      for (std::size_t i = 0; i < floats.size(); i += 4) floats[i + 3] = floats[i] = 0x3e;
      for (int step = 0; step < 10; ++step) {
        CAPTURE(step);
        const std::uint32_t state_seed = static_cast<std::uint32_t>(r.i(0, 1 << 30));
        for (Context* c : all) {
          SceneRng s(state_seed);
          random_transfer_state(*c, s);
        }
        static const GLenum kFormats[] = {gl::RGBA, gl::RGB, gl::LUMINANCE_ALPHA, gl::BGRA, gl::ALPHA};
        static const GLenum kTypes[] = {gl::UNSIGNED_BYTE, gl::BYTE, gl::UNSIGNED_SHORT, gl::SHORT, gl::FLOAT};
        static const GLenum kInternal[] = {gl::RGBA8, gl::ALPHA8, gl::RGB8, gl::LUMINANCE8_ALPHA8, gl::RGBA4,
                                           gl::INTENSITY};
        const GLenum format = r.pick(kFormats), type = r.pick(kTypes), internal = r.pick(kInternal);
        const std::uint8_t* data = type == gl::FLOAT ? floats.data() : client.data();
        const int border = r.b(25) ? 1 : 0;
        const int side = 1 << r.i(5, 7);  // 32 .. 128: 1024 .. 16384 texels
        const int what = r.i(0, 3);
        CAPTURE(what);
        CAPTURE(side);
        CAPTURE(border);
        CAPTURE(format);
        CAPTURE(type);
        CAPTURE(internal);
        for (Context* c : all) {
          if (what == 3) {
            c->texImage1D(gl::TEXTURE_1D, 0, internal, side + 2 * border, border, format, type, data);
          } else {
            c->texImage2D(gl::TEXTURE_2D, 0, internal, side + 2 * border, side + 2 * border, border, format, type,
                          data);
            if (what == 2) {  // a sub-image of odd height over it, offset into the border
              c->texSubImage2D(gl::TEXTURE_2D, 0, -border, 3, side / 2 + 1, side / 2 + 7, format, type, data);
            }
          }
          CHECK(c->getError() == gl::NO_ERROR);
        }
        const GLenum target = what == 3 ? gl::TEXTURE_1D : gl::TEXTURE_2D;
        check_same_levels(one, two, target);
        check_same_levels(one, three, target);
      }
      CHECK(one.split_uploads() == 0);
      CHECK(two.split_uploads() == three.split_uploads());
      split += two.split_uploads();
    }
  }
  CHECK(split > 20);
}

TEST_CASE("upload bands: a convolution, a small image or one thread keeps the whole-image path") {
  std::vector<std::uint8_t> client(4 * 128 * 128, 77);
  Context c(profile_named("geforce256"), 4, 4);
  c.set_threads(2);
  double m[16] = {0, 0, 0, 0.5, 0, 0, 0, 0.5, 0, 0, 0, 0.5, 0, 0, 0, 0.5};  // not per component: no byte table
  c.matrixMode(gl::COLOR);
  c.loadMatrix(m);
  c.matrixMode(gl::MODELVIEW);
  c.texImage2D(gl::TEXTURE_2D, 0, gl::ALPHA8, 64, 64, 0, gl::RGBA, gl::UNSIGNED_BYTE, client.data());
  CHECK(c.split_uploads() == 1);  // 4096 texels: split
  c.texImage2D(gl::TEXTURE_2D, 0, gl::ALPHA8, 64, 32, 0, gl::RGBA, gl::UNSIGNED_BYTE, client.data());
  CHECK(c.split_uploads() == 1);  // 2048: below kSplitUploadTexels
  std::vector<float> taps(4 * 9, 0.1f);
  c.convolutionFilter2D(gl::CONVOLUTION_2D, gl::RGBA, 3, 3, gl::RGBA, gl::FLOAT, taps.data());
  c.enable(gl::CONVOLUTION_2D);
  c.texImage2D(gl::TEXTURE_2D, 0, gl::ALPHA8, 66, 66, 0, gl::RGBA, gl::UNSIGNED_BYTE, client.data());
  CHECK(c.getError() == gl::NO_ERROR);
  CHECK(c.split_uploads() == 1);  // the convolution reads neighbours: whole image
  c.disable(gl::CONVOLUTION_2D);
  c.set_threads(1);
  c.texImage2D(gl::TEXTURE_2D, 0, gl::ALPHA8, 64, 64, 0, gl::RGBA, gl::UNSIGNED_BYTE, client.data());
  CHECK(c.split_uploads() == 1);
}

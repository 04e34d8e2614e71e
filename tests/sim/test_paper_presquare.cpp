// Pre-squaring (the paper's section 5): squaring in the register combiners AFTER
// bilinear filtering makes a dip wherever a component changes sign between
// neighbouring texels; squaring BEFORE (pre-squared maps) does not. The 1D example
// of section 5 with its exact codes, a 2D texture whose difference image is
// non-zero only next to sign changes, and the two paper traces on a magnified polygon.
#include <doctest/doctest.h>

#include <filesystem>
#include <sstream>
#include <unistd.h>

#include "sim/image_io.h"
#include "sim/trace/executor.h"
#include "sim/trace/trace.h"

using namespace ffsim;
using namespace ffsim::trace;
namespace fs = std::filesystem;

namespace {

// One quad with texture unit 0 on the combiners. `squared_in_combiner`: the final
// colour is (EXPAND_NORMAL(tex))^2 computed in general combiner 0 (A*B with A = B);
// otherwise the texture already holds the square and passes through unchanged.
std::string combiner_trace(bool squared_in_combiner, int fb_w, int fb_h, double s0, double s1, double t0, double t1) {
  std::ostringstream o;
  o << "ffsim-trace 1\nframebuffer " << fb_w << " " << fb_h << "\n"
    << "image tex tex.png\n"
       "glPixelStorei GL_UNPACK_ALIGNMENT 1\n"
       "glBindTexture GL_TEXTURE_2D 1\n"
       "glTexParameteri GL_TEXTURE_2D GL_TEXTURE_MIN_FILTER GL_LINEAR\n"
       "glTexParameteri GL_TEXTURE_2D GL_TEXTURE_MAG_FILTER GL_LINEAR\n"
       "glTexParameteri GL_TEXTURE_2D GL_TEXTURE_WRAP_S GL_CLAMP_TO_EDGE\n"
       "glTexParameteri GL_TEXTURE_2D GL_TEXTURE_WRAP_T GL_CLAMP_TO_EDGE\n"
       "glTexImage2D GL_TEXTURE_2D 0 GL_RGB8 TW TH 0 GL_RGB GL_UNSIGNED_BYTE tex\n"
       "glEnable GL_TEXTURE_2D\n"
       "glEnable GL_REGISTER_COMBINERS_NV\n"
       "glCombinerParameteriNV GL_NUM_GENERAL_COMBINERS_NV 1\n";
  if (squared_in_combiner)
    o << "glCombinerInputNV GL_COMBINER0_NV GL_RGB GL_VARIABLE_A_NV GL_TEXTURE0_ARB GL_EXPAND_NORMAL_NV GL_RGB\n"
         "glCombinerInputNV GL_COMBINER0_NV GL_RGB GL_VARIABLE_B_NV GL_TEXTURE0_ARB GL_EXPAND_NORMAL_NV GL_RGB\n";
  else
    o << "glCombinerInputNV GL_COMBINER0_NV GL_RGB GL_VARIABLE_A_NV GL_TEXTURE0_ARB GL_UNSIGNED_IDENTITY_NV GL_RGB\n"
         "glCombinerInputNV GL_COMBINER0_NV GL_RGB GL_VARIABLE_B_NV GL_ZERO GL_UNSIGNED_INVERT_NV GL_RGB\n";
  o << "glCombinerInputNV GL_COMBINER0_NV GL_RGB GL_VARIABLE_C_NV GL_ZERO GL_UNSIGNED_IDENTITY_NV GL_RGB\n"
       "glCombinerInputNV GL_COMBINER0_NV GL_RGB GL_VARIABLE_D_NV GL_ZERO GL_UNSIGNED_IDENTITY_NV GL_RGB\n"
       "glCombinerOutputNV GL_COMBINER0_NV GL_RGB GL_SPARE0_NV GL_DISCARD_NV GL_DISCARD_NV GL_NONE GL_NONE GL_FALSE GL_FALSE GL_FALSE\n"
       "glFinalCombinerInputNV GL_VARIABLE_A_NV GL_ZERO GL_UNSIGNED_IDENTITY_NV GL_RGB\n"
       "glFinalCombinerInputNV GL_VARIABLE_B_NV GL_ZERO GL_UNSIGNED_IDENTITY_NV GL_RGB\n"
       "glFinalCombinerInputNV GL_VARIABLE_C_NV GL_ZERO GL_UNSIGNED_IDENTITY_NV GL_RGB\n"
       "glFinalCombinerInputNV GL_VARIABLE_D_NV GL_SPARE0_NV GL_UNSIGNED_IDENTITY_NV GL_RGB\n"
       "glMatrixMode GL_PROJECTION\nglOrtho 0 1 0 1 -1 1\nglMatrixMode GL_MODELVIEW\n"
    << "glBegin GL_QUADS\n"
    << "glMultiTexCoord2d GL_TEXTURE0 " << s0 << " " << t0 << "\nglVertex3d 0 0 0\n"
    << "glMultiTexCoord2d GL_TEXTURE0 " << s1 << " " << t0 << "\nglVertex3d 1 0 0\n"
    << "glMultiTexCoord2d GL_TEXTURE0 " << s1 << " " << t1 << "\nglVertex3d 1 1 0\n"
    << "glMultiTexCoord2d GL_TEXTURE0 " << s0 << " " << t1 << "\nglVertex3d 0 1 0\n"
    << "glEnd\n";
  return o.str();
}

// Runs a trace that reads `tex` (written as tex.png next to it); returns the colour buffer.
Image run_with_texture(const std::string& name, std::string text, const Image& tex) {
  const fs::path dir = fs::temp_directory_path() / (std::string("ffsim-test-presquare-") + std::to_string(::getpid()));
  fs::create_directories(dir);
  write_image((dir / "tex.png").string(), tex);
  auto put = [&](const std::string& key, int v) {
    for (std::size_t at; (at = text.find(key)) != std::string::npos;) text.replace(at, key.size(), std::to_string(v));
  };
  put("TW", tex.width);
  put("TH", tex.height);
  const Program p = load_trace_text(text, (dir / (name + ".trace")).string(), {});
  RunOptions ro;
  ro.keep_images = true;
  std::ostringstream out;
  const RunResult r = run_program(p, ro, out);
  std::error_code ec;
  fs::remove_all(dir, ec);  // (the trace has read tex.png; nothing else is kept)
  REQUIRE(r.ok);
  CHECK(r.gl_errors.empty());
  return r.images.at("final-color");
}

Image rgb(int w, int h, const std::vector<std::uint8_t>& codes) {  // one code per texel, copied to R, G, B
  Image im = Image::make(w, h, 3, SampleType::U8);
  for (int i = 0; i < w * h; ++i)
    for (int c = 0; c < 3; ++c) im.u8[3 * i + c] = codes[i];
  return im;
}

// Round half up of a non-negative rational n / d.
int round_half_up(long long n, long long d) { return static_cast<int>((2 * n + d) / (2 * d)); }

}  // namespace

TEST_CASE("paper pre-squaring: the 1D example of section 5 gives 1, 0, 1 unsquared and 1, 1, 1 pre-squared") {
  // "texel 1 contains the value -1 and texel 2 contains the value 1 ... the polygon is
  // exactly twice as big as the texture map": three pixels sampling texel 1's centre,
  // the midpoint and texel 2's centre (s = 1/4, 1/2, 3/4: pixel x maps to s = (x + 1/2)/4).
  // Signed values are stored biased: -1 -> code 0, +1 -> code 255.
  const Image un = run_with_texture("un", combiner_trace(true, 3, 1, 0.125, 0.875, 0.5, 0.5), rgb(2, 1, {0, 255}));
  const Image pre = run_with_texture("pre", combiner_trace(false, 3, 1, 0.125, 0.875, 0.5, 0.5), rgb(2, 1, {255, 255}));
  // Expected, derived: at the midpoint the bilinear weight is 128/256 and the filtered
  // code round_half_up((0 * 128 + 255 * 128) / 256) = 128; EXPAND_NORMAL gives
  // (2 * 128 - 255)/255 = 1/255, squared 1/65025, stored as round(255/65025) = 0.
  // At the texel centres the code is 0 or 255, expanded -1 or +1, squared 1 -> 255.
  const int mid_code = round_half_up(255 * 128, 256);
  CHECK(mid_code == 128);
  const int mid_square = round_half_up(static_cast<long long>(2 * mid_code - 255) * (2 * mid_code - 255), 255LL * 255);
  CHECK(mid_square == 0);
  const std::vector<int> expected_un = {255, mid_square, 255};
  for (int x = 0; x < 3; ++x) {
    CHECK(un.u8[un.index(x, 0, 0)] == expected_un[x]);
    CHECK(pre.u8[pre.index(x, 0, 0)] == 255);
  }
}

TEST_CASE("paper pre-squaring: in 2D the difference image is non-zero only next to sign changes") {
  // 4 x 4 texels of +-1 (codes 255 / 0) magnified 4x with bilinear filtering; the
  // pre-squared texture is all 1. A pixel's filtered value is +-1 exactly when every
  // texel with a non-zero bilinear weight has the same sign; then its square is 1 and
  // it equals the pre-squared result. Otherwise the value is strictly inside (-1, 1)
  // and squares to less than 1: the dip.
  const int n = 4, z = 4, w = n * z;
  std::vector<std::uint8_t> sign(n * n), ones(n * n, 255);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) sign[j * n + i] = (i * 3 + j * 5) % 7 < 3 ? 255 : 0;
  const Image un = run_with_texture("un2", combiner_trace(true, w, w, 0, 1, 0, 1), rgb(n, n, sign));
  const Image pre = run_with_texture("pre2", combiner_trace(false, w, w, 0, 1, 0, 1), rgb(n, n, ones));
  long long differ = 0, mixed = 0;
  for (int y = 0; y < w; ++y)
    for (int x = 0; x < w; ++x) {
      // Texel coordinate of the pixel centre: u = (x + 1/2)/z; bilinear footprint
      // floor(u - 1/2) and the next texel (clamped to the edge), weights from frac.
      auto footprint = [&](int p, int& a, int& b, bool& two) {
        const double u = (p + 0.5) / z - 0.5;
        const int i0 = static_cast<int>(std::floor(u));
        two = u != std::floor(u);
        a = std::clamp(i0, 0, n - 1);
        b = std::clamp(i0 + 1, 0, n - 1);
      };
      int x0, x1, y0, y1;
      bool tx, ty;
      footprint(x, x0, x1, tx);
      footprint(y, y0, y1, ty);
      std::vector<int> used = {sign[y0 * n + x0]};
      if (tx) used.push_back(sign[y0 * n + x1]);
      if (ty) used.push_back(sign[y1 * n + x0]);
      if (tx && ty) used.push_back(sign[y1 * n + x1]);
      bool mixed_here = false;
      for (int v : used) mixed_here = mixed_here || v != used.front();
      const int du = un.u8[un.index(x, y, 0)], dp = pre.u8[pre.index(x, y, 0)];
      CHECK(dp == 255);
      if (!mixed_here) CHECK_MESSAGE(du == dp, "pixel (" << x << ", " << y << ") is not next to a sign change");
      differ += du != dp;
      mixed += mixed_here;
    }
  MESSAGE(differ << " of " << w * w << " pixels differ; " << mixed << " see a sign change");
  CHECK(differ > 0);
  CHECK(differ <= mixed);
}

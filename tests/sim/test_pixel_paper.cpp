// The paper's imaging-subset check (Kautz, Heidrich, Daubert, MPI-I-2000-4-001,
// sections 4.1.3-4.1.4): the colour matrix M puts a dot product with the light
// into alpha and the post-colour-matrix alpha table squares it while a texture
// is loaded with glTexImage2D.
//
// Derivation (stated here because the test relies on it). The texture holds the
// biased texel T_b = (t + 1) / 2 per component (section 4.1.1), t in [-1,1]^3,
// and A = 1 (section 4.1.2). M is printed "in OpenGL notation, i.e. transposed":
// its 4th column (m3, m7, m11, m15 of the column-major array) produces alpha:
//   A' = (lx/2) R + (ly/2) G - (1/2) B + (-(lx + ly)/4 + 1/2) A
//      = (lx/2)(tx+1)/2 + (ly/2)(ty+1)/2 - (tz+1)/4 - (lx+ly)/4 + 1/2
//      = (lx tx + ly ty - tz)/4 + (lx + ly - 1 - lx - ly)/4 + 1/2
//      = (L.t)/4 + 1/4,          with L = (lx, ly, -1) (paper eq. 3.2).
// The table lookup(a) = (4a - 1)^2 / 2 then gives (4((L.t)/4 + 1/4) - 1)^2 / 2
// = (L.t)^2 / 2, the alpha the paper stores (section 4.1.4).
//
// Range: for L.t in [-1, 1], A' lies in [0, 1/2] and lookup in [0, 1/2]: no clamp
// acts. Outside, the spec's clamps decide (docs/numerics.md §7):
// - L.t < -1: A' < 0; the colour-table index clamps c to [0,1] first, so the
//   index is 0 and the result is entry 0 = lookup(0) = 1/2 whatever L.t is
//   (code 128 = rnd(127.5)).
// - L.t > 1: A' in (1/2, 1]; the index is fine, but table entries are clamped to
//   [0,1] when specified, so the result is min(1, (L.t)^2/2) (255 from L.t >= sqrt 2).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include "sim/context.h"

using namespace ffsim;

namespace {
struct Sweep {
  long long in_range = 0, below = 0, above = 0;
  double max_err_lsb = 0;  // in-range: |code - 255 (L.t)^2/2| (fixed) or |value - (L.t)^2/2| * 255 (float)
  double max_err_above_lsb = 0;
  long long rgb_nonzero = 0, below_wrong = 0, above_not_saturated = 0;
};

void setup_paper_state(Context& ctx, double lx, double ly) {
  const double m[16] = {0, 0, 0, lx / 2, 0, 0, 0, ly / 2, 0, 0, 0, -0.5, 0, 0, 0, -(lx + ly) / 4 + 0.5};
  ctx.matrixMode(gl::COLOR);
  ctx.loadMatrix(m);
  ctx.matrixMode(gl::MODELVIEW);
  std::vector<float> table(4096);
  for (int i = 0; i < 4096; ++i) {
    const double a = i / 4095.0;
    table[i] = static_cast<float>((4 * a - 1) * (4 * a - 1) / 2);  // > 1 for a > (1 + sqrt 2)/4: clamped by the GL
  }
  ctx.colorTable(gl::POST_COLOR_MATRIX_COLOR_TABLE, gl::ALPHA, 4096, gl::ALPHA, gl::FLOAT, table.data());
  ctx.enable(gl::POST_COLOR_MATRIX_COLOR_TABLE);
}

// Loads 256x256 texels (R = x, G = y, B = b, A = 255) and checks every alpha.
void load_and_check(Context& ctx, double lx, double ly, int b, Sweep& s) {
  std::vector<std::uint8_t> tex(4 * 256 * 256);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) {
      std::uint8_t* p = &tex[4 * (256 * y + x)];
      p[0] = static_cast<std::uint8_t>(x);
      p[1] = static_cast<std::uint8_t>(y);
      p[2] = static_cast<std::uint8_t>(b);
      p[3] = 255;
    }
  ctx.texImage2D(gl::TEXTURE_2D, 0, gl::RGBA, 256, 256, 0, gl::RGBA, gl::UNSIGNED_BYTE, tex.data());
  REQUIRE(ctx.getError() == gl::NO_ERROR);
  const TextureImage& ti = ctx.bound_texture(0, gl::TEXTURE_2D).levels.at(0);
  const bool fixed = ctx.profile().is_fixed();
  const double tz = 2.0 * b / 255 - 1;
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) {
      const double tx = 2.0 * x / 255 - 1, ty = 2.0 * y / 255 - 1;
      const double d = lx * tx + ly * ty - tz;  // L.t in binary64
      const std::size_t i = 4 * (256 * static_cast<std::size_t>(y) + x) + 3;
      const double got = fixed ? ti.codes[i] : 255.0 * ti.values[i];  // in 8-bit LSB units
      // RGB: the first three rows of M are 0, so R' = G' = B' = 0.
      if (fixed) s.rgb_nonzero += ti.codes[i - 3] + ti.codes[i - 2] + ti.codes[i - 1] != 0;
      if (d < -1) {
        ++s.below;
        s.below_wrong += fixed ? ti.codes[i] != 128 : ti.values[i] != 0.5;
      } else if (d > 1) {
        ++s.above;
        const double want = 255.0 * std::min(1.0, d * d / 2);
        s.max_err_above_lsb = std::max(s.max_err_above_lsb, std::abs(got - want));
        if (d >= 1.5) s.above_not_saturated += got != 255.0;
      } else {
        ++s.in_range;
        s.max_err_lsb = std::max(s.max_err_lsb, std::abs(got - 255.0 * d * d / 2));
      }
    }
}
}  // namespace

TEST_CASE("pixel paper check 4.1.4: colour matrix and alpha table give (L.T)^2/2 within 1 LSB") {
  Context ctx(*find_builtin_profile("geforce256"), 8, 8);
  Sweep s;
  int lights = 0;
  // Light directions: unit vectors at elevation angles 90, 60, 30 and 5 degrees above
  // the tangent plane (sin of the polar angle = |(lx, ly)|), 8 azimuths each.
  for (double polar : {0.0, 30.0, 60.0, 85.0})
    for (int k = 0; k < (polar == 0.0 ? 1 : 8); ++k) {
      const double phi = k * std::numbers::pi / 4 + 0.3, r = std::sin(polar * std::numbers::pi / 180);
      const double lx = r * std::cos(phi), ly = r * std::sin(phi);
      setup_paper_state(ctx, lx, ly);
      for (int b = 0; b <= 255; b += 17) load_and_check(ctx, lx, ly, b, s);
      ++lights;
    }
  // One light with every texel of the 8-bit cube (all 2^24 R, G, B codes).
  setup_paper_state(ctx, 0.6, -0.45);
  for (int b = 0; b < 256; ++b) load_and_check(ctx, 0.6, -0.45, b, s);
  ++lights;
  MESSAGE("geforce256: ", lights, " lights, ", s.in_range, " in-range texels, max error ", s.max_err_lsb,
          " LSB; ", s.below, " texels with L.t < -1 (all 128), ", s.above, " with L.t > 1 (max error vs min(1,d^2/2) ",
          s.max_err_above_lsb, " LSB)");
  CHECK(s.in_range > 10000000);
  CHECK(s.below > 0);
  CHECK(s.above > 0);
  CHECK(s.max_err_lsb <= 1.0);
  CHECK(s.max_err_above_lsb <= 1.0);
  CHECK(s.rgb_nonzero == 0);  // rows 1-3 of M are 0: R' = G' = B' = 0
  CHECK(s.below_wrong == 0);
  CHECK(s.above_not_saturated == 0);
}

TEST_CASE("pixel paper check 4.1.4 under the ideal and float32 profiles: only the table spacing remains") {
  for (const char* name : {"ideal", "float32"}) {
    CAPTURE(name);
    Context ctx(*find_builtin_profile(name), 8, 8);
    Sweep s;
    for (int k = 0; k < 8; ++k) {
      const double phi = k * std::numbers::pi / 4 + 0.1;
      const double lx = 0.7 * std::cos(phi), ly = 0.7 * std::sin(phi);
      setup_paper_state(ctx, lx, ly);
      for (int b = 0; b <= 255; b += 51) load_and_check(ctx, lx, ly, b, s);
    }
    MESSAGE(std::string(name), ": ", s.in_range, " in-range texels, max error ", s.max_err_lsb, " LSB");
    // Index rounding moves a by at most 0.5/4095; |d lookup/da| = 4|4a - 1| <= 4 on [0, 1/2]
    // (entries are binary32 under ideal too, 2^-25 relative): bound 255 * 2/4095 = 0.1246 LSB.
    // float32 adds the binary32 rounding of the stored value (2^-24 relative of a value
    // <= 1/2: < 1e-5 LSB) and of the transfer arithmetic (same order): + 1e-5 LSB.
    CHECK(s.max_err_lsb <= 255.0 * 2 / 4095 + 1e-5);
    CHECK(s.below_wrong == 0);
    CHECK(s.above_not_saturated == 0);
  }
}

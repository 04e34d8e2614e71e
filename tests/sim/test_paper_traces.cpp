// The paper's traces (traces/kautz-*.trace, issue 8) replayed at small sizes:
// the clamping they rely on, the agreement of the hard-shadow mask with the float64
// shadow test, the out-of-range texels of the imaging path.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "bumpshadow/encodings.h"
#include "bumpshadow/ellipse_test.h"
#include "bumpshadow/generators.h"
#include "bumpshadow/shadow_map.h"
#include "sim/trace/executor.h"
#include "sim/trace/trace.h"

using namespace ffsim;
using namespace ffsim::trace;
namespace fs = std::filesystem;

namespace {
const fs::path kTraces = fs::path(FFSIM_SOURCE_DIR) / "traces";
constexpr int kRes = 32;
constexpr int kRays = 64;

using Sets = std::vector<std::pair<std::string, std::string>>;

RunResult run_paper(const std::string& trace, Sets sets) {
  LoadOptions lo;
  lo.sets = {{"res", std::to_string(kRes)}, {"rays", std::to_string(kRays)}};
  for (auto& s : sets) lo.sets.push_back(s);
  const Program p = load_trace_file((kTraces / trace).string(), lo);
  RunOptions ro;
  ro.keep_images = true;
  std::ostringstream out;
  RunResult r = run_program(p, ro, out);
  INFO(trace << ": " << r.fatal << (r.gl_errors.empty() ? "" : r.gl_errors.front()));
  REQUIRE(r.ok);
  CHECK(r.gl_errors.empty());
  return r;
}

const Image& image(const RunResult& r, const std::string& name) {
  auto it = r.images.find(name);
  REQUIRE_MESSAGE(it != r.images.end(), "no dump " << name);
  return it->second;
}

// The scene-0 field of traces/include/scene.trace at kRes, and its ellipse map.
const bumpshadow::EllipseMap& polygon_map() {
  static const bumpshadow::EllipseMap m = [] {
    const bumpshadow::HeightField hf = bumpshadow::generate("bumps", {{"w", std::to_string(kRes)}, {"seed", "1"}});
    bumpshadow::ShadowMapOptions o;
    o.rays = bumpshadow::rays_for_count(kRays);
    return bumpshadow::compute_ellipse_map(hf, o);
  }();
  return m;
}

bumpshadow::Vec3 decoded(const bumpshadow::ByteMap& m, int i) {
  return {bumpshadow::decode_biased(m.v[4 * i]), bumpshadow::decode_biased(m.v[4 * i + 1]), bumpshadow::decode_biased(m.v[4 * i + 2])};
}
double dot_l(const bumpshadow::Vec3& t, double lx, double ly) { return lx * t.x + ly * t.y - t.z; }

// 1/2 d of eq. 4.1 on the decoded 8-bit maps (what the imaging path computes,
// before its own roundings).
double half_d_codes(const bumpshadow::EncodedMaps& em, int i, double lx, double ly) {
  const double s1 = dot_l(decoded(em.t1r8, i), lx, ly), s2 = dot_l(decoded(em.t2r8, i), lx, ly);
  return em.t3r8.v[i] / 255.0 - 0.5 * s1 * s1 - 0.5 * s2 * s2;
}
}  // namespace

TEST_CASE("paper clamping: the subtract pass leaves exactly 0 where the shadow test is negative") {
  const double lx = 0.7, ly = 0.4;  // the traces' defaults
  const bumpshadow::EncodedMaps em = bumpshadow::encode_maps(polygon_map());
  const RunResult r = run_paper("kautz-imaging-hard.trace", {});
  const Image& a = image(r, "alpha.png");
  REQUIRE(a.width == kRes);
  // Margin: the lookup table's index rounds A' = (L.T)/4 + 1/4 to 1/255, an error of
  // up to 2/255 in L.T, i.e. |L.T| * 2/255 <= 4/255 in each square; plus half an
  // LSB for each of the three stored terms.
  const double margin = 10.0 / 255;
  long long negative = 0, positive = 0;
  for (int i = 0; i < kRes * kRes; ++i) {
    const double hd = half_d_codes(em, i, lx, ly);
    const int code = a.u8[i];
    if (hd < -margin) {
      ++negative;
      CHECK_MESSAGE(code == 0, "texel " << i << ": 1/2 d = " << hd);
    } else if (hd > margin) {
      ++positive;
      CHECK_MESSAGE(code > 0, "texel " << i << ": 1/2 d = " << hd);
    }
  }
  MESSAGE("clearly negative texels (alpha exactly 0): " << negative << ", clearly positive: " << positive);
  CHECK(negative > 50);
  CHECK(positive > 50);
  // Where alpha is exactly 0 the stencil holds 1 (shadow), elsewhere 0.
  const Image& st = image(r, "stencil.png");
  for (int i = 0; i < kRes * kRes; ++i) CHECK(st.u8[i] == (a.u8[i] == 0 ? 1 : 0));
}

TEST_CASE("paper clamping: the doubling passes saturate at 1") {
  const RunResult r = run_paper("kautz-imaging-aa.trace", {});
  const Image& a = image(r, "alpha.png");
  const Image& f = image(r, "factor.png");
  // Step 13: A + 1 * A = 2A, exact in codes (2k, clamped to 255); step 14 with source
  // alpha 1 again; the third pass has source alpha 0 (penumbra 2) and keeps A.
  long long saturated = 0;
  for (int i = 0; i < kRes * kRes; ++i) {
    const int k = a.u8[i];
    CHECK(f.u8[i] == std::min(255, 2 * std::min(255, 2 * k)));
    saturated += f.u8[i] == 255;
  }
  MESSAGE("pixels saturated at 1 after the doublings: " << saturated);
  CHECK(saturated > 0);
}

TEST_CASE("paper clamping: texels outside the imaging path's ranges give the clamped codes") {
  // Three texels (the third twice, for a power-of-two width) through the colour matrix M and the lookup table of section 4.1.3/4.1.4
  // (lx = 0.7, ly = 0.4), L = (lx, ly, -1):
  //   T = (-1, -1, 1): L.T = -2.1, A' = (L.T)/4 + 1/4 = -0.275 < 0: the table index
  //                   clamps to 0, lookup(0) = 1/2, code round(127.5) = 128 (not 1/2 (L.T)^2 = 2.205)
  //   T = (1, 1, -1):  L.T = 2.1, A' = 0.775, index round(197.625) = 198,
  //                   lookup = 1/2 (4*198/255 - 1)^2 = 2.22 > 1: the entry clamps to 1, code 255
  //   T = (1, 0, 0):   L.T = 0.7, A' = 0.425, index round(108.375) = 108,
  //                   lookup = 1/2 (432/255 - 1)^2 = 0.2409, code round(61.43) = 61
  const double lx = 0.7, ly = 0.4;
  auto expected = [&](double tx, double ty, double tz) {
    const double ap = (lx * tx + ly * ty - tz) / 4 + 0.25;
    const double idx = std::floor(std::min(1.0, std::max(0.0, ap)) * 255 + 0.5);
    const double entry = std::min(1.0, 0.5 * std::pow(4 * idx / 255 - 1, 2));
    return static_cast<int>(std::floor(entry * 255 + 0.5));
  };
  CHECK(expected(-1, -1, 1) == 128);
  CHECK(expected(1, 1, -1) == 255);
  CHECK(expected(1, 0, 0) == 61);
  const std::string text =
      "ffsim-trace 1\n"
      "framebuffer 4 1\n"
      "param lx 0.7\nparam ly 0.4\n"
      "table lookup 256 0.5*(4*x-1)^2\n"
      "glPixelStorei GL_UNPACK_ALIGNMENT 1\n"
      // biased (T + 1)/2 per texel i = 0, 1, 2, 3: (0, 0, 1), (1, 1, 0), (1, 1/2, 1/2) twice
      // (a power-of-two width; expressions have no comparisons, so min/max select)
      "table texels 4 min(i,1) (min(i,1)-0.5*min(max(i-1,0),1)) (1-min(i,1)+0.5*min(max(i-1,0),1)) 1\n"
      "glMatrixMode GL_COLOR\n"
      "glLoadMatrixd 0 0 0 (0.5*lx)   0 0 0 (0.5*ly)   0 0 0 -0.5   0 0 0 (-0.25*(lx+ly)+0.5)\n"
      "glMatrixMode GL_MODELVIEW\n"
      "glColorTable GL_POST_COLOR_MATRIX_COLOR_TABLE GL_ALPHA 256 GL_ALPHA GL_FLOAT lookup\n"
      "glEnable GL_POST_COLOR_MATRIX_COLOR_TABLE\n"
      "glBindTexture GL_TEXTURE_2D 1\n"
      "glTexParameteri GL_TEXTURE_2D GL_TEXTURE_MIN_FILTER GL_NEAREST\n"
      "glTexParameteri GL_TEXTURE_2D GL_TEXTURE_MAG_FILTER GL_NEAREST\n"
      "glTexImage2D GL_TEXTURE_2D 0 GL_ALPHA8 4 1 0 GL_RGBA GL_FLOAT texels\n"
      "glEnable GL_TEXTURE_2D\n"
      "glTexEnvi GL_TEXTURE_ENV GL_TEXTURE_ENV_MODE GL_REPLACE\n"
      "glMatrixMode GL_PROJECTION\nglOrtho 0 1 0 1 -1 1\nglMatrixMode GL_MODELVIEW\n"
      "glBegin GL_QUADS\n"
      "glMultiTexCoord2d GL_TEXTURE0 0 0\nglVertex3d 0 0 0\nglMultiTexCoord2d GL_TEXTURE0 1 0\nglVertex3d 1 0 0\n"
      "glMultiTexCoord2d GL_TEXTURE0 1 1\nglVertex3d 1 1 0\nglMultiTexCoord2d GL_TEXTURE0 0 1\nglVertex3d 0 1 0\n"
      "glEnd\n"
      "expect pixel 0 0 alpha 128/255\n"
      "expect pixel 1 0 alpha 255/255\n"
      "expect pixel 2 0 alpha 61/255\n"
      "expect pixel 3 0 alpha 61/255\n";
  const Program p = load_trace_text(text, "clamp.trace", {});
  std::ostringstream out;
  const RunResult r = run_program(p, {}, out);
  CHECK(r.ok);
  CHECK(r.gl_errors.empty());
  for (const auto& e : r.expect_failures) FAIL_CHECK(e);
}

TEST_CASE("paper agreement: the hard-shadow mask is the sign of the float64 test away from zero") {
  // Lights for which nothing clamps on the imaging path: -1 <= L.T <= sqrt 2 for both
  // maps (the colour matrix output and the table entry stay in [0, 1]), r_x^2 <= 2,
  // and the sum 1/2 (L.T1)^2 + 1/2 (L.T2)^2 <= 1 (step 8 does not saturate).
  const bumpshadow::EllipseMap& m = polygon_map();
  const bumpshadow::EncodedMaps em = bumpshadow::encode_maps(m);
  const std::vector<std::pair<double, double>> candidates = {{0.7, 0.4}, {0.3, 0.2}, {-0.4, 0.5}, {0.5, -0.6}, {0.1, 0.1}};
  // Tolerance: 3 LSBs of the alpha channel, which holds d/2: |d| <= 6/255.
  const double tol = 6.0 / 255;
  int lights = 0;
  for (const auto& [lx, ly] : candidates) {
    bool clamps = false;
    for (int i = 0; i < kRes * kRes && !clamps; ++i) {
      const double s1 = dot_l(decoded(em.t1r8, i), lx, ly), s2 = dot_l(decoded(em.t2r8, i), lx, ly);
      clamps = s1 < -1 || s2 < -1 || s1 > std::sqrt(2.0) || s2 > std::sqrt(2.0) || 0.5 * (s1 * s1 + s2 * s2) > 1 ||
               em.t3r8.v[i] == 255;
    }
    if (clamps) continue;
    ++lights;
    const RunResult r = run_paper("kautz-imaging-hard.trace", {{"lx", std::to_string(lx)}, {"ly", std::to_string(ly)}});
    const Image& st = image(r, "stencil.png");
    const std::vector<double> d = bumpshadow::ellipse_test_map(m, {lx, ly, std::sqrt(1 - lx * lx - ly * ly)});
    long long disagree = 0, near_zero = 0;
    for (int i = 0; i < kRes * kRes; ++i) {
      const bool lit_hw = st.u8[i] == 0, lit64 = d[i] > 0;
      if (std::fabs(d[i]) <= tol) {
        ++near_zero;
        disagree += lit_hw != lit64;
        continue;
      }
      CHECK_MESSAGE(lit_hw == lit64, "light (" << lx << ", " << ly << ") texel " << i << ": d = " << d[i]);
    }
    MESSAGE("light (" << lx << ", " << ly << "): " << disagree << " of " << near_zero << " texels within |d| <= 6/255 disagree; "
                      "none outside");
  }
  MESSAGE("clamp-free lights tested: " << lights);
  CHECK(lights >= 1);
}

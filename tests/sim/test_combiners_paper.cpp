// The GeForce 256 pass of Kautz, Heidrich, Daubert, "Bump Map Shadows for
// OpenGL Rendering" (MPI-I-2000-4-001), section 5, set up through the GL entry
// points and shaded with the combiner span function:
//
//   stage 0 RGB:   spare0.rgb = L1n . T1n, spare1.rgb = L2n . T2n (dot products of
//                  EXPAND_NORMAL'd constants and textures, biased as in 5.1.2)
//   stage 1 alpha: spare0.a = spare0.b * 1 + spare1.b * 1 (BLUE usage)
//   final:         rgb = 0, alpha = spare0.a
//
// Inputs: random ellipses (centre |C| <= 1, major axis a, radii rx <= ry) give
// T1r, T2r (paper 4.1) and T1n, T2n (5.1), with L2n = (ly, ly^2, 1) (erratum in
// ../shared/papers/README.md: the printed (ly^2, ly, 1) pairs the wrong terms).
// Texels are quantised to 8 bits after the bias (c + 1)/2; the constants are
// passed as GLfloat and rounded to 8-bit codes on entry (choice #36).
//
// Reported (and bounded): the largest difference in LSBs (1/255) of the alpha
// against (1) the exact real value of the spec arithmetic on the quantised
// inputs (pure combiner arithmetic error) and (2) the float64 value
// L1n.T1n + L2n.T2n of the unquantised inputs (total error), over the cases in
// which nothing clamps. Cases where a T^n component lies outside [-1, 1] (the
// biased texture clamps) or a dot product or the sum leaves [-1, 1] (register
// clamp) are counted and checked against the exact clamped model only.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "pipeline/combiners/register_combiners.h"
#include "pipeline/number/unorm.h"
#include "sim/context.h"

using namespace ffsim;
using namespace ffsim::combiners;

namespace {

struct Ellipse {
  double t1n[3], t2n[3];
};

Ellipse random_ellipse(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double pi = std::acos(-1.0);
  const double th = 2 * pi * u(rng), ax = std::cos(th), ay = std::sin(th);
  const double rc = std::sqrt(u(rng)), ph = 2 * pi * u(rng);  // centre uniform in the unit disk
  const double cx = rc * std::cos(ph), cy = rc * std::sin(ph);
  const double rho = 0.05 + 0.95 * u(rng);  // rx / ry in (0, 1]
  const double t1[3] = {ax, ay, ax * cx + ay * cy};                               // T1r (paper 4.1)
  const double t2[3] = {-ay * rho, ax * rho, (-ay * cx + ax * cy) * rho};         // T2r
  Ellipse e;
  e.t1n[0] = t1[0] * t1[0] + t2[0] * t2[0];                                        // T1n (paper 5.1)
  e.t1n[1] = 2 * t1[0] * t1[1] + 2 * t2[0] * t2[1];
  e.t1n[2] = -2 * t1[0] * t1[2] - 2 * t2[0] * t2[2];
  e.t2n[0] = -2 * t1[1] * t1[2] - 2 * t2[1] * t2[2];                               // T2n
  e.t2n[1] = t1[1] * t1[1] + t2[1] * t2[1];
  e.t2n[2] = t1[2] * t1[2] + t2[2] * t2[2];
  return e;
}

std::uint16_t biased_code(double c) { return static_cast<std::uint16_t>(unorm_from_double((c + 1) / 2, 8)); }

// Exact dot product of EXPAND_NORMAL'd 8-bit codes, in units of 1/255^2.
std::int64_t expanded_dot(const std::uint16_t* a, const std::uint16_t* b) {
  std::int64_t s = 0;
  for (int i = 0; i < 3; ++i) s += (2 * std::int64_t{a[i]} - 255) * (2 * std::int64_t{b[i]} - 255);
  return s;
}

void setup_paper_pass(Context& ctx, const float l1[4], const float l2[4]) {
  ctx.enable(gl::REGISTER_COMBINERS_NV);
  ctx.combinerParameteri(gl::NUM_GENERAL_COMBINERS_NV, 2);
  ctx.combinerParameterfv(gl::CONSTANT_COLOR0_NV, l1);
  ctx.combinerParameterfv(gl::CONSTANT_COLOR1_NV, l2);
  ctx.combinerInput(gl::COMBINER0_NV, gl::RGB, gl::VARIABLE_A_NV, gl::CONSTANT_COLOR0_NV, gl::EXPAND_NORMAL_NV, gl::RGB);
  ctx.combinerInput(gl::COMBINER0_NV, gl::RGB, gl::VARIABLE_B_NV, gl::TEXTURE0, gl::EXPAND_NORMAL_NV, gl::RGB);
  ctx.combinerInput(gl::COMBINER0_NV, gl::RGB, gl::VARIABLE_C_NV, gl::CONSTANT_COLOR1_NV, gl::EXPAND_NORMAL_NV, gl::RGB);
  ctx.combinerInput(gl::COMBINER0_NV, gl::RGB, gl::VARIABLE_D_NV, gl::TEXTURE1, gl::EXPAND_NORMAL_NV, gl::RGB);
  ctx.combinerOutput(gl::COMBINER0_NV, gl::RGB, gl::SPARE0_NV, gl::SPARE1_NV, gl::DISCARD_NV, gl::NONE, gl::NONE,
                     true, true, false);
  ctx.combinerInput(gl::COMBINER1_NV, gl::ALPHA, gl::VARIABLE_A_NV, gl::SPARE0_NV, gl::SIGNED_IDENTITY_NV, gl::BLUE);
  ctx.combinerInput(gl::COMBINER1_NV, gl::ALPHA, gl::VARIABLE_B_NV, gl::ZERO, gl::UNSIGNED_INVERT_NV, gl::ALPHA);
  ctx.combinerInput(gl::COMBINER1_NV, gl::ALPHA, gl::VARIABLE_C_NV, gl::SPARE1_NV, gl::SIGNED_IDENTITY_NV, gl::BLUE);
  ctx.combinerInput(gl::COMBINER1_NV, gl::ALPHA, gl::VARIABLE_D_NV, gl::ZERO, gl::UNSIGNED_INVERT_NV, gl::ALPHA);
  ctx.combinerOutput(gl::COMBINER1_NV, gl::ALPHA, gl::DISCARD_NV, gl::DISCARD_NV, gl::SPARE0_NV, gl::NONE, gl::NONE,
                     false, false, false);
  for (GLenum v : {gl::VARIABLE_A_NV, gl::VARIABLE_B_NV, gl::VARIABLE_C_NV, gl::VARIABLE_D_NV})
    ctx.finalCombinerInput(v, gl::ZERO, gl::UNSIGNED_IDENTITY_NV, gl::RGB);
  ctx.finalCombinerInput(gl::VARIABLE_G_NV, gl::SPARE0_NV, gl::UNSIGNED_IDENTITY_NV, gl::ALPHA);
}

}  // namespace

TEST_CASE("combiners paper section 5: spare0.a = L1n.T1n + L2n.T2n against exact and float64 values") {
  constexpr int kTexels = 4096, kAzimuths = 16, kElevations = 8;
  std::mt19937_64 rng(2000);
  std::vector<Ellipse> ell(kTexels);
  for (auto& e : ell) e = random_ellipse(rng);
  std::vector<std::uint16_t> tex0(4 * kTexels), tex1(4 * kTexels), primary(4 * kTexels, 0), out(4 * kTexels);
  std::vector<double> ftex0(4 * kTexels), ftex1(4 * kTexels), fprimary(4 * kTexels, 0), fout(4 * kTexels);
  int texture_clamped = 0;
  std::vector<bool> tclamp(kTexels);
  for (int i = 0; i < kTexels; ++i) {
    bool clamp = false;
    for (int c = 0; c < 3; ++c) {
      const std::size_t k = 4 * static_cast<std::size_t>(i) + static_cast<std::size_t>(c);
      tex0[k] = biased_code(ell[static_cast<std::size_t>(i)].t1n[c]);
      tex1[k] = biased_code(ell[static_cast<std::size_t>(i)].t2n[c]);
      ftex0[k] = std::clamp((ell[static_cast<std::size_t>(i)].t1n[c] + 1) / 2, 0.0, 1.0);
      ftex1[k] = std::clamp((ell[static_cast<std::size_t>(i)].t2n[c] + 1) / 2, 0.0, 1.0);
      clamp |= std::fabs(ell[static_cast<std::size_t>(i)].t1n[c]) > 1 || std::fabs(ell[static_cast<std::size_t>(i)].t2n[c]) > 1;
    }
    tex0[4 * static_cast<std::size_t>(i) + 3] = tex1[4 * static_cast<std::size_t>(i) + 3] = 255;
    ftex0[4 * static_cast<std::size_t>(i) + 3] = ftex1[4 * static_cast<std::size_t>(i) + 3] = 1;
    tclamp[static_cast<std::size_t>(i)] = clamp;
    texture_clamped += clamp;
  }

  Context hw(*find_builtin_profile("geforce256"), 4, 4);
  Context ideal(*find_builtin_profile("ideal"), 4, 4);
  long cases = 0, register_clamped = 0, both_clean = 0;
  double max_arith = 0, max_arith_clamped = 0, max_total = 0, max_ideal = 0;
  const double pi = std::acos(-1.0);
  for (int az = 0; az < kAzimuths; ++az)
    for (int el = 1; el <= kElevations; ++el) {
      const double psi = 2 * pi * az / kAzimuths, phi = (pi / 2) * el / (kElevations + 1);
      const double lx = std::sin(phi) * std::cos(psi), ly = std::sin(phi) * std::sin(psi);
      const double L1[3] = {lx * lx, lx * ly, lx}, L2[3] = {ly, ly * ly, 1};  // erratum pairing
      float l1[4], l2[4];
      for (int c = 0; c < 3; ++c) {
        l1[c] = static_cast<float>((L1[c] + 1) / 2);
        l2[c] = static_cast<float>((L2[c] + 1) / 2);
      }
      l1[3] = l2[3] = 1;
      setup_paper_pass(hw, l1, l2);
      setup_paper_pass(ideal, l1, l2);
      REQUIRE(hw.getError() == gl::NO_ERROR);
      REQUIRE(ideal.getError() == gl::NO_ERROR);
      const CombinerPlan& plan = hw.combiner_plan();
      CHECK(plan.texture_needed[0]);
      CHECK(plan.texture_needed[1]);
      CHECK_FALSE(plan.primary_needed);
      CombinerInputsFixed in;
      in.count = kTexels;
      in.primary = primary.data();
      in.texture[0] = tex0.data();
      in.texture[1] = tex1.data();
      shade_span(plan, in, {0, 0, 0, 0}, out.data());
      CombinerInputsFloat fin;
      fin.count = kTexels;
      fin.primary = fprimary.data();
      fin.texture[0] = ftex0.data();
      fin.texture[1] = ftex1.data();
      shade_span(ideal.combiner_plan(), fin, {0, 0, 0, 0}, fout.data());

      std::uint16_t k1[3], k2[3];
      for (int c = 0; c < 3; ++c) {
        k1[c] = static_cast<std::uint16_t>(unorm_from_double(l1[c], 8));
        k2[c] = static_cast<std::uint16_t>(unorm_from_double(l2[c], 8));
      }
      for (int i = 0; i < kTexels; ++i) {
        ++cases;
        const std::size_t q = 4 * static_cast<std::size_t>(i);
        const Ellipse& e = ell[static_cast<std::size_t>(i)];
        for (int c = 0; c < 3; ++c) CHECK(out[q + static_cast<std::size_t>(c)] == 0);  // rgb = 0
        // (1) exact spec arithmetic on the quantised inputs, units of 1/255^2.
        const std::int64_t d1 = expanded_dot(k1, &tex0[q]), d2 = expanded_dot(k2, &tex1[q]);
        const std::int64_t one = 255 * 255;
        const bool rclamp = std::llabs(d1) > one || std::llabs(d2) > one || std::llabs(d1 + d2) > one;
        register_clamped += rclamp;
        auto sat = [&](std::int64_t x) { return std::clamp(x, -one, one); };
        const std::int64_t exact = std::max<std::int64_t>(0, sat(sat(d1) + sat(d2)));  // final max(0, .)
        const double arith = std::fabs(out[q + 3] - static_cast<double>(exact) / 255.0);  // LSBs
        // (2) float64 value of the unquantised inputs.
        const double dot1 = L1[0] * e.t1n[0] + L1[1] * e.t1n[1] + L1[2] * e.t1n[2];
        const double dot2 = L2[0] * e.t2n[0] + L2[1] * e.t2n[1] + L2[2] * e.t2n[2];
        const double v = dot1 + dot2;  // = (L.T1r)^2 + (L.T2r)^2 >= 0 with L = (lx, ly, -1)
        // Clamp-free: no texture clamp, and neither the quantised nor the float64
        // dot products and sum leave [-1, 1].
        const bool fclamp = std::fabs(dot1) > 1 || std::fabs(dot2) > 1 || v > 1;
        register_clamped += !rclamp && fclamp;
        const bool clean = !rclamp && !fclamp && !tclamp[static_cast<std::size_t>(i)];
        if (clean) {
          ++both_clean;
          max_arith = std::max(max_arith, arith);
          max_total = std::max(max_total, std::fabs(out[q + 3] - 255.0 * v));
          max_ideal = std::max(max_ideal, std::fabs(fout[q + 3] - v) * 255.0);
        } else {
          max_arith_clamped = std::max(max_arith_clamped, arith);
        }
      }
    }
  char msg[512];
  std::snprintf(msg, sizeof msg,
                "paper sec. 5 on geforce256: %ld cases (%d light directions x %d texels); texture clamp (a T^n "
                "component outside [-1,1]) in %d of %d texels; register clamp (a dot or the sum outside [-1,1], quantised or float64) "
                "in %ld cases; %ld cases clamp-free. Max |alpha - exact| = %.4f LSB clamp-free, %.4f LSB "
                "in clamped cases; max |alpha - float64| = %.4f LSB clamp-free; ideal profile vs float64 %.2e LSB",
                cases, kAzimuths * kElevations, kTexels, texture_clamped, kTexels, register_clamped, both_clean,
                max_arith, max_arith_clamped, max_total, max_ideal);
  MESSAGE(msg);
  CHECK(both_clean > cases / 4);
  // Two register writes round (the two dot products, 1/2 LSB each); the stage-1
  // sum of codes and the final conversion are exact: at most 1 LSB.
  CHECK(max_arith <= 1.0);
  CHECK(max_arith_clamped <= 1.0);
  CHECK(max_arith > 0.5);  // both roundings are visible, i.e. the bound is tight
  // Quantising six texels and six constants to 8 bits, expanded x2, times factors
  // up to 1 each: at most 2 * 6 * 1/2 LSB from the inputs plus the 1 LSB above.
  CHECK(max_total <= 7.0);
  // The ideal profile differs from float64 only by the GLfloat constants.
  CHECK(max_ideal < 1e-4);
}

TEST_CASE("combiners paper section 5: describe() prints the pass as equations") {
  Context ctx(*find_builtin_profile("geforce256"), 4, 4);
  const float l[4] = {0.5f, 0.5f, 0.5f, 1};
  setup_paper_pass(ctx, l, l);
  CHECK(ctx.describe_combiners() ==
        "stage 0 rgb:   spare0.rgb = dot(expand(const0.rgb), expand(tex0.rgb))\n"
        "               spare1.rgb = dot(expand(const1.rgb), expand(tex1.rgb))\n"
        "stage 1 alpha: spare0.a = spare0.b + spare1.b\n"
        "final:         fcoc.rgb = 0\n"
        "               fcoc.a = max(spare0.a, 0)\n");
}

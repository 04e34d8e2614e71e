#include "sim/stress/invariants.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "bumpshadow/ellipse_test.h"
#include "bumpshadow/horizon.h"
#include "bumpshadow/reference.h"
#include "bumpshadow/shadow_map.h"
#include "pipeline/combiners/register_combiners.h"
#include "pipeline/number/unorm.h"
#include "sim/context.h"

namespace ffsim::stress {

namespace bs = ffsim::bumpshadow;

namespace {

bool finite3(const bs::Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool in_unit3(const bs::Vec3& v) { return std::fabs(v.x) <= 1 && std::fabs(v.y) <= 1 && std::fabs(v.z) <= 1; }
double comp(const bs::Vec3& v, int c) { return c == 0 ? v.x : c == 1 ? v.y : v.z; }

std::string fmt(const char* f, double a, double b = 0, double c = 0, double d = 0, double e = 0, double g = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a, b, c, d, e, g);
  return buf;
}

std::string describe(const bs::Ellipse& e, const LightDir& l) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "C=(%.17g, %.17g) a=(%.17g, %.17g) rx=%.17g ry=%.17g light=(%.17g, %.17g)", e.cx, e.cy,
                e.ax, e.ay, e.rx, e.ry, l.lx, l.ly);
  return buf;
}

// Fixed profile whose texture, colour and combiner grids are all 1/M (every
// built-in fixed profile): returns M, else throws.
int common_grid(const Profile& p) {
  const int mt = (1 << p.texture_bits) - 1, mc = (1 << p.color_bits) - 1, mr = (1 << (p.combiner_bits - 1)) - 1;
  if (!p.is_fixed() || mt != mc || mc != mr)
    throw std::invalid_argument(std::string("stress: the bounds of numerics §12 need a fixed profile with texture, "
                                            "colour and combiner grids equal (profile ") + p.name + ")");
  return mt;
}

// The section-5 pass (tests/sim/test_combiners_paper.cpp): stage 0 RGB spare0 =
// expand(const0).expand(tex0), spare1 = expand(const1).expand(tex1); stage 1 alpha
// spare0.a = spare0.b + spare1.b; final rgb 0, alpha spare0.a.
void setup_combiner_pass(Context& ctx, const float l1[4], const float l2[4]) {
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

// Registers after every stage: counts NaN/Inf and values outside [-1, 1].
void check_trace(const combiners::RegisterTrace& t, long long& nonfinite, long long& out_of_range) {
  bool nf = false, oor = false;
  for (const auto& stage : t.after_stage)
    for (const auto& reg : stage)
      for (double v : reg) {
        nf |= !std::isfinite(v);
        oor |= std::isfinite(v) && std::fabs(v) > 1;
      }
  nonfinite += nf;
  out_of_range += oor;
}

void note_worst(PathStats& s, double err, double bound, double lsb, const std::string& what) {
  const double ratio = err / bound;
  s.max_err_lsb = std::max(s.max_err_lsb, err * lsb);
  if (ratio > s.max_ratio || s.worst.empty()) {
    s.max_ratio = ratio;
    s.worst = what + fmt(": |hw - ideal| = %.4f LSB, bound %.4f LSB", err * lsb, bound * lsb);
  }
  if (err > bound) ++s.bound_exceeded;
}

}  // namespace

void RangeCounts::add(const RangeCounts& o) {
  texels += o.texels;
  center += o.center;
  tr_component += o.tr_component;
  tn_component += o.tn_component;
  t3r_alpha += o.t3r_alpha;
  t1n_alpha += o.t1n_alpha;
  cases += o.cases;
  dot += o.dot;
  sum += o.sum;
  lookup_index += o.lookup_index;
  lookup_entry += o.lookup_entry;
}

std::string RangeCounts::str() const {
  std::ostringstream o;
  o << "texels=" << texels << " |C|>1=" << center << " T^r-comp=" << tr_component << " T^n-comp=" << tn_component
    << " T3r-alpha>1=" << t3r_alpha << " T1n-alpha>1=" << t1n_alpha << " | cases=" << cases << " dot=" << dot
    << " sum=" << sum << " lookup-index=" << lookup_index << " lookup-entry=" << lookup_entry;
  return o.str();
}

void PathStats::add(const PathStats& o) {
  cases += o.cases;
  clamp_free += o.clamp_free;
  nonfinite += o.nonfinite;
  out_of_range += o.out_of_range;
  bound_exceeded += o.bound_exceeded;
  max_err_lsb = std::max(max_err_lsb, o.max_err_lsb);
  max_err_clamped_lsb = std::max(max_err_clamped_lsb, o.max_err_clamped_lsb);
  if (o.max_ratio > max_ratio || (worst.empty() && !o.worst.empty())) {
    max_ratio = std::max(max_ratio, o.max_ratio);
    worst = o.worst;
  }
  if (violation.empty()) violation = o.violation;
}

void EncodingStats::add(const EncodingStats& o) {
  cases += o.cases;
  nonfinite += o.nonfinite;
  formula_mismatch += o.formula_mismatch;
  bound_exceeded += o.bound_exceeded;
  max_ratio41 = std::max(max_ratio41, o.max_ratio41);
  max_ratio51 = std::max(max_ratio51, o.max_ratio51);
  if (worst.empty()) worst = o.worst;
}

void FieldStats::add(const FieldStats& o) {
  texels += o.texels;
  nonfinite += o.nonfinite;
  out_of_range += o.out_of_range;
  thread_mismatch += o.thread_mismatch;
  center_outside += o.center_outside;
  rx_above_sqrt2 += o.rx_above_sqrt2;
  max_abs_center = std::max(max_abs_center, o.max_abs_center);
  max_rx = std::max(max_rx, o.max_rx);
  if (detail.empty()) detail = o.detail;
}

// ---- bounds (docs/numerics.md §12) ----

double combiner_bound(const bs::Vec3& t1n, const bs::Vec3& t2n, double lx, double ly, int M) {
  const double eps = 1.0 / M;
  const double L[6] = {lx * lx, lx * ly, lx, ly, ly * ly, 1.0};
  const double T[6] = {t1n.x, t1n.y, t1n.z, t2n.x, t2n.y, t2n.z};
  double b = eps;  // two register writes, half a step each (§10.4)
  for (int i = 0; i < 6; ++i) b += eps * (std::fabs(L[i]) + std::fabs(T[i])) + eps * eps;
  // GLfloat constants (2^-24 per expanded component, in hw and ideal) and binary64.
  return b + 6 * 0x1.0p-23 + 1e-12;
}

double lookup_bound(double d, int table_width, int bits) {
  // Index step: half a table interval plus binary32 evaluation of A' and the index.
  const double delta = 0.5 / (table_width - 1) + 0x1.0p-20;
  const double spacing = 4 * delta * std::fabs(d) + 8 * delta * delta + 0x1.0p-24;  // per profile
  return 0.5 / ((1 << bits) - 1) + 2 * spacing + 1e-9;
}

// ---- encodings ----

EncodingStats encoding_path(const std::vector<bs::Ellipse>& ell, const std::vector<LightDir>& lights,
                            RangeCounts* ranges) {
  EncodingStats s;
  RangeCounts rc;
  const int n = static_cast<int>(ell.size());
  if (n == 0) return s;
  bs::EllipseMap m;
  m.width = n;
  m.height = 1;
  m.ellipse = ell;
  m.kind.assign(ell.size(), bs::TexelKind::Fitted);
  m.agree.assign(ell.size(), 0);
  const bs::EncodedMaps maps = bs::encode_maps(m);
  std::vector<bs::TexelEncoding> enc(ell.size());
  std::vector<char> in41(ell.size()), in51(ell.size());
  for (int i = 0; i < n; ++i) {
    const bs::Ellipse& e = ell[static_cast<std::size_t>(i)];
    const bs::TexelEncoding t = bs::encode_texel(e);
    enc[static_cast<std::size_t>(i)] = t;
    ++rc.texels;
    rc.center += std::hypot(e.cx, e.cy) > 1;
    const bool tr = in_unit3(t.t1r) && in_unit3(t.t2r), tn = in_unit3(t.t1n) && in_unit3(t.t2n);
    rc.tr_component += !tr;
    rc.tn_component += !tn;
    rc.t3r_alpha += t.rx2 / 2 > 1;
    rc.t1n_alpha += t.rx2 > 1;
    in41[static_cast<std::size_t>(i)] = tr && t.rx2 / 2 <= 1;
    in51[static_cast<std::size_t>(i)] = tn && t.rx2 <= 1;
    if (!finite3(t.t1r) || !finite3(t.t2r) || !finite3(t.t1n) || !finite3(t.t2n) || !std::isfinite(t.rx2)) {
      ++s.nonfinite;
      if (s.worst.empty()) s.worst = std::string("non-finite encoding: ") + describe(e, {});
    }
  }
  for (const auto* fm : {&maps.t1r, &maps.t2r, &maps.t3r, &maps.t1n, &maps.t2n})
    for (double v : fm->v)
      if (!std::isfinite(v)) {
        ++s.nonfinite;
        if (s.worst.empty()) s.worst = std::string("non-finite value in float map ") + fm->name;
      }
  for (const LightDir& l : lights) {
    const double lx = l.lx, ly = l.ly;
    for (int i = 0; i < n; ++i) {
      const std::size_t k = static_cast<std::size_t>(i);
      const bs::Ellipse& e = ell[k];
      const bs::TexelEncoding& t = enc[k];
      ++s.cases;
      const double v0 = bs::ellipse_test(e, lx, ly), v41 = bs::eq41(t.t1r, t.t2r, t.rx2, lx, ly),
                   v51 = bs::eq51(t.t1n, t.t2n, t.rx2, lx, ly);
      if (!std::isfinite(v0) || !std::isfinite(v41) || !std::isfinite(v51)) {
        ++s.nonfinite;
        if (s.worst.empty()) s.worst = std::string("non-finite shadow test: ") + describe(e, l);
        continue;
      }
      // Magnitude of the terms: the formulas agree to rounding relative to it.
      const double s1 = t.t1r.x * lx + t.t1r.y * ly - t.t1r.z, s2 = t.t2r.x * lx + t.t2r.y * ly - t.t2r.z;
      const double L[6] = {lx * lx, lx * ly, lx, ly, ly * ly, 1.0};
      double mag = 1 + t.rx2 + s1 * s1 + s2 * s2;
      for (int c = 0; c < 3; ++c) mag += std::fabs(L[c] * comp(t.t1n, c)) + std::fabs(L[3 + c] * comp(t.t2n, c));
      mag += (std::fabs(t.t1r.x) + std::fabs(t.t1r.y) + std::fabs(t.t1r.z) + std::fabs(t.t2r.x) + std::fabs(t.t2r.y) +
              std::fabs(t.t2r.z)) * 4;
      const double tol = 1e-12 * mag * mag;
      if (std::fabs(v41 - v0) > tol || std::fabs(v51 - v41) > tol) {
        ++s.formula_mismatch;
        if (s.worst.empty())
          s.worst = std::string("eq41/eq51/ellipse_test disagree: ") + describe(e, l) + fmt(" (%.17g, %.17g, %.17g)", v0, v41, v51);
      }
      // Decoded 8-bit maps (numerics §11.3), in-range texels only.
      const int x = i;
      if (in41[k]) {
        const bs::Vec3 a = bs::decode_rgb(maps.t1r8, x, 0), b = bs::decode_rgb(maps.t2r8, x, 0);
        const double rx2q = 2.0 * maps.t3r8.v[k] / 255.0;
        const double err = std::fabs(bs::eq41(a, b, rx2q, lx, ly) - v41);
        const double bound = bs::quantisation_bound41(t.t1r, t.t2r, lx, ly);
        s.max_ratio41 = std::max(s.max_ratio41, err / bound);
        if (err > bound) {
          ++s.bound_exceeded;
          if (s.worst.empty()) s.worst = std::string("eq41 8-bit beyond quantisation_bound41: ") + describe(e, l);
        }
      }
      if (in51[k]) {
        const bs::Vec3 a = bs::decode_rgb(maps.t1n8, x, 0), b = bs::decode_rgb(maps.t2n8, x, 0);
        const double rx2q = maps.t1n8.v[4 * k + 3] / 255.0;
        const double err = std::fabs(bs::eq51(a, b, rx2q, lx, ly) - v51);
        const double bound = bs::quantisation_bound51(lx, ly);
        s.max_ratio51 = std::max(s.max_ratio51, err / bound);
        if (err > bound) {
          ++s.bound_exceeded;
          if (s.worst.empty()) s.worst = std::string("eq51 8-bit beyond quantisation_bound51: ") + describe(e, l);
        }
      }
    }
  }
  if (ranges) ranges->add(rc);
  return s;
}

// ---- combiner path (paper section 5) ----

PathStats combiner_path(const std::vector<bs::Ellipse>& ell, const std::vector<LightDir>& lights, const Profile& hwp,
                        RangeCounts* ranges) {
  const int M = common_grid(hwp);
  PathStats s;
  RangeCounts rc;
  Context hw(hwp, 4, 4), ideal(*find_builtin_profile("ideal"), 4, 4);
  const std::size_t n = ell.size();
  std::vector<bs::TexelEncoding> enc(n);
  std::vector<std::uint16_t> tex0(4 * n), tex1(4 * n);
  std::vector<double> ftex0(4 * n), ftex1(4 * n);
  std::vector<char> tn_ok(n);
  for (std::size_t i = 0; i < n; ++i) {
    enc[i] = bs::encode_texel(ell[i]);
    for (int c = 0; c < 3; ++c) {
      const double a = comp(enc[i].t1n, c), b = comp(enc[i].t2n, c);
      tex0[4 * i + static_cast<std::size_t>(c)] = static_cast<std::uint16_t>(unorm_from_double((a + 1) / 2, hwp.texture_bits));
      tex1[4 * i + static_cast<std::size_t>(c)] = static_cast<std::uint16_t>(unorm_from_double((b + 1) / 2, hwp.texture_bits));
      ftex0[4 * i + static_cast<std::size_t>(c)] = std::clamp((a + 1) / 2, 0.0, 1.0);
      ftex1[4 * i + static_cast<std::size_t>(c)] = std::clamp((b + 1) / 2, 0.0, 1.0);
    }
    tex0[4 * i + 3] = static_cast<std::uint16_t>(unorm_from_double(enc[i].rx2, hwp.texture_bits));
    tex1[4 * i + 3] = static_cast<std::uint16_t>(M);
    ftex0[4 * i + 3] = std::clamp(enc[i].rx2, 0.0, 1.0);
    ftex1[4 * i + 3] = 1;
    tn_ok[i] = in_unit3(enc[i].t1n) && in_unit3(enc[i].t2n);
  }
  const std::uint16_t zero4[4] = {0, 0, 0, 0};
  const double fzero4[4] = {0, 0, 0, 0};
  for (const LightDir& l : lights) {
    const double lx = l.lx, ly = l.ly;
    const double L1[3] = {lx * lx, lx * ly, lx}, L2[3] = {ly, ly * ly, 1};  // erratum pairing
    float l1[4], l2[4];
    for (int c = 0; c < 3; ++c) {
      l1[c] = static_cast<float>((L1[c] + 1) / 2);
      l2[c] = static_cast<float>((L2[c] + 1) / 2);
    }
    l1[3] = l2[3] = 1;
    setup_combiner_pass(hw, l1, l2);
    setup_combiner_pass(ideal, l1, l2);
    if (hw.getError() != gl::NO_ERROR || ideal.getError() != gl::NO_ERROR)
      throw std::runtime_error("stress: GL error setting up the combiner pass");
    // The constants' codes as the hardware holds them (choice #36).
    std::int64_t k1[3], k2[3];
    for (int c = 0; c < 3; ++c) {
      k1[c] = 2 * unorm_from_double(l1[c], hwp.color_bits) - M;
      k2[c] = 2 * unorm_from_double(l2[c], hwp.color_bits) - M;
    }
    const auto& hplan = hw.combiner_plan();
    const auto& iplan = ideal.combiner_plan();
    for (std::size_t i = 0; i < n; ++i) {
      ++s.cases;
      ++rc.cases;
      combiners::CombinerInputsFixed in;
      in.count = 1;
      in.primary = zero4;
      in.secondary = zero4;
      in.texture[0] = &tex0[4 * i];
      in.texture[1] = &tex1[4 * i];
      std::uint16_t out[4];
      combiners::RegisterTrace tr;
      combiners::shade_span(hplan, in, {0, 0, 0, 0}, out, &tr);
      combiners::CombinerInputsFloat fin;
      fin.count = 1;
      fin.primary = fzero4;
      fin.secondary = fzero4;
      fin.texture[0] = &ftex0[4 * i];
      fin.texture[1] = &ftex1[4 * i];
      double fout[4];
      combiners::RegisterTrace ftr;
      combiners::shade_span(iplan, fin, {0, 0, 0, 0}, fout, &ftr);
      long long nf = 0, oor = 0;
      check_trace(tr, nf, oor);
      check_trace(ftr, nf, oor);
      for (int c = 0; c < 4; ++c) {
        oor += out[c] > M;
        nf += !std::isfinite(fout[c]);
        oor += std::isfinite(fout[c]) && (fout[c] < 0 || fout[c] > 1);
      }
      if (nf || oor) {
        s.nonfinite += nf > 0;
        s.out_of_range += oor > 0;
        if (s.violation.empty()) s.violation = std::string("NaN/Inf or out-of-range register: ") + describe(ell[i], l);
        continue;
      }
      // Clamps: texture (a T^n component outside [-1, 1]), register (a dot product or
      // the sum outside [-1, 1], exact on the codes or in float64), final max(0, .).
      std::int64_t q1 = 0, q2 = 0;
      for (int c = 0; c < 3; ++c) {
        q1 += k1[c] * (2 * std::int64_t{tex0[4 * i + static_cast<std::size_t>(c)]} - M);
        q2 += k2[c] * (2 * std::int64_t{tex1[4 * i + static_cast<std::size_t>(c)]} - M);
      }
      const std::int64_t one = std::int64_t{M} * M;
      double d1 = 0, d2 = 0;
      for (int c = 0; c < 3; ++c) {
        d1 += L1[c] * comp(enc[i].t1n, c);
        d2 += L2[c] * comp(enc[i].t2n, c);
      }
      const bool dot_clamp = std::llabs(q1) > one || std::llabs(q2) > one || std::fabs(d1) > 1 || std::fabs(d2) > 1;
      const bool sum_clamp = q1 + q2 > one || q1 + q2 < 0 || d1 + d2 > 1 || d1 + d2 < 0;
      rc.dot += dot_clamp;
      rc.sum += !dot_clamp && sum_clamp;
      const double err = std::fabs(out[3] / static_cast<double>(M) - fout[3]);
      if (!tn_ok[i] || dot_clamp || sum_clamp) {
        s.max_err_clamped_lsb = std::max(s.max_err_clamped_lsb, err * M);
        continue;
      }
      ++s.clamp_free;
      note_worst(s, err, combiner_bound(enc[i].t1n, enc[i].t2n, lx, ly, M), M, hwp.name + " " + describe(ell[i], l));
    }
  }
  if (ranges) ranges->add(rc);
  return s;
}

// ---- lookup-table path (paper section 4.1.4) ----

namespace {

void setup_lookup(Context& ctx, double lx, double ly, int width) {
  const double m[16] = {0, 0, 0, lx / 2, 0, 0, 0, ly / 2, 0, 0, 0, -0.5, 0, 0, 0, -(lx + ly) / 4 + 0.5};
  ctx.matrixMode(gl::COLOR);
  ctx.loadMatrix(m);
  ctx.matrixMode(gl::MODELVIEW);
  std::vector<float> table(static_cast<std::size_t>(width));
  for (int i = 0; i < width; ++i) {
    const double a = static_cast<double>(i) / (width - 1);
    table[static_cast<std::size_t>(i)] = static_cast<float>((4 * a - 1) * (4 * a - 1) / 2);
  }
  ctx.colorTable(gl::POST_COLOR_MATRIX_COLOR_TABLE, gl::ALPHA, width, gl::ALPHA, gl::FLOAT, table.data());
  ctx.enable(gl::POST_COLOR_MATRIX_COLOR_TABLE);
}

}  // namespace

PathStats lookup_path(const std::vector<bs::Ellipse>& ell, const std::vector<LightDir>& lights, const Profile& hwp,
                      int table_width, RangeCounts* ranges) {
  if (!hwp.is_fixed()) throw std::invalid_argument("stress: lookup_path needs a fixed hardware profile");
  PathStats s;
  RangeCounts rc;
  Context hw(hwp, 4, 4), ideal(*find_builtin_profile("ideal"), 4, 4);
  // T1^r and T2^r of every ellipse, biased 8-bit RGBA (alpha 1), as texels of a
  // 64-wide power-of-two texture (padding texels: code 128 everywhere).
  const std::size_t n = 2 * ell.size();
  int h = 1;
  while (static_cast<std::size_t>(64 * h) < n) h *= 2;
  std::vector<std::uint8_t> data(static_cast<std::size_t>(4 * 64 * h), 128);
  for (std::size_t i = 0; i < ell.size(); ++i) {
    const bs::TexelEncoding t = bs::encode_texel(ell[i]);
    for (int k = 0; k < 2; ++k) {
      const bs::Vec3& v = k == 0 ? t.t1r : t.t2r;
      std::uint8_t* p = &data[4 * (2 * i + static_cast<std::size_t>(k))];
      for (int c = 0; c < 3; ++c) p[c] = static_cast<std::uint8_t>(unorm_from_double((comp(v, c) + 1) / 2, 8));
      p[3] = 255;
    }
  }
  const int maxcode = (1 << hwp.texture_bits) - 1;
  for (const LightDir& l : lights) {
    const double lx = l.lx, ly = l.ly;
    setup_lookup(hw, lx, ly, table_width);
    setup_lookup(ideal, lx, ly, table_width);
    hw.texImage2D(gl::TEXTURE_2D, 0, gl::RGBA, 64, h, 0, gl::RGBA, gl::UNSIGNED_BYTE, data.data());
    ideal.texImage2D(gl::TEXTURE_2D, 0, gl::RGBA, 64, h, 0, gl::RGBA, gl::UNSIGNED_BYTE, data.data());
    if (hw.getError() != gl::NO_ERROR || ideal.getError() != gl::NO_ERROR)
      throw std::runtime_error("stress: GL error in the lookup-table path");
    const TextureImage& th = hw.bound_texture(0, gl::TEXTURE_2D).levels.at(0);
    const TextureImage& ti = ideal.bound_texture(0, gl::TEXTURE_2D).levels.at(0);
    for (std::size_t i = 0; i < n; ++i) {
      ++s.cases;
      ++rc.cases;
      const std::uint8_t* p = &data[4 * i];
      const double tx = 2.0 * p[0] / 255 - 1, ty = 2.0 * p[1] / 255 - 1, tz = 2.0 * p[2] / 255 - 1;
      const double d = lx * tx + ly * ty - tz;  // L.t of the decoded texel
      const double a = d / 4 + 0.25;            // A' before the index clamp
      bool bad = false;
      for (int c = 0; c < 4; ++c) {
        const double v = ti.values[4 * i + static_cast<std::size_t>(c)];
        bad |= th.codes[4 * i + static_cast<std::size_t>(c)] > maxcode || !std::isfinite(v) || v < 0 || v > 1;
        s.nonfinite += !std::isfinite(v);
      }
      if (bad) {
        ++s.out_of_range;
        if (s.violation.empty()) s.violation = std::string("NaN/Inf or out-of-range texel in the lookup path: ") + describe(ell[i / 2], l);
        continue;
      }
      const bool index_clamp = a < 0 || a > 1, entry_clamp = !index_clamp && d * d / 2 > 1;
      rc.lookup_index += index_clamp;
      rc.lookup_entry += entry_clamp;
      const double err = std::fabs(th.codes[4 * i + 3] / static_cast<double>(maxcode) - ti.values[4 * i + 3]);
      if (index_clamp || entry_clamp) {
        s.max_err_clamped_lsb = std::max(s.max_err_clamped_lsb, err * maxcode);
        continue;
      }
      ++s.clamp_free;
      note_worst(s, err, lookup_bound(d, table_width, hwp.texture_bits), maxcode,
                 hwp.name + " W=" + std::to_string(table_width) + " " + describe(ell[i / 2], l));
    }
  }
  if (ranges) ranges->add(rc);
  return s;
}

// ---- height fields ----

FieldStats field_path(const bs::HeightField& hf, const std::vector<LightDir>& lights, int rays, RangeCounts* ranges) {
  FieldStats s;
  auto flag = [&](long long& counter, const std::string& what) {
    ++counter;
    if (s.detail.empty()) s.detail = what;
  };
  bs::ShadowMapOptions o;
  o.rays = bs::rays_for_count(rays);
  o.threads = 1;
  const bs::EllipseMap m1 = bs::compute_ellipse_map(hf, o);
  for (int t : {2, 3}) {
    o.threads = t;
    if (!(bs::compute_ellipse_map(hf, o) == m1)) flag(s.thread_mismatch, std::string("ellipse map differs at threads=") + std::to_string(t));
  }
  s.texels = static_cast<long long>(m1.ellipse.size());
  for (std::size_t i = 0; i < m1.ellipse.size(); ++i) {
    const bs::Ellipse& e = m1.ellipse[i];
    const std::string where = std::string("texel ") + std::to_string(i % static_cast<std::size_t>(hf.width())) + "," +
                              std::to_string(i / static_cast<std::size_t>(hf.width()));
    if (!std::isfinite(e.cx) || !std::isfinite(e.cy) || !std::isfinite(e.ax) || !std::isfinite(e.ay) ||
        !std::isfinite(e.rx) || !std::isfinite(e.ry)) {
      flag(s.nonfinite, std::string("non-finite ellipse at ") + where);
      continue;
    }
    if (e.rx < 0 || e.ry < e.rx || std::fabs(e.ax * e.ax + e.ay * e.ay - 1) > 1e-9)
      flag(s.out_of_range, std::string("ellipse outside its documented form at ") + where);
    const double c = std::hypot(e.cx, e.cy);
    s.center_outside += c > 1;
    s.rx_above_sqrt2 += e.rx > std::sqrt(2.0);
    s.max_abs_center = std::max(s.max_abs_center, c);
    s.max_rx = std::max(s.max_rx, e.rx);
  }
  // Encodings of the fitted map (range counts as the encoding path counts them).
  RangeCounts rc;
  const bs::EncodedMaps maps = bs::encode_maps(m1);
  for (const auto* fm : {&maps.t1r, &maps.t2r, &maps.t3r, &maps.t1n, &maps.t2n})
    for (double v : fm->v)
      if (!std::isfinite(v)) flag(s.nonfinite, std::string("non-finite value in ") + fm->name);
  for (const bs::Ellipse& e : m1.ellipse) {
    const bs::TexelEncoding t = bs::encode_texel(e);
    ++rc.texels;
    rc.center += std::hypot(e.cx, e.cy) > 1;
    rc.tr_component += !(in_unit3(t.t1r) && in_unit3(t.t2r));
    rc.tn_component += !(in_unit3(t.t1n) && in_unit3(t.t2n));
    rc.t3r_alpha += t.rx2 / 2 > 1;
    rc.t1n_alpha += t.rx2 > 1;
  }
  if (ranges) ranges->add(rc);
  const bs::FloatMap nm = bs::normal_map(hf);
  for (double v : nm.v)
    if (!std::isfinite(v) || v < 0 || v > 1) flag(v != v ? s.nonfinite : s.out_of_range, "normal map value outside [0,1]");
  // Horizon map: elevations in [0, pi/2], thread independent.
  const bs::HorizonMap h1 = bs::compute_horizon_map(hf, 8, {}, 1);
  const bs::HorizonMap h3 = bs::compute_horizon_map(hf, 8, {}, 3);
  if (h1.elevation != h3.elevation) flag(s.thread_mismatch, "horizon map differs at threads=3");
  for (double v : h1.elevation) {
    if (!std::isfinite(v)) flag(s.nonfinite, "non-finite horizon elevation");
    else if (v < 0 || v > std::numbers::pi / 2) flag(s.out_of_range, "horizon elevation outside [0, pi/2]");
  }
  for (const LightDir& l : lights) {
    const bs::Vec3 L{l.lx, l.ly, l.lz};
    const auto r1 = bs::reference_lit_map(hf, L, {}, 1), r3 = bs::reference_lit_map(hf, L, {}, 3);
    if (r1 != r3) flag(s.thread_mismatch, "reference lit map differs at threads=3");
    for (auto v : r1)
      if (v > 1) flag(s.out_of_range, "reference lit map value not 0/1");
    const auto f1 = bs::reference_soft_map(hf, L, 0.2, 8, {}, 1), f3 = bs::reference_soft_map(hf, L, 0.2, 8, {}, 3);
    if (f1 != f3) flag(s.thread_mismatch, "soft reference differs at threads=3");
    for (double v : f1) {
      if (!std::isfinite(v)) flag(s.nonfinite, "non-finite soft reference");
      else if (v < 0 || v > 1) flag(s.out_of_range, "soft reference outside [0,1]");
    }
    for (double d : bs::ellipse_test_map(m1, L))
      if (!std::isfinite(d)) flag(s.nonfinite, std::string("non-finite ellipse test d for light ") + fmt("(%.17g, %.17g, %.17g)", l.lx, l.ly, l.lz));
    for (auto v : bs::horizon_lit_map(h1, L))
      if (v > 1) flag(s.out_of_range, "horizon lit map value not 0/1");
    for (int y = 0; y < hf.height(); ++y)
      for (int x = 0; x < hf.width(); ++x) {
        const double f = bs::horizon_light(h1, x, y, L, 0.2);
        if (!std::isfinite(f)) flag(s.nonfinite, "non-finite horizon_light");
        else if (f < 0 || f > 1) flag(s.out_of_range, "horizon_light outside [0,1]");
      }
  }
  return s;
}

}  // namespace ffsim::stress

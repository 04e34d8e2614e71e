#include "bumpshadow/encodings.h"

#include <cmath>

#include "pipeline/number/unorm.h"

namespace ffsim::bumpshadow {

TexelEncoding encode_texel(const Ellipse& e) {
  TexelEncoding t;
  const double q = radius_ratio(e);
  t.t1r = {e.ax, e.ay, e.ax * e.cx + e.ay * e.cy};
  t.t2r = {-e.ay * q, e.ax * q, (-e.ay * e.cx + e.ax * e.cy) * q};
  const Vec3 &a = t.t1r, &b = t.t2r;
  t.t1n = {a.x * a.x + b.x * b.x, 2 * a.x * a.y + 2 * b.x * b.y, -2 * a.x * a.z - 2 * b.x * b.z};
  t.t2n = {-2 * a.y * a.z - 2 * b.y * b.z, a.y * a.y + b.y * b.y, a.z * a.z + b.z * b.z};
  t.rx2 = e.rx * e.rx;
  return t;
}

double eq41(const Vec3& t1r, const Vec3& t2r, double rx2, double lx, double ly) {
  const double s1 = t1r.x * lx + t1r.y * ly - t1r.z;
  const double s2 = t2r.x * lx + t2r.y * ly - t2r.z;
  return rx2 - s1 * s1 - s2 * s2;
}

double eq51(const Vec3& t1n, const Vec3& t2n, double rx2, double lx, double ly, L2Pairing pairing) {
  const double d1 = lx * lx * t1n.x + lx * ly * t1n.y + lx * t1n.z;
  const double d2 = pairing == L2Pairing::Consistent ? ly * t2n.x + ly * ly * t2n.y + t2n.z
                                                     : ly * ly * t2n.x + ly * t2n.y + t2n.z;
  return rx2 - d1 - d2;
}

ByteMap quantise(const FloatMap& m, long long* clamped_components) {
  ByteMap b{m.name, m.width, m.height, m.channels, std::vector<std::uint8_t>(m.v.size())};
  long long clamped = 0;
  for (std::size_t i = 0; i < m.v.size(); ++i) {
    clamped += m.v[i] < 0 || m.v[i] > 1;
    b.v[i] = static_cast<std::uint8_t>(unorm_from_double(m.v[i], 8));
  }
  if (clamped_components) *clamped_components = clamped;
  return b;
}

namespace {

FloatMap make_map(const char* name, int w, int h, int ch) {
  return FloatMap{name, w, h, ch, std::vector<double>(static_cast<std::size_t>(w) * h * ch)};
}

// Counts components outside [lo, hi] of one texel for the range report.
struct RangeCounter {
  RangeReport r;
  bool texel_bad = false;
  void check(double c, double lo, double hi) {
    if (c < lo || c > hi) {
      ++r.components_out_of_range;
      texel_bad = true;
    }
  }
  void end_texel() {
    r.texels_out_of_range += texel_bad;
    texel_bad = false;
  }
};

}  // namespace

EncodedMaps encode_maps(const EllipseMap& m) {
  const int w = m.width, h = m.height;
  EncodedMaps out;
  out.t1r = make_map("t1r", w, h, 4);
  out.t2r = make_map("t2r", w, h, 4);
  out.t3r = make_map("t3r", w, h, 1);
  out.t1n = make_map("t1n", w, h, 4);
  out.t2n = make_map("t2n", w, h, 4);
  RangeCounter r1{{"t1r"}}, r2{{"t2r"}}, r3{{"t3r"}}, n1{{"t1n"}}, n2{{"t2n"}};
  auto bias = [](double c) { return 0.5 * (c + 1.0); };
  for (std::size_t t = 0; t < m.ellipse.size(); ++t) {
    const Ellipse& e = m.ellipse[t];
    const TexelEncoding enc = encode_texel(e);
    out.center_outside_unit += e.cx * e.cx + e.cy * e.cy > 1;
    out.rx_above_sqrt2 += e.rx * e.rx > 2;
    out.rx_above_1 += e.rx > 1;
    auto put3 = [&](FloatMap& f, RangeCounter& rc, const Vec3& v, double alpha) {
      for (int c = 0; c < 3; ++c) {
        const double comp = c == 0 ? v.x : c == 1 ? v.y : v.z;
        rc.check(comp, -1, 1);
        f.v[t * 4 + c] = bias(comp);
      }
      f.v[t * 4 + 3] = alpha;
    };
    put3(out.t1r, r1, enc.t1r, 1.0);
    put3(out.t2r, r2, enc.t2r, 1.0);
    r3.check(enc.rx2 / 2, 0, 1);
    out.t3r.v[t] = enc.rx2 / 2;
    put3(out.t1n, n1, enc.t1n, enc.rx2);
    n1.check(enc.rx2, 0, 1);
    put3(out.t2n, n2, enc.t2n, 1.0);
    for (RangeCounter* rc : {&r1, &r2, &r3, &n1, &n2}) rc->end_texel();
  }
  out.t1r8 = quantise(out.t1r, &r1.r.components_clamped);
  out.t2r8 = quantise(out.t2r, &r2.r.components_clamped);
  out.t3r8 = quantise(out.t3r, &r3.r.components_clamped);
  out.t1n8 = quantise(out.t1n, &n1.r.components_clamped);
  out.t2n8 = quantise(out.t2n, &n2.r.components_clamped);
  out.ranges = {r1.r, r2.r, r3.r, n1.r, n2.r};
  return out;
}

FloatMap normal_map(const HeightField& hf) {
  const int w = hf.width(), h = hf.height();
  FloatMap m = make_map("normal", w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double nx = -0.5 * (hf.at(x + 1, y) - hf.at(x - 1, y));
      const double ny = -0.5 * (hf.at(x, y + 1) - hf.at(x, y - 1));
      const double len = std::sqrt(nx * nx + ny * ny + 1.0);
      const std::size_t t = (static_cast<std::size_t>(y) * w + x) * 3;
      m.v[t] = 0.5 * (nx / len + 1);
      m.v[t + 1] = 0.5 * (ny / len + 1);
      m.v[t + 2] = 0.5 * (1 / len + 1);
    }
  return m;
}

Vec3 decode_rgb(const ByteMap& m, int x, int y) {
  const std::size_t t = (static_cast<std::size_t>(y) * m.width + x) * m.channels;
  return {decode_biased(m.v[t]), decode_biased(m.v[t + 1]), decode_biased(m.v[t + 2])};
}

double quantisation_bound41(const Vec3& t1r, const Vec3& t2r, double lx, double ly) {
  const double delta = (std::abs(lx) + std::abs(ly) + 1) / 255.0;
  const double s1 = std::abs(t1r.x * lx + t1r.y * ly - t1r.z), s2 = std::abs(t2r.x * lx + t2r.y * ly - t2r.z);
  return 1 / 255.0 + (2 * s1 * delta + delta * delta) + (2 * s2 * delta + delta * delta) + 1e-12;
}

double quantisation_bound51(double lx, double ly) {
  return 1 / 510.0 + (lx * lx + std::abs(lx * ly) + std::abs(lx) + std::abs(ly) + ly * ly + 1) / 255.0 + 1e-12;
}

}  // namespace ffsim::bumpshadow

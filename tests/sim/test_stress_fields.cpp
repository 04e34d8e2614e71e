// Issue 9, numerical stability: height fields that are flat, a single spike one
// texel wide, a cliff, noise at the texel scale, with height scales from 1e-6 to
// 1e6, non-square and non-power-of-two sizes, through visibility, ellipse fit,
// encodings, horizon map and the references (sim/stress/invariants.h
// field_path): no NaN/Inf, every value in its documented range, identical maps
// at 1, 2 and 3 threads. |C| > 1 and rx > sqrt 2 are flagged and printed.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "bumpshadow/shadow_map.h"
#include "sim/stress/cases.h"
#include "sim/stress/invariants.h"

using namespace ffsim::stress;
namespace bs = ffsim::bumpshadow;

TEST_CASE("stress fields: flat, spike, cliff and noise at scales 1e-6..1e6 and odd sizes stay finite and in range") {
  const std::vector<LightDir> lights = {light_at(60, 0.4), light_at(1, 2.5), light_at(0, 4.0),
                                        LightDir{0.6, 0.8, std::sqrt(1 - 0.6 * 0.6 - 0.8 * 0.8)}};
#ifdef FFSIM_SANITIZE
  const std::vector<std::pair<int, int>> sizes = {{1, 1}, {2, 2}, {7, 3}};
  const std::vector<double> scales = {1e-6, 1, 1e6};
#else
  const std::vector<std::pair<int, int>> sizes = {{1, 1}, {1, 7}, {7, 1}, {2, 2}, {7, 3}, {5, 13}, {16, 16}};
  const std::vector<double> scales = {1e-6, 1e-3, 1, 30, 1e6};
#endif
  FieldStats total;
  RangeCounts ranges;
  int fields = 0;
  for (int k = 0; k < static_cast<int>(FieldKind::Count); ++k)
    for (const auto& [w, h] : sizes)
      for (double scale : scales)
        for (bs::Border border : {bs::Border::Wrap, bs::Border::Clamp}) {
          const auto kind = static_cast<FieldKind>(k);
          CAPTURE(field_kind_name(kind));
          CAPTURE(w);
          CAPTURE(h);
          CAPTURE(scale);
          CAPTURE(bs::border_name(border));
          const bs::HeightField hf = make_field(kind, w, h, scale, border, 11);
          const FieldStats s = field_path(hf, lights, 16, &ranges);
          CAPTURE(s.detail);
          CHECK(s.nonfinite == 0);
          CHECK(s.out_of_range == 0);
          CHECK(s.thread_mismatch == 0);
          CHECK(s.texels == static_cast<long long>(w) * h);
          total.add(s);
          ++fields;
        }
  MESSAGE(fields, " fields, ", total.texels, " texels: |C| > 1 in ", total.center_outside, " (max |C| ",
          total.max_abs_center, "), rx > sqrt 2 in ", total.rx_above_sqrt2, " (max rx ", total.max_rx,
          "); encodings: ", ranges.str());
  // A flat field is all lit: the unit circle at 0 (docs/bumpshadow.md §4.4), so
  // max rx = 1 is reached; the fit never leaves rx <= ry or produces |C| > 1 here.
  CHECK(total.max_rx >= 1);
}

TEST_CASE("stress fields: a spike one texel wide shadows its neighbours at every scale, a flat field at none") {
  for (double scale : {1e-6, 1.0, 1e6}) {
    CAPTURE(scale);
    const bs::HeightField spike = make_field(FieldKind::Spike, 9, 9, scale, bs::Border::Clamp, 1);
    bs::ShadowMapOptions o;
    o.rays = bs::rays_for_count(64);
    o.threads = 1;
    const bs::EllipseMap m = bs::compute_ellipse_map(spike, o);
    // The spike itself (texel 4,4) sees the whole sky; its neighbour (5,4) loses
    // the rays toward -x below the spike's elevation atan(scale): at scale 1e-6
    // that is < 1e-6 rad, which no ray of 64 hits, so the neighbour is all lit too.
    CHECK(m.kind[4 * 9 + 4] == bs::TexelKind::AllLit);
    if (scale >= 1) CHECK(m.kind[4 * 9 + 5] != bs::TexelKind::AllLit);
    else CHECK(m.kind[4 * 9 + 5] == bs::TexelKind::AllLit);
  }
  const bs::EllipseMap flat = [] {
    bs::ShadowMapOptions o;
    o.rays = bs::rays_for_count(64);
    o.threads = 1;
    return bs::compute_ellipse_map(make_field(FieldKind::Flat, 5, 3, 1e6, bs::Border::Wrap, 1), o);
  }();
  CHECK(flat.kind_count[static_cast<int>(bs::TexelKind::AllLit)] == 15);
}

TEST_CASE("stress fields: 1x1 and 1xN fields are all lit or shadowed as their profile says, 0-sized ones are refused") {
  // A 1x1 field is flat under either border (it tiles, or its plateau continues):
  // every ray escapes, so the texel is all lit (docs/bumpshadow.md §1).
  for (bs::Border border : {bs::Border::Wrap, bs::Border::Clamp}) {
    bs::ShadowMapOptions o;
    o.rays = bs::rays_for_count(64);
    o.threads = 1;
    const bs::EllipseMap m = bs::compute_ellipse_map(make_field(FieldKind::Noise, 1, 1, 1e6, border, 3), o);
    CHECK(m.kind_count[static_cast<int>(bs::TexelKind::AllLit)] == 1);
  }
  // A 7x1 cliff under clamp is a step along x that continues in y: the texel at the
  // foot of the cliff loses the rays toward the cliff, the top one sees everything.
  {
    bs::ShadowMapOptions o;
    o.rays = bs::rays_for_count(64);
    o.threads = 1;
    const bs::HeightField cliff = make_field(FieldKind::Cliff, 7, 1, 1, bs::Border::Clamp, 1);
    const bs::EllipseMap m = bs::compute_ellipse_map(cliff, o);
    int shadowed = 0;
    for (int x = 0; x < 7; ++x) shadowed += m.kind[static_cast<std::size_t>(x)] != bs::TexelKind::AllLit;
    CHECK(shadowed > 0);
    CHECK(shadowed < 7);
  }
  for (auto [w, h] : std::vector<std::pair<int, int>>{{0, 0}, {0, 7}, {7, 0}}) {
    CAPTURE(w);
    CAPTURE(h);
    std::string msg;
    try {
      bs::HeightField(w, h, {}, bs::Border::Wrap);
    } catch (const bs::HeightFieldError& e) {
      msg = e.what();
    }
    CAPTURE(msg);
    CHECK(msg.find(std::string("height field size ") + std::to_string(w) + "x" + std::to_string(h)) != std::string::npos);
  }
}

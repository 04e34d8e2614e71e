#include "sim/bench/accuracy_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "sim/paper.h"

namespace ffsim::bench {

namespace {

const Image& need(const paper::Run& run, const std::string& name) {
  const Image* im = paper::image_of(run, name);
  if (!im) throw std::runtime_error(std::string("the run dumped no ") + name);
  return *im;
}

std::vector<float> rgb(const Image& im) {
  std::vector<float> v(static_cast<std::size_t>(im.width) * im.height * 3);
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x)
      for (int c = 0; c < 3; ++c)
        v[(static_cast<std::size_t>(y) * im.width + x) * 3 + c] =
            static_cast<float>(im.value(x, y, std::min(c, im.channels - 1)));
  return v;
}

std::vector<double> as_factor(const std::vector<bool>& lit) {
  std::vector<double> f(lit.size());
  for (std::size_t i = 0; i < lit.size(); ++i) f[i] = lit[i] ? 1.0 : 0.0;
  return f;
}

}  // namespace

ReferenceFrame reference_frame(const paper::Run& run) {
  ReferenceFrame r;
  const Image& cov = need(run, "coverage.png");
  r.width = cov.width;
  r.height = cov.height;
  r.covered = paper::threshold(paper::channel_values(cov), 0.5);
  r.exact.width = r.ellipse.width = r.width;
  r.exact.height = r.ellipse.height = r.height;
  r.exact.lit = paper::threshold(paper::channel_values(need(run, "reference.png")), 0.5);
  r.soft = paper::channel_values(need(run, "soft.png"));
  r.exact.factor = as_factor(r.exact.lit);  // the hard reference: its factor is its mask
  r.exact.shaded = rgb(need(run, "shaded.png"));
  r.ellipse.lit = paper::threshold(paper::channel_values(need(run, "ellipse.png")), 0.5);
  r.ellipse.factor = as_factor(r.ellipse.lit);
  r.ellipse.shaded = rgb(need(run, "bump.png"));
  for (std::size_t i = 0; i < r.ellipse.lit.size(); ++i)
    if (!r.ellipse.lit[i])
      for (int c = 0; c < 3; ++c) r.ellipse.shaded[i * 3 + c] = 0;
  return r;
}

Frame variant_frame(const paper::Run& run, VariantKind kind) {
  Frame f;
  const Image& color = need(run, "color.png");
  f.width = color.width;
  f.height = color.height;
  f.shaded = rgb(color);
  if (kind == VariantKind::Hard) {
    const std::vector<double> s = paper::channel_values(need(run, "stencil.png"));
    f.lit.resize(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) f.lit[i] = s[i] == 0;
    f.factor = as_factor(f.lit);
  } else {
    f.lit = paper::threshold(paper::channel_values(need(run, "alpha.png")), 0);
    f.factor = paper::channel_values(need(run, "factor.png"));
  }
  return f;
}

FrameError frame_error(const Frame& f, const Frame& ref, const std::vector<bool>& covered,
                       const std::vector<double>* soft) {
  FrameError e;
  const paper::ShadowStats s = paper::compare_masks(f.lit, ref.lit, covered);
  e.pixels = s.pixels;
  e.false_lit = s.false_lit;
  e.false_shadow = s.false_shadow;
  e.disagreement = s.disagreement();
  if (soft) e.factor_rmse = paper::rmse(f.factor, *soft, covered);
  double sum = 0;
  long long n = 0;
  const std::size_t m = std::min({covered.size(), f.shaded.size() / 3, ref.shaded.size() / 3});
  for (std::size_t i = 0; i < m; ++i) {
    if (!covered[i]) continue;
    for (int c = 0; c < 3; ++c) {
      const double d = static_cast<double>(f.shaded[i * 3 + c]) - static_cast<double>(ref.shaded[i * 3 + c]);
      sum += d * d;
      ++n;
      if (std::fabs(d) > e.worst) {
        e.worst = std::fabs(d);
        e.worst_x = f.width ? static_cast<int>(i % static_cast<std::size_t>(f.width)) : 0;
        e.worst_y = f.width ? static_cast<int>(i / static_cast<std::size_t>(f.width)) : 0;
      }
    }
  }
  e.shaded_rmse = n ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
  return e;
}

void RowAccumulator::add(const FrameError& e, const std::string& light) {
  ++lights;
  sum_dis += e.disagreement;
  sum_shaded += e.shaded_rmse;
  sum_factor += e.factor_rmse;
  if (e.disagreement > max_dis) max_dis = e.disagreement, worst_light = light;
  max_shaded = std::max(max_shaded, e.shaded_rmse);
  max_factor = std::max(max_factor, e.factor_rmse);
  if (e.worst > worst) worst = e.worst, worst_x = e.worst_x, worst_y = e.worst_y, worst_pixel_light = light;
}

void RowAccumulator::add_vs_ideal(const FrameError& e) {
  ++ideal_lights;
  sum_ideal_dis += e.disagreement;
  sum_ideal_shaded += e.shaded_rmse;
  max_ideal_dis = std::max(max_ideal_dis, e.disagreement);
}

void RowAccumulator::fail(const std::string& message) {
  if (ok) error = message;
  ok = false;
}

Spread spread(std::vector<double> v) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (v.empty()) return {nan, nan, nan};
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  const double med = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  return {med, v.front(), v.back()};
}

}  // namespace ffsim::bench

// The transfer plan: stages that cannot change anything drop out, the plan says
// so, and running the plan gives exactly the bits of running every stage.
#include <doctest/doctest.h>

#include <cstring>
#include <random>

#include "color_table_util.h"
#include "pipeline/pixel_transfer/transfer_plan.h"

using namespace ffsim;
using namespace ffsim::pixel;
using ffsim::pixel::test::random_table;

namespace {
const Matrix4 kIdentity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

template <class T>
bool same_bits(const RgbaImage<T>& a, const RgbaImage<T>& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.px.data(), b.px.data(), a.px.size() * sizeof(T)) == 0;
}
}  // namespace

TEST_CASE("pixel plan: identity and disabled stages drop out and the plan prints them") {
  PixelTransferState ts;
  ImagingState is;
  Matrix4 m = kIdentity;
  CHECK(plan_transfer({ts, is, m}, ImageDims::TwoD).str({ts, is, m}) == "identity");
  // A table that is enabled but has width 0, and a filter that is enabled but empty, do nothing.
  is.table(TableSlot::Color).enabled = true;
  is.conv2d.enabled = true;
  CHECK(plan_transfer({ts, is, m}, ImageDims::TwoD).empty());
  // The paper's configuration: colour matrix + post-colour-matrix ALPHA table.
  m[3] = 0.5;
  is.table(TableSlot::PostColorMatrix) = ColorTable{true, gl::ALPHA, BaseFormat::Alpha, 4096, std::vector<double>(4096, 0.0), {1, 1, 1, 1}, {0, 0, 0, 0}};
  TransferInputs in{ts, is, m};
  CHECK(plan_transfer(in, ImageDims::TwoD).str(in) == "color_matrix -> post_color_matrix_color_table(ALPHA, 4096)");
  // Convolution: 1D images use CONVOLUTION_1D only; 2D prefers CONVOLUTION_2D over SEPARABLE_2D.
  is.conv2d.width = 3;
  is.conv2d.height = 3;
  is.conv2d.taps.assign(36, 0.0);
  is.separable2d.enabled = true;
  is.separable2d.width = 3;
  ts.post_convolution_scale = {2, 2, 2, 2};
  // `in` refers to ts and is, so it sees the changes above.
  CHECK(plan_transfer(in, ImageDims::TwoD).str(in) ==
        "convolution(2D 3x3, RGBA, REDUCE) -> post_convolution_scale_bias -> color_matrix -> "
        "post_color_matrix_color_table(ALPHA, 4096)");
  CHECK(plan_transfer(in, ImageDims::OneD).str(in) == "color_matrix -> post_color_matrix_color_table(ALPHA, 4096)");
  is.conv2d.enabled = false;
  // `in` refers to ts and is, so it sees the changes above.
  CHECK(plan_transfer(in, ImageDims::TwoD).filter_kind == FilterKind::Separable);
}

TEST_CASE_TEMPLATE("pixel plan: the planned path is bit-identical to running every stage", T, float, double) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  const auto maybe = [&](double identity_value) { return rng() % 2 ? identity_value : u(rng); };
  int nonempty_plans = 0, skipped_stages = 0;
  for (int trial = 0; trial < 400; ++trial) {
    PixelTransferState ts;
    for (int c = 0; c < 4; ++c) {
      ts.scale[c] = maybe(1);
      ts.bias[c] = maybe(0);
      ts.post_convolution_scale[c] = maybe(1);
      ts.post_convolution_bias[c] = maybe(0);
      ts.post_color_matrix_scale[c] = maybe(1);
      ts.post_color_matrix_bias[c] = maybe(0);
      ts.color_maps[c].clear();
      for (int i = 0; i < 1 + static_cast<int>(rng() % 8); ++i) ts.color_maps[c].push_back(std::abs(u(rng)) / 1.5);
    }
    ts.map_color = rng() % 4 == 0;
    ImagingState is;
    for (auto& t : is.tables) t = random_table(rng, rng() % 3 == 0);
    if (rng() % 3 == 0) {
      ConvolutionFilter& f = rng() % 2 ? is.conv2d : is.separable2d;
      f.enabled = true;
      f.base = static_cast<BaseFormat>(rng() % 6);
      f.width = 1 + static_cast<int>(rng() % 3);
      f.height = 1 + static_cast<int>(rng() % 3);
      f.border_mode = static_cast<BorderMode>(rng() % 3);
      for (int i = 0; i < 4 * f.width * f.height; ++i) f.taps.push_back(u(rng));
      for (int i = 0; i < 4 * f.width; ++i) f.row.push_back(u(rng));
      for (int i = 0; i < 4 * f.height; ++i) f.column.push_back(u(rng));
    }
    Matrix4 m = kIdentity;
    if (rng() % 2)
      for (double& v : m) v = maybe(v);
    const TransferInputs in{ts, is, m};
    RgbaImage<T> img(5, 4);
    for (T& v : img.px) v = static_cast<T>(u(rng));
    const TransferPlan plan = plan_transfer(in, ImageDims::TwoD);
    const RgbaImage<T> a = run_plan(plan, in, img);
    const RgbaImage<T> b = run_every_stage(in, ImageDims::TwoD, img);
    CHECK_MESSAGE(same_bits(a, b), "trial ", trial, " plan ", plan.str(in));
    nonempty_plans += !plan.empty();
    skipped_stages += plan.stages.size() < 7;
  }
  // The random states exercise both full and reduced plans.
  CHECK(nonempty_plans > 300);
  CHECK(skipped_stages > 100);
}

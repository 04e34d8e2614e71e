// Pixel transfer stages driven directly (pipeline/pixel_transfer). Golden values
// are hand derivations written next to each check or independent binary64
// computations in the test.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "pipeline/number/unorm.h"
#include "pipeline/pixel_transfer/color_matrix.h"
#include "pipeline/pixel_transfer/color_table.h"
#include "pipeline/pixel_transfer/convolution.h"
#include "pipeline/pixel_transfer/final_conversion.h"
#include "pipeline/pixel_transfer/formats.h"
#include "pipeline/pixel_transfer/pixel_map.h"
#include "pipeline/pixel_transfer/scale_bias.h"
#include "pipeline/pixel_transfer/transfer_plan.h"
#include "pipeline/pixel_transfer/unpack.h"

using namespace ffsim;
using namespace ffsim::pixel;

namespace {
// 256 RGBA groups in which every component runs through all 256 codes, each in a
// different order: R = k, G = 255 - k, B = (k * 7) mod 256, A = (k + 128) mod 256.
std::vector<std::uint8_t> all_codes_rgba() {
  std::vector<std::uint8_t> d(4 * 256);
  for (int k = 0; k < 256; ++k) {
    d[4 * k] = static_cast<std::uint8_t>(k);
    d[4 * k + 1] = static_cast<std::uint8_t>(255 - k);
    d[4 * k + 2] = static_cast<std::uint8_t>((k * 7) % 256);
    d[4 * k + 3] = static_cast<std::uint8_t>((k + 128) % 256);
  }
  return d;
}
const Matrix4 kIdentity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

template <class T>
RgbaImage<T> one_pixel(T r, T g, T b, T a) {
  RgbaImage<T> img(1, 1);
  img.px = {r, g, b, a};
  return img;
}
}  // namespace

TEST_CASE_TEMPLATE("pixel identity path is exact for all 256 codes of every component", T, float, double) {
  const std::vector<std::uint8_t> d = all_codes_rgba();
  PixelStoreModes modes;
  PixelTransferState ts;
  ImagingState is;
  const TransferInputs in{ts, is, kIdentity};
  const TransferPlan plan = plan_transfer(in, ImageDims::TwoD);
  CHECK(plan.empty());
  CHECK(plan.str(in) == "identity");
  const RgbaImage<T> img = unpack_rgba<T>(d.data(), 256, 1, gl::RGBA, gl::UNSIGNED_BYTE, modes);
  const RgbaImage<T> planned = run_plan(plan, in, img);
  const RgbaImage<T> every = run_every_stage(in, ImageDims::TwoD, img);
  for (int i = 0; i < 4 * 256; ++i) {
    // k -> k/255 (one rounding in T) -> clamp -> rnd(255 x) gives k back.
    CHECK(final_code(planned.px[i], 8) == d[i]);
    CHECK(final_code(every.px[i], 8) == d[i]);
  }
  // Into an RGBA8 texture and back out through ReadPixels packing.
  const TextureImage tex = make_texture_image(planned, gl::RGBA8, InternalFormat{BaseFormat::RGBA, 8}, 0, Profile{});
  for (int i = 0; i < 4 * 256; ++i) CHECK(tex.codes[i] == d[i]);
  std::vector<std::uint8_t> back(4 * 256);
  pack_rgba(every, gl::RGBA, gl::UNSIGNED_BYTE, modes, back.data());
  CHECK(back == d);
}

TEST_CASE("pixel unpack: formats, types and Table 2.6 conversions") {
  PixelStoreModes m;
  m.alignment = 1;
  const std::uint8_t la[2] = {51, 204};  // L = 0.2, A = 0.8
  auto img = unpack_rgba<double>(la, 1, 1, gl::LUMINANCE_ALPHA, gl::UNSIGNED_BYTE, m);
  CHECK(img.px == std::vector<double>{51 / 255.0, 51 / 255.0, 51 / 255.0, 204 / 255.0});
  const std::uint8_t bgr[3] = {1, 2, 3};
  img = unpack_rgba<double>(bgr, 1, 1, gl::BGR, gl::UNSIGNED_BYTE, m);
  CHECK(img.px == std::vector<double>{3 / 255.0, 2 / 255.0, 1 / 255.0, 1.0});  // missing A = 1
  const std::uint8_t g[1] = {255};
  img = unpack_rgba<double>(g, 1, 1, gl::GREEN, gl::UNSIGNED_BYTE, m);
  CHECK(img.px == std::vector<double>{0, 1, 0, 1});
  const std::int8_t sb[1] = {-128};  // (2c+1)/255 = -255/255 = -1 (Table 2.6)
  img = unpack_rgba<double>(sb, 1, 1, gl::ALPHA, gl::BYTE, m);
  CHECK(img.px == std::vector<double>{0, 0, 0, -1});
  const std::uint16_t us[1] = {65535};
  img = unpack_rgba<double>(us, 1, 1, gl::RED, gl::UNSIGNED_SHORT, m);
  CHECK(img.px[0] == 1.0);
  const float fl[1] = {-2.5f};  // floats are taken as they are: unclamped
  img = unpack_rgba<double>(fl, 1, 1, gl::BLUE, gl::FLOAT, m);
  CHECK(img.px[2] == -2.5);
}

TEST_CASE("pixel unpack: ALIGNMENT, ROW_LENGTH, SKIP_PIXELS, SKIP_ROWS and SWAP_BYTES") {
  // 3x2 RGB ubyte image, alignment 4: rows are 9 bytes padded to 12 (GL121 eq. 3.11).
  std::vector<std::uint8_t> buf(24, 0);
  for (int r = 0; r < 2; ++r)
    for (int i = 0; i < 9; ++i) buf[12 * r + i] = static_cast<std::uint8_t>(10 * r + i + 1);
  PixelStoreModes m;  // alignment 4
  auto img = unpack_rgba<double>(buf.data(), 3, 2, gl::RGB, gl::UNSIGNED_BYTE, m);
  CHECK(img.at(0, 1)[0] == 11 / 255.0);  // row 1 starts at byte 12
  CHECK(img.at(2, 1)[2] == 19 / 255.0);
  const ClientLayout L = client_layout(m, 3, 2, 3, 1);
  CHECK(L.row_stride == 12);
  CHECK(L.extent(3, 2) == 21);
  // ROW_LENGTH 4, SKIP_PIXELS 1, SKIP_ROWS 1, alignment 1, LUMINANCE: group (0,0) is byte 4 + 1 = 5.
  std::vector<std::uint8_t> lum(16);
  for (int i = 0; i < 16; ++i) lum[i] = static_cast<std::uint8_t>(i);
  PixelStoreModes s;
  s.alignment = 1;
  s.row_length = 4;
  s.skip_pixels = 1;
  s.skip_rows = 1;
  img = unpack_rgba<double>(lum.data(), 2, 2, gl::LUMINANCE, gl::UNSIGNED_BYTE, s);
  CHECK(img.at(0, 0)[0] == 5 / 255.0);
  CHECK(img.at(1, 0)[0] == 6 / 255.0);
  CHECK(img.at(0, 1)[0] == 9 / 255.0);
  // SWAP_BYTES on UNSIGNED_SHORT: bytes {0x12, 0x34} read as 0x3412 little-endian; swapped 0x1234.
  const std::uint8_t sh[2] = {0x12, 0x34};
  std::uint16_t native;
  std::memcpy(&native, sh, 2);
  PixelStoreModes w;
  w.swap_bytes = true;
  img = unpack_rgba<double>(sh, 1, 1, gl::RED, gl::UNSIGNED_SHORT, w);
  const std::uint16_t swapped = static_cast<std::uint16_t>((native >> 8) | (native << 8));
  CHECK(img.px[0] == swapped / 65535.0);
}

TEST_CASE("pixel pack: Table 4.7 with round half up, LUMINANCE = R + G + B, signed types") {
  CHECK(pack_unsigned(0.5, 8) == 128);  // 127.5 -> 128 (half up)
  CHECK(pack_unsigned(127.4999 / 255, 8) == 127);
  CHECK(pack_unsigned(1.5, 8) == 255);  // clamp
  CHECK(pack_unsigned(-1, 16) == 0);
  CHECK(pack_unsigned(0.5, 32) == 2147483648u);  // (2^32-1)/2 = 2147483647.5 -> up
  CHECK(pack_signed(1.0, 8) == 127);
  CHECK(pack_signed(0.0, 8) == 0);   // (0 - 1)/2 = -0.5 -> 0 (half up)
  CHECK(pack_signed(0.5, 8) == 63);  // (127.5 - 1)/2 = 63.25 -> 63
  RgbaImage<double> img = one_pixel<double>(0.2, 0.3, 0.4, 0.25);
  std::uint8_t out[2] = {0, 0};
  PixelStoreModes m;
  pack_rgba(img, gl::LUMINANCE_ALPHA, gl::UNSIGNED_BYTE, m, out);
  CHECK(out[0] == 230);  // L = 0.9 -> 229.5 -> 230 (the binary64 sum 0.2+0.3+0.4 = 0.9000000000000000222)
  CHECK(out[1] == 64);   // 63.75 -> 64
}

TEST_CASE("pixel scale and bias against hand-computed values, no clamp between stages") {
  // scale 0.5, bias 0.25: 0 -> 0.25 (63.75 -> 64); 255 -> 0.75 (191.25 -> 191);
  // 128 -> 128/510 + 0.25 = 0.50098 (127.75 -> 128).
  RgbaImage<float> img(3, 1);
  img.px = {0, 0, 0, 0, 1, 1, 1, 1, 128 / 255.0f, 128 / 255.0f, 128 / 255.0f, 128 / 255.0f};
  scale_bias(img, {0.5, 0.5, 0.5, 0.5}, {0.25, 0.25, 0.25, 0.25});
  CHECK(final_code(img.px[0], 8) == 64);
  CHECK(final_code(img.px[4], 8) == 191);
  CHECK(final_code(img.px[8], 8) == 128);
  // RED_SCALE 2 makes 200/255 -> 1.5686 (not clamped); post-colour-matrix scale 0.5
  // brings it back to 200/255 -> code 200. A clamp after the first stage would give 128.
  PixelTransferState ts;
  ts.scale = {2, 1, 1, 1};
  ts.post_color_matrix_scale = {0.5, 1, 1, 1};
  ImagingState is;
  const TransferInputs in{ts, is, kIdentity};
  const TransferPlan plan = plan_transfer(in, ImageDims::TwoD);
  CHECK(plan.str(in) == "scale_bias -> post_color_matrix_scale_bias");
  const RgbaImage<float> out = run_plan(plan, in, one_pixel<float>(200 / 255.0f, 0, 0, 1));
  CHECK(out.px[0] > 0.78f);
  CHECK(final_code(out.px[0], 8) == 200);
  CHECK(is_identity_scale_bias({1, 1, 1, 1}, {0, 0, 0, 0}));
  CHECK_FALSE(is_identity_scale_bias({1, 1, 1, 1}, {0, 0, 0, -0.5}));
}

TEST_CASE("pixel MAP_COLOR: clamp, index rnd(c*(size-1)), per-component maps") {
  std::array<std::vector<double>, 4> maps{std::vector<double>{0.0, 0.25, 0.5, 1.0}, std::vector<double>{1.0, 0.0},
                                          std::vector<double>{0.125}, std::vector<double>{0.0, 0.1, 0.2, 0.3, 0.4}};
  // R = -0.5 -> clamp 0 -> index 0 -> 0; G = 0.5 -> 0.5*1 = 0.5 -> floor(1.0) = 1 -> 0.0 (tie up);
  // B = 7 -> clamp 1 -> the only entry 0.125; A = 0.6 -> 0.6*4 = 2.4 -> 2 -> 0.2.
  RgbaImage<double> img = one_pixel<double>(-0.5, 0.5, 7.0, 0.6);
  map_color(img, maps);
  CHECK(img.px == std::vector<double>{0.0, 0.0, 0.125, 0.2});
  // Index rule on the 3-entry-minus-one grid: c = 0.5 with size 4 -> 1.5 -> 2 -> 0.5.
  RgbaImage<float> f = one_pixel<float>(0.5f, 1.0f, 0.0f, 0.875f);
  map_color(f, maps);
  CHECK(f.px[0] == 0.5f);
  CHECK(f.px[1] == 0.0f);
  CHECK(f.px[3] == 0.4f);  // 0.875*4 = 3.5 -> 4 -> 0.4
  CHECK(table_index<float>(std::nanf(""), 256) == 0);
}

TEST_CASE("pixel colour table: each format replaces exactly its components, per-component indices") {
  // A 4-entry table; entry i of each stored component k is (10 i + k + 1)/64 (exact in binary32).
  const auto make = [](BaseFormat b) {
    ColorTable t;
    t.enabled = true;
    t.base = b;
    t.width = 4;
    const int nc = component_count(b);
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < nc; ++k) t.entries.push_back((10.0 * i + k + 1) / 64.0);
    return t;
  };
  const auto e = [](int i, int k) { return (10.0 * i + k + 1) / 64.0; };
  // Input: R = 0 (index 0), G = 1/3 (index 1), B = 1 (index 3), A = 2/3 -> 2 (all exact ties avoided).
  // Unreplaced components keep their value, including out-of-range ones (A = 2/3 here, or 5.0 below).
  struct Case {
    BaseFormat b;
    std::array<double, 4> want;
  };
  const double r = 0, g = 1.0 / 3, bl = 1, a = 2.0 / 3;
  const Case cases[] = {
      {BaseFormat::Alpha, {r, g, bl, e(2, 0)}},
      {BaseFormat::Luminance, {e(0, 0), e(1, 0), e(3, 0), a}},
      {BaseFormat::LuminanceAlpha, {e(0, 0), e(1, 0), e(3, 0), e(2, 1)}},
      {BaseFormat::Intensity, {e(0, 0), e(1, 0), e(3, 0), e(2, 0)}},
      {BaseFormat::RGB, {e(0, 0), e(1, 1), e(3, 2), a}},
      {BaseFormat::RGBA, {e(0, 0), e(1, 1), e(3, 2), e(2, 3)}},
  };
  for (const Case& c : cases) {
    RgbaImage<double> img = one_pixel<double>(r, g, bl, a);
    color_table_lookup(img, make(c.b));
    for (int k = 0; k < 4; ++k) CHECK(img.px[k] == c.want[k]);
  }
  // Components the table does not replace pass unclamped; replaced ones index with clamp01.
  RgbaImage<float> img = one_pixel<float>(-3.0f, 0.0f, 0.0f, 5.0f);
  color_table_lookup(img, make(BaseFormat::RGB));
  CHECK(img.px[0] == static_cast<float>(e(0, 0)));
  CHECK(img.px[3] == 5.0f);
  // Several pixels: each as if looked up alone.
  for (const Case& c : cases) {
    RgbaImage<double> many(5, 1);
    for (std::size_t i = 0; i < many.px.size(); ++i) many.px[i] = static_cast<double>((i * 7) % 11) / 10.0 - 0.05;
    RgbaImage<double> want = many;
    for (int x = 0; x < 5; ++x) {
      RgbaImage<double> alone = one_pixel<double>(want.at(x, 0)[0], want.at(x, 0)[1], want.at(x, 0)[2], want.at(x, 0)[3]);
      color_table_lookup(alone, make(c.b));
      for (int k = 0; k < 4; ++k) want.at(x, 0)[k] = alone.px[static_cast<std::size_t>(k)];
    }
    color_table_lookup(many, make(c.b));
    CHECK(many.px == want.px);
  }
  // Disabled or empty: no-op.
  ColorTable off = make(BaseFormat::RGBA);
  off.enabled = false;
  RgbaImage<float> same = one_pixel<float>(0.3f, 0.3f, 0.3f, 0.3f);
  color_table_lookup(same, off);
  CHECK(same.px[0] == 0.3f);
}

TEST_CASE("pixel colour table entries: clamp01(c * scale + bias), components per Table 3.15") {
  ColorTable t;
  t.base = BaseFormat::LuminanceAlpha;
  t.width = 2;
  t.scale = {2, 1, 1, 0.5};
  t.bias = {-0.5, 0, 0, 0.25};
  RgbaImage<float> g(2, 1);
  g.px = {0.25f, 0.9f, 0.9f, 1.0f, 1.0f, 0.0f, 0.0f, 3.0f};
  set_table_entries(t, g);
  // L from R: 0.25*2 - 0.5 = 0 ; 1*2 - 0.5 = 1.5 -> 1. A: 1*0.5 + 0.25 = 0.75 ; 3*0.5 + 0.25 = 1.75 -> 1.
  CHECK(t.entries == std::vector<double>{0.0, 0.75, 1.0, 1.0});
}

namespace {
// Independent binary64 convolution straight from the GL121 formulas (sums in the
// same n-outer, m-inner order so that the binary64 stage must match bit for bit).
std::vector<double> reference_convolution(const RgbaImage<double>& img, const std::vector<double>& taps, int wf,
                                          int hf, BorderMode mode, const std::array<double, 4>& border, int& ow,
                                          int& oh) {
  ow = mode == BorderMode::Reduce ? img.width - wf + 1 : img.width;
  oh = mode == BorderMode::Reduce ? img.height - hf + 1 : img.height;
  std::vector<double> out;
  for (int j = 0; j < oh; ++j)
    for (int i = 0; i < ow; ++i)
      for (int c = 0; c < 4; ++c) {
        double sum = 0;
        for (int n = 0; n < wf; ++n)
          for (int m = 0; m < hf; ++m) {
            int x = i + n, y = j + m;
            if (mode != BorderMode::Reduce) {
              x -= wf / 2;
              y -= hf / 2;
            }
            double v;
            if (x >= 0 && y >= 0 && x < img.width && y < img.height) v = img.at(x, y)[c];
            else if (mode == BorderMode::ConstantBorder) v = border[c];
            else v = img.at(std::min(std::max(x, 0), img.width - 1), std::min(std::max(y, 0), img.height - 1))[c];
            sum += v * taps[4 * (m * wf + n) + c];
          }
        out.push_back(sum);
      }
  return out;
}
}  // namespace

TEST_CASE("pixel convolution against a direct binary64 convolution for each border mode") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 2.0);
  RgbaImage<double> img(7, 5);
  for (double& v : img.px) v = u(rng);
  RgbaImage<float> imgf(7, 5);
  for (std::size_t i = 0; i < img.px.size(); ++i) imgf.px[i] = static_cast<float>(img.px[i]);
  for (BorderMode mode : {BorderMode::Reduce, BorderMode::ConstantBorder, BorderMode::ReplicateBorder}) {
    for (FilterKind kind : {FilterKind::OneD, FilterKind::TwoD, FilterKind::Separable}) {
      ConvolutionFilter f;
      f.base = BaseFormat::RGBA;
      f.width = 3;
      f.height = kind == FilterKind::OneD ? 1 : 3;
      f.border_mode = mode;
      f.border_color = {0.5, -0.25, 2.0, 1.0};
      std::vector<double> taps(4 * f.width * f.height);
      if (kind == FilterKind::Separable) {
        for (int i = 0; i < 4 * f.width; ++i) f.row.push_back(static_cast<float>(u(rng)));
        for (int i = 0; i < 4 * f.height; ++i) f.column.push_back(static_cast<float>(u(rng)));
        for (int m = 0; m < f.height; ++m)
          for (int n = 0; n < f.width; ++n)
            for (int c = 0; c < 4; ++c) taps[4 * (m * f.width + n) + c] = f.row[4 * n + c] * f.column[4 * m + c];
      } else {
        for (double& t : taps) t = static_cast<float>(u(rng));
        f.taps = taps;
      }
      RgbaImage<double> src = img;
      if (kind == FilterKind::OneD) src.height = 1, src.px.resize(4 * 7);
      int ow = 0, oh = 0;
      const std::vector<double> ref = reference_convolution(src, taps, f.width, f.height, mode, f.border_color, ow, oh);
      const RgbaImage<double> got = convolve(src, f, kind);
      REQUIRE(got.width == ow);
      REQUIRE(got.height == oh);
      RgbaImage<float> srcf = imgf;
      if (kind == FilterKind::OneD) srcf.height = 1, srcf.px.resize(4 * 7);
      const RgbaImage<float> gotf = convolve(srcf, f, kind);
      double max_err = 0;
      for (std::size_t i = 0; i < ref.size(); ++i) {
        if (kind == FilterKind::Separable) CHECK(got.px[i] == doctest::Approx(ref[i]).epsilon(1e-14));
        else CHECK(got.px[i] == ref[i]);  // same operations in the same order in binary64
        max_err = std::max(max_err, std::abs(static_cast<double>(gotf.px[i]) - ref[i]));
      }
      // binary32: 9 products and sums of magnitudes < 4: error well below 1e-5 (1/100000 of full scale).
      CHECK(max_err < 1e-5);
    }
  }
}

TEST_CASE("pixel convolution: filter formats convolve only their components, REDUCE keeps the centre value") {
  RgbaImage<double> img(3, 3);
  for (int i = 0; i < 9; ++i)
    for (int c = 0; c < 4; ++c) img.px[4 * i + c] = i + 10 * c;
  ConvolutionFilter f;
  f.base = BaseFormat::Alpha;
  f.width = f.height = 3;
  f.taps.assign(4 * 9, 0.0);
  for (int i = 0; i < 9; ++i) f.taps[4 * i + 3] = 1.0;  // box filter on A
  const RgbaImage<double> out = convolve(img, f, FilterKind::TwoD);
  REQUIRE(out.width == 1);
  CHECK(out.px[0] == 4);                     // R of the centre pixel (index 4)
  CHECK(out.px[2] == 24);                    // B of the centre
  CHECK(out.px[3] == 9 * 30 + (0 + 8) * 4.5);  // sum of A = sum(i + 30) = 270 + 36
  // make_filter_taps: LUMINANCE takes R (scaled and biased, no clamp) into R, G, B.
  ConvolutionFilter lf;
  lf.base = BaseFormat::Luminance;
  lf.filter_scale = {4, 1, 1, 1};
  lf.filter_bias = {-1, 0, 0, 0};
  RgbaImage<double> g = one_pixel<double>(1.0, 0.25, 0.5, 0.75);
  CHECK(make_filter_taps(g, lf) == std::vector<double>{3, 3, 3, 0});
}

TEST_CASE("pixel colour matrix against a binary64 product") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int trial = 0; trial < 200; ++trial) {
    Matrix4 m;
    for (double& v : m) v = u(rng);
    const std::array<double, 4> s{u(rng), u(rng), u(rng), u(rng)}, b{u(rng), u(rng), u(rng), u(rng)};
    const std::array<double, 4> in{u(rng), u(rng), u(rng), u(rng)};
    RgbaImage<double> d = one_pixel<double>(in[0], in[1], in[2], in[3]);
    RgbaImage<float> f = one_pixel<float>(static_cast<float>(in[0]), static_cast<float>(in[1]),
                                          static_cast<float>(in[2]), static_cast<float>(in[3]));
    color_matrix(d, m, s, b);
    color_matrix(f, m, s, b);
    for (int r = 0; r < 4; ++r) {
      // Row r of the column-major matrix: m[r], m[4+r], m[8+r], m[12+r].
      const double ref = (m[r] * in[0] + m[4 + r] * in[1] + m[8 + r] * in[2] + m[12 + r] * in[3]) * s[r] + b[r];
      CHECK(d.px[r] == ref);  // same association in binary64
      CHECK(std::abs(f.px[r] - ref) < 1e-5);
    }
  }
  CHECK(is_identity_matrix(kIdentity));
  Matrix4 nid = kIdentity;
  nid[12] = 0.5;
  CHECK_FALSE(is_identity_matrix(nid));
}

TEST_CASE("pixel texture conversion: base formats pick components, sized widths, float profiles") {
  RgbaImage<float> img = one_pixel<float>(0.2f, 0.4f, 0.6f, 0.8f);
  Profile p;  // geforce256: texture_bits 8
  TextureImage t = make_texture_image(img, gl::LUMINANCE_ALPHA, InternalFormat{BaseFormat::LuminanceAlpha, 0}, 0, p);
  CHECK(t.bits == 8);
  CHECK(t.codes == std::vector<std::uint16_t>{51, 204});  // R -> L, A
  t = make_texture_image(img, gl::INTENSITY, InternalFormat{BaseFormat::Intensity, 0}, 0, p);
  CHECK(t.codes == std::vector<std::uint16_t>{51});
  t = make_texture_image(img, gl::RGBA4, InternalFormat{BaseFormat::RGBA, 4}, 0, p);
  CHECK(t.bits == 4);
  // 0.2*15 = 3 (binary32 0.2 is slightly above: 3.0000000447 -> 3), 6, 9, 12.
  CHECK(t.codes == std::vector<std::uint16_t>{3, 6, 9, 12});
  t = make_texture_image(img, gl::ALPHA, InternalFormat{BaseFormat::Alpha, 0}, 0, p);
  CHECK(t.codes == std::vector<std::uint16_t>{204});
  Profile ideal = *find_builtin_profile("ideal");
  RgbaImage<double> dimg = one_pixel<double>(-0.5, 0.4, 1.5, 0.8);
  t = make_texture_image(dimg, gl::RGB, InternalFormat{BaseFormat::RGB, 0}, 0, ideal);
  CHECK(t.codes.empty());
  CHECK(t.values == std::vector<double>{0.0, 0.4, 1.0});  // clamp01 only
  Profile f32 = *find_builtin_profile("float32");
  t = make_texture_image(dimg, gl::RGB, InternalFormat{BaseFormat::RGB, 0}, 0, f32);
  CHECK(t.values[1] == static_cast<double>(0.4f));
  CHECK(texture_storage_bits(InternalFormat{BaseFormat::RGB, 0}, *find_builtin_profile("rgba12")) == 12);
}

TEST_CASE("pixel table index is floor(x + 1/2) evaluated in the transfer precision") {
  // c = 1/2 - 2^-25 (exact in binary32), W = 2: x = c. In binary32, x + 1/2 = 1 - 2^-25 is
  // a tie between 1 - 2^-24 and 1 and rounds to even (1.0), so the index is 1; in
  // binary64 the sum is exact and the index is 0 (docs/numerics.md §7.3).
  const float c = 0.5f - 0x1p-25f;
  CHECK(table_index<float>(c, 2) == 1);
  CHECK(table_index<double>(static_cast<double>(c), 2) == 0);
  // Exact half-steps round up: c = 1/2 with W = 2 gives index 1 in both.
  CHECK(table_index<float>(0.5f, 2) == 1);
  CHECK(table_index<double>(0.5, 2) == 1);
  CHECK(table_index<float>(2.0f, 4096) == 4095);
  CHECK(table_index<float>(-1.0f, 4096) == 0);
}

TEST_CASE("pixel mixed-width sized texture formats round each component at its own width") {
  Profile p;
  RgbaImage<float> img = one_pixel<float>(0.5f, 0.2f, 0.6f, 0.6f);
  // RGB5_A1: storage 5 bits; R = rnd(15.5) = 16, G = rnd(6.2) = 6, B = rnd(18.6) = 19;
  // A rounds at 1 bit (rnd(0.6) = 1) and is stored as 31 (1 * 31/1, exact).
  TextureImage t = make_texture_image(img, gl::RGB5_A1, *texture_internal_format(gl::RGB5_A1), 0, p);
  CHECK(t.bits == 5);
  CHECK(t.codes == std::vector<std::uint16_t>{16, 6, 19, 31});
  // R3_G3_B2: storage lcm(3, 2) = 6 bits; R = rnd(3.5) = 4 -> 4 * 9 = 36; G = rnd(1.4) = 1 -> 9;
  // B = rnd(0.6 * 3 = 1.8) = 2 -> 2 * 21 = 42.
  t = make_texture_image(img, gl::R3_G3_B2, *texture_internal_format(gl::R3_G3_B2), 0, p);
  CHECK(t.bits == 6);
  CHECK(t.codes == std::vector<std::uint16_t>{36, 9, 42});
  // Uniform sized formats are unaffected: RGBA4 of 0.6 = rnd(9) = 9.
  t = make_texture_image(img, gl::RGBA4, *texture_internal_format(gl::RGBA4), 0, p);
  CHECK(t.codes[3] == 9);
}

// Every byte of both one-byte types through unpack_rgba (which looks them up in a
// table of 256) against GL121 Table 2.6 written out here: c/255 for UNSIGNED_BYTE,
// (2c + 1)/255 for BYTE, each one division in T, compared bit for bit.
TEST_CASE_TEMPLATE("pixel unpack: every UNSIGNED_BYTE and BYTE value is Table 2.6's conversion", T, float, double) {
  std::vector<std::uint8_t> bytes(256);
  for (int b = 0; b < 256; ++b) bytes[static_cast<std::size_t>(b)] = static_cast<std::uint8_t>(b);
  PixelStoreModes m;
  m.alignment = 1;
  const RgbaImage<T> u = unpack_rgba<T>(bytes.data(), 256, 1, gl::ALPHA, gl::UNSIGNED_BYTE, m);
  const RgbaImage<T> s = unpack_rgba<T>(bytes.data(), 256, 1, gl::ALPHA, gl::BYTE, m);
  for (int b = 0; b < 256; ++b) {
    const T eu = static_cast<T>(b) / T(255);
    const T es = static_cast<T>(2 * static_cast<std::int8_t>(b) + 1) / T(255);
    CHECK(std::memcmp(&u.px[4 * static_cast<std::size_t>(b) + 3], &eu, sizeof(T)) == 0);
    CHECK(std::memcmp(&s.px[4 * static_cast<std::size_t>(b) + 3], &es, sizeof(T)) == 0);
    CHECK(u.px[4 * static_cast<std::size_t>(b)] == T(0));  // R, G, B of ALPHA data: 0
  }
}

TEST_CASE_TEMPLATE("final conversion: store_texels writes final_code of each component's RGBA slot, at every width", T, float, double) {
  // An independent statement of §3.8.1 for fixed profiles: stored component k
  // of a texel is the code of the RGBA value its base format takes (Table 3.15),
  // rounded at the component's width and widened to the level's (mixed-width
  // formats), at (x0 + x, y0 + y); everything else of the level is left alone.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.25, 1.25);
  const GLenum kInternalFormats[] = {gl::ALPHA8, gl::LUMINANCE, gl::LUMINANCE12_ALPHA4, gl::LUMINANCE_ALPHA, gl::INTENSITY,
                                     gl::RGB8, gl::R3_G3_B2, gl::RGB5, gl::RGBA8, gl::RGB5_A1, gl::RGB10_A2, gl::RGBA12,
                                     gl::RGBA16, gl::RGBA, 3, 4};
  const char* profiles[] = {"geforce256", "rgba10", "rgba12"};
  for (int trial = 0; trial < 300; ++trial) {
    CAPTURE(trial);
    const Profile& p = *find_builtin_profile(profiles[rng() % 3]);
    const GLenum internal = kInternalFormats[rng() % std::size(kInternalFormats)];
    CAPTURE(internal);
    const InternalFormat f = *texture_internal_format(internal);
    const int w = static_cast<int>(rng() % 7), h = 1 + static_cast<int>(rng() % 4);  // (w = 0: nothing stored)
    RgbaImage<T> img(w, h);
    for (auto& v : img.px) v = static_cast<T>(rng() % 8 == 0 ? (rng() % 2 ? 0.0 : 1.0) : u(rng));
    const int x0 = static_cast<int>(rng() % 3), y0 = static_cast<int>(rng() % 2);
    TextureImage level = texture_level(w + x0 + 2, h + y0 + 1, internal, f, 0, p);
    for (auto& c : level.codes) c = static_cast<std::uint16_t>(rng() & ((1u << level.bits) - 1));
    TextureImage expect = level;
    const int nc = component_count(level.base);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int k = 0; k < nc; ++k) {
          const int width = f.sized_bits == level.bits && f.component_bits[static_cast<std::size_t>(k)] > 0
                                ? f.component_bits[static_cast<std::size_t>(k)]
                                : level.bits;
          const std::uint32_t code = final_code(img.at(x, y)[rgba_component_for(level.base, k)], width);
          expect.codes[(static_cast<std::size_t>(y0 + y) * static_cast<std::size_t>(level.width) + static_cast<std::size_t>(x0 + x)) *
                           static_cast<std::size_t>(nc) + static_cast<std::size_t>(k)] =
              static_cast<std::uint16_t>(unorm_convert(code, width, level.bits));
        }
    store_texels(img, level, x0, y0, p);
    CHECK(level.codes == expect.codes);
  }
}

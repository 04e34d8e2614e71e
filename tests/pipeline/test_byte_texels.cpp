// Texture uploads of one-byte data by table (pipeline/pixel_transfer/byte_texels.h):
// over random component-wise transfer states (scale and bias, colour maps, colour
// tables of every base format, post-colour-matrix scale, bias and table), every
// client format, UNSIGNED_BYTE and BYTE, every sized and unsized internal format
// (mixed widths included), the fixed profiles, the unpack modes and sub-image
// positions, store_byte_texels writes exactly what store_texels(run_plan(
// unpack_rgba(...))) writes, and leaves the rest of the level alone.
#include <doctest/doctest.h>

#include <random>
#include <vector>

#include "color_table_util.h"
#include "pipeline/pixel_transfer/byte_texels.h"
#include "pipeline/pixel_transfer/final_conversion.h"
#include "pipeline/pixel_transfer/formats.h"
#include "pipeline/pixel_transfer/unpack.h"

using namespace ffsim;
using namespace ffsim::pixel;
using ffsim::pixel::test::random_table;

namespace {

const Matrix4 kIdentity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

const GLenum kFormats[] = {gl::RED, gl::GREEN, gl::BLUE, gl::ALPHA, gl::LUMINANCE,
                           gl::LUMINANCE_ALPHA, gl::RGB, gl::BGR, gl::RGBA, gl::BGRA};
const GLenum kInternal[] = {gl::ALPHA, gl::ALPHA4, gl::ALPHA8, gl::ALPHA12, gl::ALPHA16, gl::LUMINANCE,
                            gl::LUMINANCE8, gl::LUMINANCE_ALPHA, gl::LUMINANCE6_ALPHA2, gl::LUMINANCE12_ALPHA4,
                            gl::INTENSITY, gl::INTENSITY8, gl::INTENSITY12, gl::RGB, gl::R3_G3_B2, gl::RGB5,
                            gl::RGB8, gl::RGB10, gl::RGBA, gl::RGBA2, gl::RGB5_A1, gl::RGBA8, gl::RGB10_A2,
                            gl::RGBA12, gl::RGBA16, 3, 4};

}  // namespace

TEST_CASE_TEMPLATE("byte texels: the tables give the generic path's codes", T, float, double) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  const auto maybe = [&](double identity_value) { return rng() % 2 ? identity_value : u(rng); };
  const char* profiles[] = {"geforce256", "rgba10", "rgba12"};
  int componentwise = 0, other = 0, tables = 0, stages = 0, widened = 0;
  for (int trial = 0; trial < 600; ++trial) {
    CAPTURE(trial);
    const Profile& p = *find_builtin_profile(profiles[rng() % 3]);
    PixelTransferState ts;
    ImagingState is;
    Matrix4 m = kIdentity;
    // One trial in four: the initial transfer state (an identity plan; rows of
    // 8-bit levels from UNSIGNED_BYTE data are widened, not looked up).
    const bool initial = rng() % 4 == 0;
    for (int c = 0; c < 4 && !initial; ++c) {
      ts.scale[c] = maybe(1);
      ts.bias[c] = maybe(0);
      ts.post_color_matrix_scale[c] = maybe(1);
      ts.post_color_matrix_bias[c] = maybe(0);
      ts.color_maps[c].clear();
      for (int i = 0; i < 1 + static_cast<int>(rng() % 8); ++i) ts.color_maps[c].push_back(std::abs(u(rng)) / 1.5);
    }
    ts.map_color = !initial && rng() % 2 == 0;
    const bool color_on = !initial && rng() % 2 == 0;
    if (!initial) is.table(TableSlot::Color) = random_table(rng, color_on);
    const bool post_on = !initial && rng() % 2 == 0;
    if (!initial) is.table(TableSlot::PostColorMatrix) = random_table(rng, post_on);
    // One trial in six: a colour matrix or a convolution, which the path refuses.
    const int mixing = initial ? 2 : static_cast<int>(rng() % 12);
    if (mixing == 0) m[1] = 0.25;
    if (mixing == 1) {
      is.conv2d.enabled = true;
      is.conv2d.width = is.conv2d.height = 1;
      is.conv2d.border_mode = BorderMode::ConstantBorder;
      is.conv2d.taps = {0.5, 0.5, 0.5, 0.5};
    }
    const TransferInputs in{ts, is, m};
    const TransferPlan plan = plan_transfer(in, ImageDims::TwoD);
    const bool cw = plan_is_componentwise(plan);
    CHECK(cw == (mixing > 1));
    if (!cw) {
      ++other;
      continue;
    }
    ++componentwise;
    stages += static_cast<int>(plan.stages.size());
    tables += plan.has(Stage::ColorTable) || plan.has(Stage::PostColorMatrixColorTable);

    // Half the initial-state trials upload a format into the 8-bit internal
    // format of the same components (what the paper's traces do), or of the same
    // components in another order (BGRA: identity tables, not widened).
    static const std::pair<GLenum, GLenum> kMatched[] = {
        {gl::RGBA, gl::RGBA8},           {gl::RGB, gl::RGB8}, {gl::ALPHA, gl::ALPHA8}, {gl::LUMINANCE, gl::LUMINANCE8},
        {gl::LUMINANCE_ALPHA, gl::LUMINANCE_ALPHA}, {gl::BGRA, gl::RGBA8}, {gl::BGR, gl::RGB8}};
    const bool matched = initial && rng() % 2 == 0;
    const auto pair = kMatched[rng() % std::size(kMatched)];
    const GLenum format = matched ? pair.first : kFormats[rng() % std::size(kFormats)];
    const GLenum type = !matched && rng() % 3 == 0 ? gl::BYTE : gl::UNSIGNED_BYTE;
    const GLenum internal = matched ? pair.second : kInternal[rng() % std::size(kInternal)];
    CAPTURE(format);
    CAPTURE(type);
    CAPTURE(internal);
    const InternalFormat f = *texture_internal_format(internal);
    const int w = 1 + static_cast<int>(rng() % 9), h = 1 + static_cast<int>(rng() % 5);
    PixelStoreModes modes;
    modes.alignment = 1 << (rng() % 4);
    modes.row_length = rng() % 3 == 0 ? w + static_cast<int>(rng() % 4) : 0;
    modes.skip_pixels = static_cast<int>(rng() % 3);
    modes.skip_rows = static_cast<int>(rng() % 3);
    const int n = color_format_components(format);
    std::vector<unsigned char> data(client_layout(modes, w, h, n, 1).extent(w, h));
    for (auto& b : data) b = static_cast<unsigned char>(rng());
    // A level larger than the image, with random codes, and the image at (x0, y0).
    const int x0 = static_cast<int>(rng() % 4), y0 = static_cast<int>(rng() % 3);
    TextureImage level = texture_level(w + x0 + static_cast<int>(rng() % 3), h + y0 + 1, internal, f, 0, p);
    for (auto& c : level.codes) c = static_cast<std::uint16_t>(rng() & ((1u << level.bits) - 1));
    TextureImage expect = level;
    store_texels(run_plan(plan, in, unpack_rgba<T>(data.data(), w, h, format, type, modes)), expect, x0, y0, p);
    const ByteTexelTables tab = byte_texel_tables<T>(format, type, plan, in, level, p);
    store_byte_texels(tab, data.data(), w, h, modes, level, x0, y0);
    CHECK(level.codes == expect.codes);
    bool identity = tab.group_bytes == tab.components;  // (store_byte_texels' widening rows)
    for (int k = 0; k < tab.components && identity; ++k) {
      identity = tab.element[static_cast<std::size_t>(k)] == k;
      for (int v = 0; v < 256 && identity; ++v) identity = tab.code[static_cast<std::size_t>(k)][static_cast<std::size_t>(v)] == v;
    }
    widened += identity;
  }
  CHECK(widened > 10);
  // The trials covered both outcomes, plans with stages and with tables.
  CHECK(componentwise > 400);
  CHECK(other > 50);
  CHECK(stages > 1000);
  CHECK(tables > 200);
}

TEST_CASE("byte texels: every byte of an identity upload to an 8-bit level is its own code") {
  // Table 2.6 and §3.8.1: c/255 rounded back to 8 bits is c (hand derivation:
  // c/255·255 is within 2^-20 of c in binary32, far from the half-way points).
  const Profile& p = *find_builtin_profile("geforce256");
  PixelTransferState ts;
  ImagingState is;
  const TransferInputs in{ts, is, kIdentity};
  const TransferPlan plan = plan_transfer(in, ImageDims::TwoD);
  REQUIRE(plan_is_componentwise(plan));
  std::vector<unsigned char> data(4 * 256);
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<unsigned char>(i / 4 ^ (i % 4) * 85);
  TextureImage level = texture_level(256, 1, gl::RGBA8, *texture_internal_format(gl::RGBA8), 0, p);
  const ByteTexelTables tab = byte_texel_tables<float>(gl::RGBA, gl::UNSIGNED_BYTE, plan, in, level, p);
  store_byte_texels(tab, data.data(), 256, 1, PixelStoreModes{}, level, 0, 0);
  for (std::size_t i = 0; i < data.size(); ++i) CHECK(level.codes[i] == data[i]);
  // ALPHA data into an RGBA level: R, G, B are the constant 0, A the byte.
  const ByteTexelTables alpha = byte_texel_tables<float>(gl::ALPHA, gl::UNSIGNED_BYTE, plan, in, level, p);
  CHECK(alpha.element == std::array<int, 4>{-1, -1, -1, 0});
  store_byte_texels(alpha, data.data(), 256, 1, PixelStoreModes{}, level, 0, 0);
  for (std::size_t x = 0; x < 256; ++x) {
    CHECK(level.codes[4 * x] == 0);
    CHECK(level.codes[4 * x + 3] == data[x]);
  }
}

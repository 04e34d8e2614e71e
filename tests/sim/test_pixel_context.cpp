// The pixel path through the Context: GL errors (state unchanged), pixel
// rectangles (placement, zoom, overlap), ReadPixels, texture images, stencil.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "sim/context.h"

using namespace ffsim;

namespace {
Profile geforce() { return *find_builtin_profile("geforce256"); }
// Sets the colour of pixel (x, y) to 8-bit codes.
void put(Context& ctx, int x, int y, std::array<std::uint16_t, 4> c) {
  for (int k = 0; k < 4; ++k) ctx.framebuffer().codes()[4 * ctx.framebuffer().index(x, y) + k] = c[k];
}
std::array<std::uint16_t, 4> get(const Context& ctx, int x, int y) {
  const auto& c = ctx.framebuffer().codes();
  const std::size_t i = 4 * ctx.framebuffer().index(x, y);
  return {c[i], c[i + 1], c[i + 2], c[i + 3]};
}
}  // namespace

TEST_CASE("pixel GL errors: pixel store, transfer, map, with state unchanged") {
  Context ctx(geforce(), 8, 8);
  ctx.pixelStorei(gl::UNPACK_ALIGNMENT, 3);
  CHECK(ctx.getError() == gl::INVALID_VALUE);
  CHECK(ctx.pixel_store().unpack.alignment == 4);
  ctx.pixelStorei(gl::PACK_ROW_LENGTH, -1);
  CHECK(ctx.getError() == gl::INVALID_VALUE);
  CHECK(ctx.pixel_store().pack.row_length == 0);
  ctx.pixelStorei(gl::RED_SCALE, 1);
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  ctx.pixelStoref(gl::UNPACK_ALIGNMENT, 8.0);
  ctx.pixelStorei(gl::PACK_SWAP_BYTES, 1);
  CHECK(ctx.getError() == gl::NO_ERROR);
  CHECK(ctx.pixel_store().unpack.alignment == 8);
  CHECK(ctx.pixel_store().pack.swap_bytes);
  ctx.pixelTransferf(gl::ZOOM_X, 2.0);
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  ctx.pixelTransferf(gl::POST_COLOR_MATRIX_ALPHA_BIAS, 0.25);
  ctx.pixelTransferf(gl::POST_CONVOLUTION_GREEN_SCALE, 3.0);
  CHECK(ctx.pixel_transfer().post_color_matrix_bias[3] == 0.25);
  CHECK(ctx.pixel_transfer().post_convolution_scale[1] == 3.0);
  const double v[3] = {0.5, 2.0, -1.0};
  ctx.pixelMapfv(gl::PIXEL_MAP_R_TO_R, 0, v);
  CHECK(ctx.getError() == gl::INVALID_VALUE);
  ctx.pixelMapfv(gl::PIXEL_MAP_S_TO_S, 3, v);  // index maps need a power of two
  CHECK(ctx.getError() == gl::INVALID_VALUE);
  ctx.pixelMapfv(gl::RED_SCALE, 1, v);
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  CHECK(ctx.pixel_transfer().color_maps[0] == std::vector<double>{0.0});
  ctx.pixelMapfv(gl::PIXEL_MAP_R_TO_R, 3, v);  // colour map entries clamped to [0,1]
  CHECK(ctx.getError() == gl::NO_ERROR);
  CHECK(ctx.pixel_transfer().color_maps[0] == std::vector<double>{0.5, 1.0, 0.0});
}

TEST_CASE("pixel GL errors: colour tables and convolution filters") {
  Context ctx(geforce(), 8, 8);
  const float data[8] = {0, 0.5f, 1, 0.25f, 1, 0, 0, 0};
  ctx.colorTable(gl::TEXTURE_2D, gl::RGBA, 2, gl::RGBA, gl::FLOAT, data);
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  ctx.colorTable(gl::COLOR_TABLE, 4, 2, gl::RGBA, gl::FLOAT, data);  // legacy 1..4 not a table format
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  ctx.colorTable(gl::COLOR_TABLE, gl::RGBA, 3, gl::RGBA, gl::FLOAT, data);
  CHECK(ctx.getError() == gl::INVALID_VALUE);
  ctx.colorTable(gl::COLOR_TABLE, gl::RGBA, 8192, gl::RGBA, gl::FLOAT, data);
  CHECK(ctx.getError() == gl::TABLE_TOO_LARGE);
  ctx.colorTable(gl::COLOR_TABLE, gl::RGBA, 2, gl::STENCIL_INDEX, gl::FLOAT, data);
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  ctx.colorTable(gl::COLOR_TABLE, gl::RGBA, 2, gl::RGBA, gl::UNSIGNED_BYTE_3_3_2, data);
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  CHECK(ctx.imaging().table(pixel::TableSlot::Color).width == 0);
  const double sc[4] = {2, 2, 2, 2};
  ctx.colorTableParameterfv(gl::COLOR_TABLE, gl::COLOR_TABLE_WIDTH, sc);
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  ctx.colorTableParameterfv(gl::COLOR_TABLE, gl::COLOR_TABLE_SCALE, sc);
  ctx.colorTable(gl::COLOR_TABLE, gl::LUMINANCE, 2, gl::RGBA, gl::FLOAT, data);
  CHECK(ctx.getError() == gl::NO_ERROR);
  // L from R of each entry: clamp01(0*2) = 0, clamp01(1*2) = 1.
  CHECK(ctx.imaging().table(pixel::TableSlot::Color).entries == std::vector<double>{0.0, 1.0});

  ctx.convolutionFilter2D(gl::CONVOLUTION_1D, gl::RGBA, 1, 1, gl::RGBA, gl::FLOAT, data);
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  ctx.convolutionFilter2D(gl::CONVOLUTION_2D, gl::RGBA, 10, 1, gl::RGBA, gl::FLOAT, data);
  CHECK(ctx.getError() == gl::INVALID_VALUE);
  ctx.convolutionFilter1D(gl::CONVOLUTION_1D, 0x1234, 1, gl::RGBA, gl::FLOAT, data);
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  CHECK(ctx.imaging().conv2d.width == 0);
  ctx.convolutionParameteri(gl::CONVOLUTION_2D, gl::CONVOLUTION_BORDER_MODE, gl::RGBA);
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  ctx.convolutionParameteri(gl::COLOR_TABLE, gl::CONVOLUTION_BORDER_MODE, gl::REDUCE);
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  CHECK(ctx.imaging().conv2d.border_mode == pixel::BorderMode::Reduce);
  ctx.convolutionParameteri(gl::CONVOLUTION_2D, gl::CONVOLUTION_BORDER_MODE, gl::REPLICATE_BORDER);
  CHECK(ctx.getError() == gl::NO_ERROR);
  CHECK(ctx.imaging().conv2d.border_mode == pixel::BorderMode::ReplicateBorder);
  // Enables and isEnabled.
  for (GLenum cap : {gl::COLOR_TABLE, gl::POST_CONVOLUTION_COLOR_TABLE, gl::POST_COLOR_MATRIX_COLOR_TABLE,
                     gl::CONVOLUTION_1D, gl::CONVOLUTION_2D, gl::SEPARABLE_2D}) {
    CHECK_FALSE(ctx.isEnabled(cap));
    ctx.enable(cap);
    CHECK(ctx.isEnabled(cap));
    ctx.disable(cap);
    CHECK_FALSE(ctx.isEnabled(cap));
  }
  CHECK(ctx.getError() == gl::NO_ERROR);
}

TEST_CASE("pixel GL errors: texture images, pixel rectangles") {
  Context ctx(geforce(), 8, 8);
  std::vector<std::uint8_t> d(4 * 16 * 16, 7);
  ctx.texImage2D(gl::TEXTURE_1D, 0, gl::RGBA, 4, 4, 0, gl::RGBA, gl::UNSIGNED_BYTE, d.data());
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  ctx.texImage2D(gl::TEXTURE_2D, -1, gl::RGBA, 4, 4, 0, gl::RGBA, gl::UNSIGNED_BYTE, d.data());
  CHECK(ctx.getError() == gl::INVALID_VALUE);
  ctx.texImage2D(gl::TEXTURE_2D, 0, 0x1234, 4, 4, 0, gl::RGBA, gl::UNSIGNED_BYTE, d.data());
  CHECK(ctx.getError() == gl::INVALID_VALUE);  // GL121: bad internalformat is INVALID_VALUE
  ctx.texImage2D(gl::TEXTURE_2D, 0, gl::RGBA, 3, 4, 0, gl::RGBA, gl::UNSIGNED_BYTE, d.data());
  CHECK(ctx.getError() == gl::INVALID_VALUE);
  ctx.texImage2D(gl::TEXTURE_2D, 0, gl::RGBA, 4, 4, 2, gl::RGBA, gl::UNSIGNED_BYTE, d.data());
  CHECK(ctx.getError() == gl::INVALID_VALUE);
  ctx.texImage2D(gl::TEXTURE_2D, 0, gl::RGBA, 4, 4, 0, gl::DEPTH_COMPONENT, gl::UNSIGNED_BYTE, d.data());
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  ctx.texImage2D(gl::TEXTURE_2D, 0, gl::RGBA, 4, 4, 0, gl::RGBA, gl::DOUBLE, d.data());
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  ctx.texSubImage2D(gl::TEXTURE_2D, 0, 0, 0, 1, 1, gl::RGBA, gl::UNSIGNED_BYTE, d.data());
  CHECK(ctx.getError() == gl::INVALID_OPERATION);  // level 0 not specified yet
  CHECK(ctx.bound_texture(0, gl::TEXTURE_2D).levels.empty());
  CHECK(ctx.bound_texture(0, gl::TEXTURE_2D).version == 0);
  ctx.texImage2D(gl::TEXTURE_2D, 0, gl::RGBA, 6, 6, 1, gl::RGBA, gl::UNSIGNED_BYTE, d.data());  // 4 + 2 border
  CHECK(ctx.getError() == gl::NO_ERROR);
  ctx.texSubImage2D(gl::TEXTURE_2D, 0, 4, 0, 2, 1, gl::RGBA, gl::UNSIGNED_BYTE, d.data());  // 4+2 > 6-1
  CHECK(ctx.getError() == gl::INVALID_VALUE);
  ctx.texSubImage2D(gl::TEXTURE_2D, 0, -1, -1, 6, 6, gl::RGBA, gl::UNSIGNED_BYTE, d.data());  // border included
  CHECK(ctx.getError() == gl::NO_ERROR);
  ctx.copyTexImage2D(gl::TEXTURE_2D, 0, gl::RGBA, 0, 0, 5, 4, 0);
  CHECK(ctx.getError() == gl::INVALID_VALUE);
  ctx.drawPixels(-1, 1, gl::RGBA, gl::UNSIGNED_BYTE, d.data());
  CHECK(ctx.getError() == gl::INVALID_VALUE);
  ctx.drawPixels(1, 1, gl::COLOR_INDEX, gl::UNSIGNED_BYTE, d.data());
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  ctx.drawPixels(1, 1, gl::RGBA, gl::BITMAP, d.data());
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  ctx.readPixels(0, 0, 1, 1, gl::RGBA, gl::UNSIGNED_BYTE_3_3_2, d.data());
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  ctx.readPixels(0, 0, 1, 1, gl::COLOR_INDEX, gl::UNSIGNED_BYTE, d.data());
  CHECK(ctx.getError() == gl::INVALID_OPERATION);
  ctx.copyPixels(0, 0, 1, 1, gl::RGBA);
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  ctx.copyPixels(0, 0, -2, 1, gl::COLOR);
  CHECK(ctx.getError() == gl::INVALID_VALUE);
  Profile nodepth = geforce();
  nodepth.depth_bits = 0;
  nodepth.stencil_bits = 0;
  Context c2(nodepth, 4, 4);
  c2.copyPixels(0, 0, 1, 1, gl::DEPTH);
  CHECK(c2.getError() == gl::INVALID_OPERATION);
  c2.drawPixels(1, 1, gl::STENCIL_INDEX, gl::UNSIGNED_BYTE, d.data());
  CHECK(c2.getError() == gl::INVALID_OPERATION);
  c2.readPixels(0, 0, 1, 1, gl::DEPTH_COMPONENT, gl::FLOAT, d.data());
  CHECK(c2.getError() == gl::INVALID_OPERATION);
}

TEST_CASE("pixel DrawPixels: centre rule placement, zoom and negative zoom") {
  Context ctx(geforce(), 16, 4);
  const std::uint8_t px[2][4] = {{10, 20, 30, 40}, {50, 60, 70, 80}};
  ctx.pixelStorei(gl::UNPACK_ALIGNMENT, 1);
  // xrp = 2.5: centre of pixel 2 is 2.5, on the left edge -> included (spec-notes 6.2).
  ctx.raster_pos().x = 2.5;
  ctx.raster_pos().y = 1.0;
  ctx.drawPixels(2, 1, gl::RGBA, gl::UNSIGNED_BYTE, px);
  CHECK(get(ctx, 2, 1) == std::array<std::uint16_t, 4>{10, 20, 30, 40});
  CHECK(get(ctx, 3, 1) == std::array<std::uint16_t, 4>{50, 60, 70, 80});
  CHECK(get(ctx, 4, 1) == std::array<std::uint16_t, 4>{0, 0, 0, 0});
  // xrp = 6.51 -> first fragment at 7 (6.5 < 6.51).
  ctx.raster_pos().x = 6.51;
  ctx.drawPixels(1, 1, gl::RGBA, gl::UNSIGNED_BYTE, px);
  CHECK(get(ctx, 6, 1)[0] == 0);
  CHECK(get(ctx, 7, 1)[0] == 10);
  // Zoom (2, 3) at (10, 0): group 0 covers x 10..11, y 0..2; group 1 x 12..13.
  ctx.pixelZoom(2, 3);
  ctx.raster_pos().x = 10;
  ctx.raster_pos().y = 0;
  ctx.drawPixels(2, 1, gl::RGBA, gl::UNSIGNED_BYTE, px);
  for (int y = 0; y < 3; ++y) {
    CHECK(get(ctx, 10, y)[0] == 10);
    CHECK(get(ctx, 11, y)[0] == 10);
    CHECK(get(ctx, 12, y)[0] == 50);
    CHECK(get(ctx, 13, y)[0] == 50);
  }
  CHECK(get(ctx, 10, 3)[0] == 0);
  // Negative zoom -1 at x = 6: group n covers [6 - (n+1), 6 - n): group 0 -> x 5, group 1 -> x 4.
  ctx.pixelZoom(-1, 1);
  ctx.raster_pos().x = 6;
  ctx.raster_pos().y = 3;
  ctx.drawPixels(2, 1, gl::RGBA, gl::UNSIGNED_BYTE, px);
  CHECK(get(ctx, 5, 3)[0] == 10);
  CHECK(get(ctx, 4, 3)[0] == 50);
  CHECK(get(ctx, 6, 3)[0] == 0);
  // Invalid raster position: nothing drawn.
  ctx.pixelZoom(1, 1);
  ctx.raster_pos().valid = false;
  ctx.raster_pos().x = 0;
  ctx.drawPixels(1, 1, gl::RGBA, gl::UNSIGNED_BYTE, px);
  CHECK(get(ctx, 0, 3)[0] == 0);
  CHECK(ctx.getError() == gl::NO_ERROR);
}

TEST_CASE("pixel CopyPixels COLOR: transfer path, read-before-write overlap, colour matrix into alpha") {
  Context ctx(geforce(), 8, 2);
  for (int x = 0; x < 8; ++x) put(ctx, x, 0, {static_cast<std::uint16_t>(10 * x), 0, 0, 255});
  // Copy x 0..5 to x 2..7 (overlapping): the result must be the original source.
  ctx.raster_pos().x = 2;
  ctx.raster_pos().y = 0;
  ctx.copyPixels(0, 0, 6, 1, gl::COLOR);
  for (int x = 2; x < 8; ++x) CHECK(get(ctx, x, 0)[0] == 10 * (x - 2));
  // Colour matrix with row 4 = (1, 0, 0, 0): A' = R (spec-notes 2.6).
  const double m[16] = {1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0};
  ctx.matrixMode(gl::COLOR);
  ctx.loadMatrix(m);
  CHECK(ctx.transfer_plan(pixel::ImageDims::TwoD).str(ctx.transfer_inputs()) == "color_matrix");
  ctx.raster_pos().y = 1;
  ctx.raster_pos().x = 0;
  ctx.copyPixels(0, 0, 8, 1, gl::COLOR);
  for (int x = 0; x < 8; ++x) CHECK(get(ctx, x, 1)[3] == get(ctx, x, 0)[0]);
}

TEST_CASE("pixel ReadPixels: identity round trip, LUMINANCE sum, pack store modes") {
  Context ctx(geforce(), 4, 4);
  put(ctx, 1, 2, {100, 50, 30, 200});
  std::uint8_t out[4] = {0, 0, 0, 0};
  ctx.readPixels(1, 2, 1, 1, gl::RGBA, gl::UNSIGNED_BYTE, out);
  CHECK(out[0] == 100);
  CHECK(out[3] == 200);
  std::uint8_t l[2] = {0, 0};
  ctx.readPixels(1, 2, 1, 1, gl::LUMINANCE_ALPHA, gl::UNSIGNED_BYTE, l);
  CHECK(l[0] == 180);  // (100 + 50 + 30)/255 -> 180
  CHECK(l[1] == 200);
  // PACK_SKIP_PIXELS 1 with ALPHA: the value lands in byte 1.
  std::uint8_t a[2] = {9, 9};
  ctx.pixelStorei(gl::PACK_SKIP_PIXELS, 1);
  ctx.readPixels(1, 2, 1, 1, gl::ALPHA, gl::UNSIGNED_BYTE, a);
  CHECK(a[0] == 9);
  CHECK(a[1] == 200);
  ctx.pixelStorei(gl::PACK_SKIP_PIXELS, 0);
  float f[3];
  ctx.readPixels(1, 2, 1, 1, gl::BGR, gl::FLOAT, f);
  CHECK(f[0] == 30 / 255.0f);
  CHECK(f[2] == 100 / 255.0f);
  CHECK(ctx.getError() == gl::NO_ERROR);
}

TEST_CASE("pixel TexImage/CopyTexImage: levels, formats, version, identity copy is bit-exact") {
  Context ctx(geforce(), 8, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      put(ctx, x, y, {static_cast<std::uint16_t>(x * 30), static_cast<std::uint16_t>(y * 30), 7, 255});
  ctx.copyTexImage2D(gl::TEXTURE_2D, 1, gl::RGB, 2, 2, 4, 4, 0);
  CHECK(ctx.getError() == gl::NO_ERROR);
  const TextureObject& t = ctx.bound_texture(0, gl::TEXTURE_2D);
  REQUIRE(t.levels.size() == 2);
  CHECK(t.version == 1);
  const TextureImage& l1 = t.levels[1];
  CHECK(l1.width == 4);
  CHECK(l1.base == BaseFormat::RGB);
  CHECK(l1.bits == 8);
  // Texel (1, 2) of the copy is framebuffer pixel (3, 4): R = 90, G = 120, B = 7 (spec-notes 2.11).
  CHECK(l1.codes[3 * (2 * 4 + 1)] == 90);
  CHECK(l1.codes[3 * (2 * 4 + 1) + 1] == 120);
  CHECK(l1.codes[3 * (2 * 4 + 1) + 2] == 7);
  ctx.copyTexSubImage2D(gl::TEXTURE_2D, 1, 0, 0, 7, 7, 1, 1);
  CHECK(t.version == 2);
  CHECK(l1.codes[0] == 210);
  // A sized format stores at its own width: LUMINANCE12 of code 255 is 4095; 1D texture.
  const std::uint8_t row[4] = {255, 0, 128, 64};
  ctx.texImage1D(gl::TEXTURE_1D, 0, gl::LUMINANCE12, 4, 0, gl::LUMINANCE, gl::UNSIGNED_BYTE, row);
  const TextureImage& l = ctx.bound_texture(0, gl::TEXTURE_1D).levels.at(0);
  CHECK(l.bits == 12);
  CHECK(l.height == 1);
  // k/255 in binary32 then rnd(4095 x): 128 -> 2055.5294 -> 2056; 64 -> 1027.76 -> 1028.
  CHECK(l.codes == std::vector<std::uint16_t>{4095, 0, 2056, 1028});
  // TexSubImage1D writes into the existing level.
  const std::uint8_t one[1] = {17};
  ctx.texSubImage1D(gl::TEXTURE_1D, 0, 1, 1, gl::LUMINANCE, gl::UNSIGNED_BYTE, one);
  CHECK(l.codes[1] == 17 * 4095 / 255);  // 17/255 = 1/15 exactly -> 273
}

TEST_CASE("pixel TexImage2D with REDUCE convolution checks the convolved size") {
  Context ctx(geforce(), 8, 8);
  std::vector<float> box(9, 1.0f / 9);
  ctx.convolutionFilter2D(gl::CONVOLUTION_2D, gl::LUMINANCE, 3, 3, gl::LUMINANCE, gl::FLOAT, box.data());
  ctx.enable(gl::CONVOLUTION_2D);
  std::vector<std::uint8_t> img(6 * 6, 90);
  ctx.pixelStorei(gl::UNPACK_ALIGNMENT, 1);
  ctx.texImage2D(gl::TEXTURE_2D, 0, gl::LUMINANCE, 5, 5, 0, gl::LUMINANCE, gl::UNSIGNED_BYTE, img.data());
  CHECK(ctx.getError() == gl::INVALID_VALUE);  // 5x5 -> 3x3 is not a power of two
  ctx.texImage2D(gl::TEXTURE_2D, 0, gl::LUMINANCE, 6, 6, 0, gl::LUMINANCE, gl::UNSIGNED_BYTE, img.data());
  CHECK(ctx.getError() == gl::NO_ERROR);
  const TextureImage& t = ctx.bound_texture(0, gl::TEXTURE_2D).levels.at(0);
  CHECK(t.width == 4);
  CHECK(t.height == 4);
  // 9 * (90/255 * 1/9) in binary32 = 90/255 up to a few ulps -> code 90.
  for (auto c : t.codes) CHECK(c == 90);
  CHECK(ctx.transfer_plan(pixel::ImageDims::TwoD).str(ctx.transfer_inputs()) ==
        "convolution(2D 3x3, LUMINANCE, REDUCE)");
}

TEST_CASE("pixel stencil rectangles: index offset, stencil mask, scissor, CopyPixels STENCIL") {
  Context ctx(geforce(), 4, 2);
  const std::uint8_t s[2] = {3, 250};
  ctx.pixelStorei(gl::UNPACK_ALIGNMENT, 1);
  ctx.pixelTransferi(gl::INDEX_OFFSET, 10);
  ctx.stencilMask(0x0F);
  ctx.drawPixels(2, 1, gl::STENCIL_INDEX, gl::UNSIGNED_BYTE, s);
  auto& st = ctx.framebuffer().stencil();
  CHECK(st[0] == (13 & 0x0F));
  CHECK(st[1] == (260 & 0xFF & 0x0F));  // masked to 8 bits, then through the write mask
  ctx.stencilMask(0xFF);
  ctx.pixelTransferi(gl::INDEX_OFFSET, 0);
  ctx.enable(gl::SCISSOR_TEST);
  ctx.scissor(0, 1, 1, 1);
  ctx.raster_pos().y = 1;
  ctx.copyPixels(0, 0, 2, 1, gl::STENCIL);
  CHECK(st[ctx.framebuffer().index(0, 1)] == st[0]);
  CHECK(st[ctx.framebuffer().index(1, 1)] == 0);  // outside the scissor box
}

TEST_CASE("pixel DrawPixels under the ideal profile keeps binary64 values") {
  Context ctx(*find_builtin_profile("ideal"), 2, 1);
  const float px[4] = {0.1f, 0.7f, 1.5f, -0.2f};
  ctx.pixelTransferf(gl::RED_SCALE, 1.0 / 3);
  ctx.drawPixels(1, 1, gl::RGBA, gl::FLOAT, px);
  const auto& v = ctx.framebuffer().values();
  CHECK(v[0] == static_cast<double>(0.1f) * (1.0 / 3));
  CHECK(v[1] == static_cast<double>(0.7f));
  CHECK(v[2] == 1.0);  // clamped at final conversion
  CHECK(v[3] == 0.0);
}

TEST_CASE("pixel ReadPixels of depth and stencil: 24-bit depth codes survive, index arithmetic applies") {
  Context ctx(geforce(), 2, 1);
  ctx.framebuffer().depth()[1] = 0xABCDEF;
  ctx.framebuffer().stencil()[1] = 5;
  std::uint32_t d[1] = {0};
  // k / (2^24 - 1) in binary64, then rnd(f (2^32 - 1)) exactly: an independent
  // integer evaluation of the same rational, round half up.
  ctx.readPixels(1, 0, 1, 1, gl::DEPTH_COMPONENT, gl::UNSIGNED_INT, d);
  // (The binary64 quotient is within 2^-53 relative of the rational, far from a tie here.)
  const std::uint64_t num = 0xABCDEFull * 0xFFFFFFFFull;  // < 2^56
  const std::uint64_t want = (2 * num + 0xFFFFFF) / (2 * 0xFFFFFFull);
  CHECK(d[0] == want);
  ctx.pixelTransferi(gl::INDEX_SHIFT, 2);
  ctx.pixelTransferi(gl::INDEX_OFFSET, 1);
  std::uint8_t s[1] = {0};
  ctx.readPixels(1, 0, 1, 1, gl::STENCIL_INDEX, gl::UNSIGNED_BYTE, s);
  CHECK(s[0] == 5 * 4 + 1);
  CHECK(ctx.getError() == gl::NO_ERROR);
}

TEST_CASE("pixel identity DrawPixels, CopyPixels and CopyTexImage keep all 256 codes of every component") {
  Context ctx(geforce(), 256, 3);
  std::vector<std::uint8_t> d(4 * 256);
  for (int k = 0; k < 256; ++k) {  // each component runs through all codes in a different order
    d[4 * k] = static_cast<std::uint8_t>(k);
    d[4 * k + 1] = static_cast<std::uint8_t>(255 - k);
    d[4 * k + 2] = static_cast<std::uint8_t>((k * 7) % 256);
    d[4 * k + 3] = static_cast<std::uint8_t>((k + 128) % 256);
  }
  CHECK(ctx.transfer_plan(pixel::ImageDims::TwoD).empty());
  ctx.drawPixels(256, 1, gl::RGBA, gl::UNSIGNED_BYTE, d.data());
  ctx.raster_pos().y = 1;
  ctx.copyPixels(0, 0, 256, 1, gl::COLOR);
  ctx.copyTexImage1D(gl::TEXTURE_1D, 0, gl::RGBA8, 0, 1, 256, 0);
  const TextureImage& t = ctx.bound_texture(0, gl::TEXTURE_1D).levels.at(0);
  for (int k = 0; k < 256; ++k)
    for (int c = 0; c < 4; ++c) {
      CHECK(get(ctx, k, 0)[c] == d[4 * k + c]);
      CHECK(get(ctx, k, 1)[c] == d[4 * k + c]);
      CHECK(t.codes[4 * k + c] == d[4 * k + c]);
    }
  CHECK(ctx.getError() == gl::NO_ERROR);
}

TEST_CASE("pixel rectangles beyond the pixel limit are OUT_OF_MEMORY, huge zoom stays in the window") {
  Context ctx(geforce(), 4, 4);
  std::uint8_t px[4] = {1, 2, 3, 4};
  ctx.drawPixels(1 << 20, 1 << 20, gl::RGBA, gl::UNSIGNED_BYTE, px);
  CHECK(ctx.getError() == gl::OUT_OF_MEMORY);
  ctx.copyPixels(0, 0, 1 << 20, 1 << 20, gl::COLOR);
  CHECK(ctx.getError() == gl::OUT_OF_MEMORY);
  ctx.pixelZoom(1e7, -1e7);  // one group covers the whole window (downwards from y = 4)
  ctx.raster_pos().y = 4;
  ctx.drawPixels(1, 1, gl::RGBA, gl::UNSIGNED_BYTE, px);
  CHECK(get(ctx, 3, 0) == std::array<std::uint16_t, 4>{1, 2, 3, 4});
  CHECK(get(ctx, 0, 3) == std::array<std::uint16_t, 4>{1, 2, 3, 4});
  CHECK(ctx.getError() == gl::NO_ERROR);
}

TEST_CASE("pixel TexImage1D with CONVOLUTION_1D: filter scale, border modes, post-convolution scale and bias") {
  Context ctx(geforce(), 4, 4);
  const float ones[3] = {1, 1, 1};
  const double quarter[4] = {0.25, 0.25, 0.25, 0.25};
  ctx.convolutionParameterfv(gl::CONVOLUTION_1D, gl::CONVOLUTION_FILTER_SCALE, quarter);
  ctx.convolutionFilter1D(gl::CONVOLUTION_1D, gl::LUMINANCE, 3, gl::LUMINANCE, gl::FLOAT, ones);  // taps 1/4
  const double border[4] = {0.8, 0.8, 0.8, 0.8};
  ctx.convolutionParameterfv(gl::CONVOLUTION_1D, gl::CONVOLUTION_BORDER_COLOR, border);
  ctx.convolutionParameteri(gl::CONVOLUTION_1D, gl::CONVOLUTION_BORDER_MODE, gl::CONSTANT_BORDER);
  ctx.enable(gl::CONVOLUTION_1D);
  ctx.pixelTransferf(gl::POST_CONVOLUTION_RED_SCALE, 2);
  ctx.pixelTransferf(gl::POST_CONVOLUTION_RED_BIAS, -0.05);
  const std::uint8_t row[4] = {0, 51, 102, 255};  // 0, 0.2, 0.4, 1
  ctx.texImage1D(gl::TEXTURE_1D, 0, gl::LUMINANCE, 4, 0, gl::LUMINANCE, gl::UNSIGNED_BYTE, row);
  CHECK(ctx.getError() == gl::NO_ERROR);
  const TextureObject& t = ctx.bound_texture(0, gl::TEXTURE_1D);
  // Hand derivation: sums (0.8+0+0.2)/4 = 0.25, (0+0.2+0.4)/4 = 0.15, (0.2+0.4+1)/4 = 0.4,
  // (0.4+1+0.8)/4 = 0.55; then *2 - 0.05: 0.45, 0.25, 0.75, 1.05 -> codes 115 (114.75),
  // 64 (63.75), 191 (191.25), 255 (clamped).
  CHECK(t.levels.at(0).codes == std::vector<std::uint16_t>{115, 64, 191, 255});
  // REPLICATE_BORDER: ends use the edge texels: (0+0+0.2)/4 = 0.05 -> 0.05 (12.75 -> 13);
  // (0.4+1+1)/4 = 0.6 -> 1.15 -> 255.
  ctx.convolutionParameteri(gl::CONVOLUTION_1D, gl::CONVOLUTION_BORDER_MODE, gl::REPLICATE_BORDER);
  ctx.texImage1D(gl::TEXTURE_1D, 0, gl::LUMINANCE, 4, 0, gl::LUMINANCE, gl::UNSIGNED_BYTE, row);
  CHECK(t.levels.at(0).codes == std::vector<std::uint16_t>{13, 64, 191, 255});
  // REDUCE: 4 - 2 = 2 texels, a power of two: 0.15, 0.4 -> 0.25, 0.75.
  ctx.convolutionParameteri(gl::CONVOLUTION_1D, gl::CONVOLUTION_BORDER_MODE, gl::REDUCE);
  ctx.texImage1D(gl::TEXTURE_1D, 0, gl::LUMINANCE, 4, 0, gl::LUMINANCE, gl::UNSIGNED_BYTE, row);
  CHECK(t.levels.at(0).width == 2);
  CHECK(t.levels.at(0).codes == std::vector<std::uint16_t>{64, 191});
  // 2D images do not use the 1D filter.
  CHECK(ctx.transfer_plan(pixel::ImageDims::TwoD).empty());
  CHECK(ctx.getError() == gl::NO_ERROR);
}

TEST_CASE("pixel client image sizes follow the store modes") {
  Context ctx(geforce(), 2, 2);
  CHECK(ctx.pixel_client_bytes(false, 3, 2, gl::RGB, gl::UNSIGNED_BYTE) == 12 + 9);  // rows padded to 4
  ctx.pixelStorei(gl::PACK_ALIGNMENT, 1);
  ctx.pixelStorei(gl::PACK_SKIP_ROWS, 1);
  CHECK(ctx.pixel_client_bytes(true, 3, 2, gl::RGB, gl::UNSIGNED_BYTE) == 9 + 9 + 9);
  CHECK(ctx.pixel_client_bytes(false, 2, 1, gl::DEPTH_COMPONENT, gl::FLOAT) == 8);
  CHECK(ctx.pixel_client_bytes(false, 2, 1, gl::COLOR_INDEX, gl::FLOAT) == 0);
}

TEST_CASE("pixel NaN parameters do not reach integer conversions") {
  Context ctx(geforce(), 2, 2);
  ctx.pixelTransferf(gl::INDEX_SHIFT, std::nan(""));
  ctx.pixelTransferf(gl::INDEX_OFFSET, 1e30);
  CHECK(ctx.pixel_transfer().index_shift == 0);
  CHECK(ctx.pixel_transfer().index_offset == 2000000000);
  ctx.pixelZoom(std::nan(""), 1);
  const std::uint8_t px[4] = {9, 9, 9, 9};
  ctx.drawPixels(1, 1, gl::RGBA, gl::UNSIGNED_BYTE, px);  // the group covers nothing
  CHECK(get(ctx, 0, 0)[0] == 0);
  CHECK(ctx.getError() == gl::NO_ERROR);
}

TEST_CASE("pixel GL errors: the remaining entry points, and CopyColorTable reads the framebuffer") {
  Context ctx(geforce(), 4, 4);
  const float f[16] = {0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f};
  ctx.separableFilter2D(gl::CONVOLUTION_2D, gl::RGBA, 2, 2, gl::RGBA, gl::FLOAT, f, f);
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  ctx.separableFilter2D(gl::SEPARABLE_2D, gl::RGBA, 2, 12, gl::RGBA, gl::FLOAT, f, f);
  CHECK(ctx.getError() == gl::INVALID_VALUE);
  CHECK(ctx.imaging().separable2d.width == 0);
  ctx.separableFilter2D(gl::SEPARABLE_2D, gl::RGBA, 2, 2, gl::RGBA, gl::FLOAT, f, f);
  CHECK(ctx.getError() == gl::NO_ERROR);
  CHECK(ctx.imaging().separable2d.row.size() == 8);
  const double v[4] = {1, 2, 3, 4};
  ctx.convolutionParameterfv(gl::SEPARABLE_2D, gl::COLOR_TABLE_SCALE, v);
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  ctx.convolutionParameterfv(gl::SEPARABLE_2D, gl::CONVOLUTION_BORDER_COLOR, v);
  CHECK(ctx.imaging().separable2d.border_color == std::array<double, 4>{1, 2, 3, 4});
  ctx.texImage1D(gl::TEXTURE_2D, 0, gl::RGBA, 4, 0, gl::RGBA, gl::FLOAT, f);
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  ctx.texImage1D(gl::TEXTURE_1D, 0, gl::RGBA, 5, 0, gl::RGBA, gl::FLOAT, f);
  CHECK(ctx.getError() == gl::INVALID_VALUE);
  ctx.texSubImage1D(gl::TEXTURE_1D, 0, 0, 1, gl::RGBA, gl::FLOAT, f);
  CHECK(ctx.getError() == gl::INVALID_OPERATION);
  ctx.copyTexImage1D(gl::TEXTURE_1D, 0, gl::RGBA, 0, 0, 4, 3);
  CHECK(ctx.getError() == gl::INVALID_VALUE);
  ctx.copyTexSubImage1D(gl::TEXTURE_1D, 0, 0, 0, 0, 1);
  CHECK(ctx.getError() == gl::INVALID_OPERATION);
  ctx.copyTexSubImage2D(gl::TEXTURE_2D, 0, 0, 0, 0, 0, 1, 1);
  CHECK(ctx.getError() == gl::INVALID_OPERATION);
  ctx.texImage1D(gl::TEXTURE_1D, 0, gl::RGBA, 4, 0, gl::RGBA, gl::FLOAT, f);
  ctx.copyTexSubImage1D(gl::TEXTURE_1D, 0, 2, 0, 0, 3);  // 2 + 3 > 4
  CHECK(ctx.getError() == gl::INVALID_VALUE);
  CHECK(ctx.bound_texture(0, gl::TEXTURE_1D).version == 1);
  ctx.copyColorTable(gl::COLOR_TABLE, gl::RGB, 0, 0, 3);
  CHECK(ctx.getError() == gl::INVALID_VALUE);
  // CopyColorTable: framebuffer row 0 as table data, no transfer operations applied.
  ctx.framebuffer().codes()[0] = 51;  // pixel (0,0) R = 0.2
  ctx.pixelTransferf(gl::RED_SCALE, 4);  // must not apply to table data
  ctx.copyColorTable(gl::COLOR_TABLE, gl::LUMINANCE, 0, 0, 2);
  CHECK(ctx.getError() == gl::NO_ERROR);
  CHECK(ctx.imaging().table(pixel::TableSlot::Color).entries == std::vector<double>{static_cast<float>(51) / 255.0f, 0.0});
}

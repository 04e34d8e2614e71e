// Texture sampling: NEAREST/LINEAR, wraps at the borders, mipmap level
// selection, completeness (pipeline/texture/texture_sample.h). Expected codes are
// hand evaluations of GL121 eq. 3.17-3.23 with the weight rule of
// docs/numerics.md §8.4: a = floor(frac(u - 1/2)·256), sum over 2^16 (2D) or 2^8
// (1D), round half up.
#include <doctest/doctest.h>

#include "pipeline/number/unorm.h"
#include "pipeline/texture/texture_sample.h"

using namespace ffsim;

namespace {

const SampleFormat kFixed{Arithmetic::Fixed, 8};
const SampleFormat kIdeal{Arithmetic::Float64, 8};

TextureImage image(BaseFormat base, int w, int h, std::vector<std::uint16_t> codes, int border = 0) {
  TextureImage im;
  im.width = w;
  im.height = h;
  im.border = border;
  im.base = base;
  im.bits = 8;
  im.codes = std::move(codes);
  for (auto k : im.codes) im.values.push_back(k / 255.0);
  return im;
}

TextureObject tex1d(std::vector<std::uint16_t> codes, GLenum filter, GLenum wrap, int border = 0) {
  TextureObject t;
  t.target = gl::TEXTURE_1D;
  const int w = static_cast<int>(codes.size());
  t.levels.push_back(image(BaseFormat::Luminance, w, 1, std::move(codes), border));
  t.params.min_filter = t.params.mag_filter = filter;
  t.params.wrap_s = wrap;
  return t;
}

std::uint32_t s1(const TextureObject& t, double s) { return sample_level(t, 0, 1, t.params.mag_filter, s, 0, kFixed).code[0]; }

}  // namespace

TEST_CASE("texture: NEAREST with REPEAT, CLAMP and CLAMP_TO_EDGE at the borders") {
  TextureObject t = tex1d({10, 20, 30, 40}, gl::NEAREST, gl::REPEAT);
  CHECK(s1(t, 0.0) == 10);
  CHECK(s1(t, 0.99) == 40);   // u = 3.96
  CHECK(s1(t, 1.0) == 10);    // REPEAT: frac(1) = 0
  CHECK(s1(t, -0.01) == 40);  // frac(-0.01) = 0.99
  CHECK(s1(t, 1.26) == 20);   // frac 0.26 -> u = 1.04
  t.params.wrap_s = gl::CLAMP;
  CHECK(s1(t, 1.0) == 40);  // s = 1 -> i = 2^n - 1 (eq. 3.19)
  CHECK(s1(t, 7.0) == 40);
  CHECK(s1(t, -3.0) == 10);
  t.params.wrap_s = gl::CLAMP_TO_EDGE;
  CHECK(s1(t, 1.0) == 40);
  CHECK(s1(t, -1.0) == 10);
}

TEST_CASE("texture: LINEAR weights are 8-bit, the sum is exact and rounded half up") {
  // 2x1 texture {0, 255}. u = 2s. s = 0.5: u - 1/2 = 0.5 -> a = 128:
  // (0·128 + 255·128 + 128) >> 8 = 32768 >> 8 = 128 (127.5 rounded up).
  TextureObject t = tex1d({0, 255}, gl::LINEAR, gl::CLAMP_TO_EDGE);
  CHECK(s1(t, 0.5) == 128);
  // s = 0.375: u - 1/2 = 0.25 -> a = 64: (255·64 + 128) >> 8 = 16448 >> 8 = 64 (63.75 -> 64).
  CHECK(s1(t, 0.375) == 64);
  // s = 0.3: u - 1/2 = 0.1 (binary32 0.100000024) -> a = floor(25.6) = 25:
  // (255·25 + 128) >> 8 = 6503 >> 8 = 25 (24.90 -> 25). The exact real lerp would give 25.5 -> 26.
  CHECK(s1(t, 0.3) == 25);
  // Ideal profile: the real weights, no quantisation: 0.1·1 = 0.1 (binary32 u).
  CHECK(sample_level(t, 0, 1, gl::LINEAR, 0.3, 0, kIdeal).value[0] == doctest::Approx(0.1).epsilon(1e-6));
  CHECK(sample_level(t, 0, 1, gl::LINEAR, 0.5, 0, kIdeal).value[0] == 0.5);
}

TEST_CASE("texture: LINEAR at the edges with REPEAT, CLAMP (border colour) and CLAMP_TO_EDGE") {
  TextureObject t = tex1d({100, 200}, gl::LINEAR, gl::REPEAT);
  // s = 0: u - 1/2 = -0.5 -> i0 = -1 -> 1 (REPEAT), i1 = 0, a = 128:
  // (200·128 + 100·128 + 128) >> 8 = 38528 >> 8 = 150.
  CHECK(s1(t, 0.0) == 150);
  t.params.wrap_s = gl::CLAMP;
  t.params.border_color = {1, 1, 1, 1};
  // CLAMP: i0 = -1 is outside the image: border colour R = 1 -> 255 (LUMINANCE takes R):
  // (255·128 + 100·128 + 128) >> 8 = 45568 >> 8 = 178.
  CHECK(s1(t, 0.0) == 178);
  CHECK(s1(t, 1.0) == 228);  // (200·128 + 255·128 + 128) >> 8 = 58368 >> 8 = 228
  t.params.wrap_s = gl::CLAMP_TO_EDGE;
  CHECK(s1(t, 0.0) == 100);  // s clamped to 1/4: u - 1/2 = 0, weight 0
  CHECK(s1(t, 1.0) == 200);
}

TEST_CASE("texture: a border texel is used instead of the border colour when the image has one") {
  // 1D, border 1: stored {border=7, 100, 200, border=9}; CLAMP, s = 0 blends 7 and 100.
  TextureObject t = tex1d({7, 100, 200, 9}, gl::LINEAR, gl::CLAMP, 1);
  CHECK(s1(t, 0.0) == 54);   // (7·128 + 100·128 + 128) >> 8 = 13824 >> 8 = 54
  CHECK(s1(t, 1.0) == 105);  // (200·128 + 9·128 + 128) >> 8 = 26880 >> 8 = 105
}

TEST_CASE("texture: 2D bilinear with unequal weights") {
  // 2x2 RGBA... as LUMINANCE {t00=0, t10=255, t01=100, t11=50} (row 0 first).
  TextureObject t;
  t.levels.push_back(image(BaseFormat::Luminance, 2, 2, {0, 255, 100, 50}));
  t.params.min_filter = t.params.mag_filter = gl::LINEAR;
  t.params.wrap_s = t.params.wrap_t = gl::CLAMP_TO_EDGE;
  // s = 0.375 -> a = 64; t = 0.625 -> u - 1/2 = 0.75 -> b = 192.
  // weights: w00 = 192·64 = 12288, w10 = 64·64 = 4096, w01 = 192·192 = 36864, w11 = 64·192 = 12288.
  // sum = 255·4096 + 100·36864 + 50·12288 = 1044480 + 3686400 + 614400 = 5345280;
  // (5345280 + 32768) >> 16 = 82 (81.56 -> 82).
  CHECK(sample_level(t, 0, 2, gl::LINEAR, 0.375, 0.625, kFixed).code[0] == 82);
  const Texel n = sample_level(t, 0, 2, gl::NEAREST, 0.375, 0.625, kFixed);
  CHECK(n.code[0] == 100);  // u = 0.75 -> i = 0, v = 1.25 -> j = 1
  CHECK(n.code[3] == 255);  // LUMINANCE expands to (L, L, L, 1)
}

TEST_CASE("texture: base formats expand as ARB_texture_env_combine Table 3.23") {
  const auto a = expand_texel(BaseFormat::Alpha, 8, {77, 0, 0, 0});
  CHECK(a.code == std::array<std::uint32_t, 4>{0, 0, 0, 77});
  const auto la = expand_texel(BaseFormat::LuminanceAlpha, 8, {5, 6, 0, 0});
  CHECK(la.code == std::array<std::uint32_t, 4>{5, 5, 5, 6});
  const auto in = expand_texel(BaseFormat::Intensity, 8, {9, 0, 0, 0});
  CHECK(in.code == std::array<std::uint32_t, 4>{9, 9, 9, 9});
  const auto rgb = expand_texel(BaseFormat::RGB, 8, {1, 2, 3, 0});
  CHECK(rgb.code == std::array<std::uint32_t, 4>{1, 2, 3, 255});
}

namespace {
TextureObject mip_chain() {  // 4x4 of 10, 2x2 of 20, 1x1 of 30
  TextureObject t;
  t.levels.push_back(image(BaseFormat::Luminance, 4, 4, std::vector<std::uint16_t>(16, 10)));
  t.levels.push_back(image(BaseFormat::Luminance, 2, 2, std::vector<std::uint16_t>(4, 20)));
  t.levels.push_back(image(BaseFormat::Luminance, 1, 1, std::vector<std::uint16_t>(1, 30)));
  t.params.mag_filter = gl::LINEAR;
  return t;
}
std::uint32_t at_lod(const TextureObject& t, double lambda) { return sample_texture(t, 2, 0.3, 0.6, lambda, kFixed).code[0]; }
}  // namespace

TEST_CASE("texture: mipmap level selection and the LOD switch-over point") {
  TextureObject t = mip_chain();
  t.params.min_filter = gl::NEAREST_MIPMAP_NEAREST;  // with MAG LINEAR: c = 0.5
  CHECK(at_lod(t, 0.4) == 10);  // λ <= c: magnification, level 0
  CHECK(at_lod(t, 0.6) == 20);  // d = ceil(0.6 + 0.5) - 1 = 1
  CHECK(at_lod(t, 1.4) == 20);  // ceil(1.9) - 1 = 1
  CHECK(at_lod(t, 1.6) == 30);  // ceil(2.1) - 1 = 2
  CHECK(at_lod(t, 9.0) == 30);  // beyond q = 2
  t.params.min_filter = gl::LINEAR_MIPMAP_LINEAR;  // c = 0
  // λ = 1.25: d1 = 1, d2 = 2, frac = 0.25 -> f = 64: (20·192 + 30·64 + 128) >> 8 = 5888 >> 8 = 23.
  CHECK(at_lod(t, 1.25) == 23);
  // λ = 0.5: levels 0 and 1 with f = 128: (10·128 + 20·128 + 128) >> 8 = 3968 >> 8 = 15.
  CHECK(at_lod(t, 0.5) == 15);
  CHECK(at_lod(t, 2.5) == 30);   // b + λ >= q: level q only
  CHECK(at_lod(t, -1.0) == 10);  // magnification
  t.params.max_lod = 1.0;        // λ clamped to MAX_LOD: level 1 exactly
  CHECK(at_lod(t, 5.0) == 20);
  t.params.max_lod = 1000;
  t.params.base_level = 1;  // q = 1 + log2(2) = 2
  CHECK(at_lod(t, -1.0) == 20);
  t.params.min_filter = gl::LINEAR_MIPMAP_NEAREST;
  CHECK(at_lod(t, 0.7) == 30);  // d = ceil(1 + 0.7 + 0.5) - 1 = 2
}

TEST_CASE("texture: completeness") {
  TextureObject t = mip_chain();
  t.params.min_filter = gl::LINEAR_MIPMAP_LINEAR;
  CHECK(texture_complete(t, 2, kFixed));
  t.levels.pop_back();  // 1x1 level missing
  CHECK_FALSE(texture_complete(t, 2, kFixed));
  t.params.min_filter = gl::LINEAR;  // no mipmaps needed
  CHECK(texture_complete(t, 2, kFixed));
  t.params.max_level = 1;  // q = min(2, 1): levels 0..1 suffice
  t.params.min_filter = gl::NEAREST_MIPMAP_LINEAR;
  CHECK(texture_complete(t, 2, kFixed));
  TextureObject odd;
  odd.levels.push_back(image(BaseFormat::Luminance, 3, 1, {1, 2, 3}));
  odd.params.min_filter = gl::LINEAR;
  CHECK_FALSE(texture_complete(odd, 1, kFixed));  // not a power of two
  TextureObject none;
  CHECK_FALSE(texture_complete(none, 2, kFixed));
}

TEST_CASE("texture: float32 profile filters in binary32 without quantisation") {
  const SampleFormat f32{Arithmetic::Float32, 8};
  TextureObject t = tex1d({0, 255}, gl::LINEAR, gl::CLAMP_TO_EDGE);
  // u = 2·0.3f, α = u - 0.5f in binary32; the filtered value is (1 - α)·0 + α·1 = α.
  const float alpha = 2.0f * 0.3f - 0.5f;
  CHECK(sample_level(t, 0, 1, gl::LINEAR, 0.3, 0, f32).value[0] == static_cast<double>(alpha));
  CHECK(static_cast<double>(alpha) != 0.1);  // differs from the binary64 value: the test can tell them apart
}

TEST_CASE("texture: 2D CLAMP at a corner blends three border-colour texels") {
  TextureObject t;
  t.levels.push_back(image(BaseFormat::Luminance, 2, 2, {100, 100, 100, 100}));
  t.params.min_filter = t.params.mag_filter = gl::LINEAR;
  t.params.wrap_s = t.params.wrap_t = gl::CLAMP;
  t.params.border_color = {1, 0, 0, 0};  // LUMINANCE takes R: code 255
  // s = t = 0: i0 = j0 = -1 (border), a = b = 128, every weight 128·128 = 16384:
  // (255·3·16384 + 100·16384 + 32768) >> 16 = (14172160 + 32768) >> 16 = 216 (216.25).
  CHECK(sample_level(t, 0, 2, gl::LINEAR, 0, 0, kFixed).code[0] == 216);
  t.params.wrap_t = gl::CLAMP_TO_EDGE;  // only the s side reaches the border: (255 + 100)/2 -> 178
  CHECK(sample_level(t, 0, 2, gl::LINEAR, 0, 0, kFixed).code[0] == 178);
  t.params.wrap_s = t.params.wrap_t = gl::REPEAT;  // wraps to the opposite texels: all 100
  CHECK(sample_level(t, 0, 2, gl::LINEAR, 0, 0, kFixed).code[0] == 100);
}

// Texturing through the Context: perspective-correct coordinates, clipping of
// a polygon partly behind the eye, LOD selection, multitexture, pixel
// rectangles, the texture entry points, and planned == full shading.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "draw_test_util.h"

using namespace ffsim;
using namespace ffsim::test;

namespace {

// 1D LUMINANCE texture of 256 texels with texel i = code i, NEAREST: a fragment's
// red code is floor(256·s) for s in [0,1).
void ramp_texture_1d(Context& ctx) {
  std::vector<std::uint16_t> codes(256);
  for (int i = 0; i < 256; ++i) codes[static_cast<std::size_t>(i)] = static_cast<std::uint16_t>(i);
  set_level(ctx, gl::TEXTURE_1D, 0, BaseFormat::Luminance, 256, 1, codes);
  ctx.texParameteri(gl::TEXTURE_1D, gl::TEXTURE_MIN_FILTER, gl::NEAREST);
  ctx.texParameteri(gl::TEXTURE_1D, gl::TEXTURE_MAG_FILTER, gl::NEAREST);
  ctx.enable(gl::TEXTURE_1D);
  ctx.texEnvi(gl::TEXTURE_ENV, gl::TEXTURE_ENV_MODE, gl::REPLACE);
}

void perspective(Context& ctx) {
  ctx.matrixMode(gl::PROJECTION);
  ctx.loadIdentity();
  ctx.frustum(-1, 1, -1, 1, 1, 10);
  ctx.matrixMode(gl::MODELVIEW);
  ctx.loadIdentity();
}

// A floor y = -1 from z = zn (s = sn) to z = zf (s = 1), x in [-1, 1].
void floor_quad(Context& ctx, double zn, double sn, double zf) {
  ctx.begin(gl::QUADS);
  ctx.texCoord2(sn, 0);
  ctx.vertex3(-1, -1, zn);
  ctx.vertex3(1, -1, zn);
  ctx.texCoord2(1, 0);
  ctx.vertex3(1, -1, zf);
  ctx.vertex3(-1, -1, zf);
  ctx.end();
}

}  // namespace

TEST_CASE("draw: texture coordinates are perspective-correct") {
  // 64x64 window, frustum(-1,1,-1,1,1,10). The floor from z = -1 (s = 0) to z = -8
  // (s = 1) has all four vertices on the sub-pixel grid (window (0,0), (64,0),
  // (36,28), (28,28)). Reference, derived independently by casting the ray through
  // each pixel centre: y_ndc = (y + 1/2)/32 - 1, z_eye = 1/y_ndc, s = (-1 - z_eye)/7.
  Context ctx(profile_named("geforce256"), 64, 64);
  perspective(ctx);
  ramp_texture_1d(ctx);
  ctx.color4(1, 1, 1, 1);
  floor_quad(ctx, -1, 0, -8);
  int checked = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      if (code_at(ctx, x, y, 3) != 255) continue;  // not drawn (alpha stays 0)
      const double yn = (y + 0.5) / 32 - 1;
      const double s = (-1 - 1 / yn) / 7;
      const double u = 256 * s;
      if (std::abs(u - std::round(u)) < 1e-3) continue;  // binary32 rounding could go either way
      ++checked;
      CHECK_MESSAGE(code_at(ctx, x, y, 0) == static_cast<int>(std::floor(u)), "pixel " << x << "," << y);
    }
  CHECK(checked > 900);
  // The check discriminates: screen-linear interpolation would give s = 14.5/28 at row 14
  // (code 132); perspective: y_ndc = -0.546875, z_eye = -1.828571, s = 0.118367, 256·s = 30.3.
  CHECK(code_at(ctx, 32, 14, 0) == 30);
}

TEST_CASE("draw: a polygon partly behind the eye is clipped at the near plane") {
  // The same floor extended from z = +5 (behind the eye, s = 0) to z = -8 (s = 1):
  // s = (5 - z)/13. Only the part with z <= -1 is visible; the part behind the eye
  // must not be projected (it would appear mirrored above the horizon).
  Context ctx(profile_named("geforce256"), 64, 64);
  perspective(ctx);
  ramp_texture_1d(ctx);
  ctx.color4(1, 1, 1, 1);
  floor_quad(ctx, 5, 0, -8);
  int checked = 0, drawn = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const bool is_drawn = code_at(ctx, x, y, 3) == 255;
      drawn += is_drawn;
      if (y >= 28) {
        CHECK_MESSAGE(!is_drawn, "pixel above the far edge " << x << "," << y);
        continue;
      }
      const double xn = (x + 0.5) / 32 - 1, yn = (y + 0.5) / 32 - 1;
      const double ze = 1 / yn, xe = -xn * ze;
      if (std::abs(xe) < 0.95 && y < 27) CHECK_MESSAGE(is_drawn, "pixel inside the floor " << x << "," << y);
      if (!is_drawn) continue;
      const double u = 256 * (5 - ze) / 13;
      if (std::abs(u - std::round(u)) < 0.02) continue;  // clipped vertices are snapped to 1/16 pixel
      ++checked;
      CHECK_MESSAGE(code_at(ctx, x, y, 0) == static_cast<int>(std::floor(u)), "pixel " << x << "," << y);
    }
  CHECK(checked > 900);
  CHECK(drawn > 1000);
}

TEST_CASE("draw: minification selects the mipmap level from the exact LOD") {
  // 16x16 texture drawn on a 4x4 square: ρ = 4, λ = 2 -> level 2 (4x4, code 30) with
  // NEAREST_MIPMAP_NEAREST; a 2x magnified square: λ = -1 -> level 0 (code 10).
  Context ctx(profile_named("geforce256"), 32, 32);
  ortho_window(ctx);
  const int codes[5] = {10, 20, 30, 40, 50};
  for (int l = 0; l < 5; ++l) {
    const int n = 16 >> l;
    set_level(ctx, gl::TEXTURE_2D, l, BaseFormat::Luminance, n, n,
              std::vector<std::uint16_t>(static_cast<std::size_t>(n * n), static_cast<std::uint16_t>(codes[l])));
  }
  ctx.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MIN_FILTER, gl::NEAREST_MIPMAP_NEAREST);
  ctx.enable(gl::TEXTURE_2D);
  ctx.texEnvi(gl::TEXTURE_ENV, gl::TEXTURE_ENV_MODE, gl::REPLACE);
  auto textured_square = [&](double x0, double y0, double size) {
    ctx.begin(gl::QUADS);
    ctx.texCoord2(0, 0);
    ctx.vertex2(x0, y0);
    ctx.texCoord2(1, 0);
    ctx.vertex2(x0 + size, y0);
    ctx.texCoord2(1, 1);
    ctx.vertex2(x0 + size, y0 + size);
    ctx.texCoord2(0, 1);
    ctx.vertex2(x0, y0 + size);
    ctx.end();
  };
  textured_square(0, 0, 4);
  CHECK(code_at(ctx, 1, 1, 0) == 30);
  textured_square(8, 0, 8);  // ρ = 2, λ = 1: d = ceil(1 + 1/2) - 1 = 1 -> 20
  CHECK(code_at(ctx, 10, 3, 0) == 20);
  textured_square(0, 16, 16);  // ρ = 1, λ = 0 <= c = 0.5 (MAG LINEAR): level 0
  CHECK(code_at(ctx, 5, 20, 0) == 10);
  ctx.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MIN_FILTER, gl::LINEAR_MIPMAP_LINEAR);
  textured_square(16, 16, 16.0 * 2 / 3);  // ρ = 1.5, λ = log2 1.5 = 0.585: f = floor(0.585·256) = 149
  // (10·(256 - 149) + 20·149 + 128) >> 8 = (1070 + 2980 + 128) >> 8 = 4178 >> 8 = 16.
  CHECK(code_at(ctx, 20, 20, 0) == 16);
}

TEST_CASE("draw: two texture units chain MODULATE then ADD, then the colour sum") {
  Context ctx(profile_named("geforce256"), 2, 2);
  ortho_window(ctx);
  set_level(ctx, gl::TEXTURE_2D, 0, BaseFormat::RGB, 1, 1, {128, 255, 0});
  ctx.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MIN_FILTER, gl::NEAREST);
  ctx.enable(gl::TEXTURE_2D);  // unit 0: MODULATE (initial)
  ctx.activeTexture(gl::TEXTURE1);
  ctx.bindTexture(gl::TEXTURE_2D, 7);
  set_level(ctx, gl::TEXTURE_2D, 0, BaseFormat::Luminance, 1, 1, {20});
  ctx.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MIN_FILTER, gl::NEAREST);
  ctx.enable(gl::TEXTURE_2D);
  ctx.texEnvi(gl::TEXTURE_ENV, gl::TEXTURE_ENV_MODE, gl::ADD);
  ctx.enable(gl::COLOR_SUM);
  ctx.color4(200 / 255.0, 100 / 255.0, 50 / 255.0, 1);
  ctx.secondaryColor3(0, 0, 10 / 255.0);
  quad(ctx, 0, 0, 2, 2);
  // unit 0: (rnd(200·128/255), rnd(100·255/255), 0) = (100, 100, 0); unit 1: + 20 each;
  // colour sum: blue + 10.
  CHECK(code_at(ctx, 1, 1, 0) == 120);
  CHECK(code_at(ctx, 1, 1, 1) == 120);
  CHECK(code_at(ctx, 1, 1, 2) == 30);
  CHECK(code_at(ctx, 1, 1, 3) == 255);
  CHECK(ctx.getError() == gl::NO_ERROR);
}

TEST_CASE("draw: pixel-rectangle fragments are textured at the raster texture coordinates") {
  Context ctx(profile_named("geforce256"), 4, 1);
  ortho_window(ctx);
  // 2x1 RGBA texture; raster s/q = 0.75 picks texel 1 with NEAREST.
  set_level(ctx, gl::TEXTURE_2D, 0, BaseFormat::RGBA, 2, 1, {1, 2, 3, 4, 200, 100, 50, 255});
  ctx.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MIN_FILTER, gl::NEAREST);
  ctx.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MAG_FILTER, gl::NEAREST);
  ctx.enable(gl::TEXTURE_2D);
  ctx.texCoord4(1.5, 0, 0, 2);
  ctx.rasterPos2(0, 0);
  FragmentSpan span;
  span.y = 0;
  span.x0 = 1;
  span.count = 2;
  span.codes = {255, 255, 255, 255, 128, 64, 0, 255};
  ctx.pixel_fragments(span);  // MODULATE
  CHECK(code_at(ctx, 1, 0, 0) == 200);
  CHECK(code_at(ctx, 1, 0, 1) == 100);
  CHECK(code_at(ctx, 2, 0, 0) == 100);  // rnd(128·200/255) = rnd(100.39)
  CHECK(code_at(ctx, 2, 0, 1) == 25);   // rnd(64·100/255) = rnd(25.1)
  CHECK(code_at(ctx, 2, 0, 2) == 0);
  ctx.disable(gl::TEXTURE_2D);
  FragmentSpan plain = span;
  plain.x0 = 3;
  plain.count = 1;
  plain.codes = {9, 8, 7, 6};
  ctx.pixel_fragments(plain);  // no texturing: unchanged
  CHECK(code_at(ctx, 3, 0, 0) == 9);
  CHECK(code_at(ctx, 3, 0, 3) == 6);
}

TEST_CASE("texture entry points: binding, names, parameters, units and errors") {
  Context ctx(profile_named("geforce256"), 4, 4);
  std::uint32_t names[3] = {};
  ctx.genTextures(3, names);
  CHECK(names[0] == 1);
  CHECK(names[1] == 2);
  CHECK(names[2] == 3);
  ctx.bindTexture(gl::TEXTURE_2D, names[1]);
  CHECK(ctx.texture_unit(0).bound_2d == 2);
  ctx.bindTexture(gl::TEXTURE_1D, names[1]);  // already a 2D texture
  CHECK(ctx.getError() == gl::INVALID_OPERATION);
  ctx.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_WRAP_S, gl::CLAMP_TO_EDGE);
  const double border[4] = {2, 0.5, -1, 1};
  ctx.texParameterfv(gl::TEXTURE_2D, gl::TEXTURE_BORDER_COLOR, border);
  const TextureObject& t = ctx.texture_objects().at(2);
  CHECK(t.params.wrap_s == gl::CLAMP_TO_EDGE);
  CHECK(t.params.border_color == std::array<double, 4>{1, 0.5, 0, 1});
  ctx.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MAG_FILTER, gl::LINEAR_MIPMAP_LINEAR);
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  CHECK(t.params.mag_filter == gl::LINEAR);
  ctx.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_BASE_LEVEL, -1);
  CHECK(ctx.getError() == gl::INVALID_VALUE);
  ctx.deleteTextures(1, &names[1]);
  CHECK(ctx.texture_unit(0).bound_2d == 0);  // deleting a bound texture binds 0
  ctx.activeTexture(gl::TEXTURE1);
  CHECK(ctx.active_texture_unit() == 1);
  ctx.activeTexture(gl::TEXTURE2);  // geforce256: MAX_TEXTURE_UNITS = 2
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  CHECK(ctx.active_texture_unit() == 1);
  ctx.clientActiveTexture(gl::TEXTURE1);
  CHECK(ctx.client_active_texture_unit() == 1);
  ctx.enable(gl::TEXTURE_1D);
  CHECK(ctx.isEnabled(gl::TEXTURE_1D));
  ctx.activeTexture(gl::TEXTURE0);
  CHECK_FALSE(ctx.isEnabled(gl::TEXTURE_1D));  // per unit
  // Texture environment.
  ctx.texEnvi(gl::TEXTURE_ENV, gl::TEXTURE_ENV_MODE, gl::COMBINE);
  ctx.texEnvi(gl::TEXTURE_ENV, gl::COMBINE_RGB, gl::DOT3_RGBA);
  ctx.texEnvi(gl::TEXTURE_ENV, gl::SOURCE1_RGB, gl::PRIMARY_COLOR);
  ctx.texEnvi(gl::TEXTURE_ENV, gl::OPERAND2_ALPHA, gl::ONE_MINUS_SRC_ALPHA);
  ctx.texEnvf(gl::TEXTURE_ENV, gl::RGB_SCALE, 4.0);
  const double env_color[4] = {0.25, 1.5, -0.5, 1};
  ctx.texEnvfv(gl::TEXTURE_ENV, gl::TEXTURE_ENV_COLOR, env_color);
  CHECK(ctx.getError() == gl::NO_ERROR);
  const TexEnvState& e = ctx.texenv(0);
  CHECK(e.mode == gl::COMBINE);
  CHECK(e.combine_rgb == gl::DOT3_RGBA);
  CHECK(e.source_rgb[1] == gl::PRIMARY_COLOR);
  CHECK(e.operand_alpha[2] == gl::ONE_MINUS_SRC_ALPHA);
  CHECK(e.rgb_scale == 4);
  CHECK(e.color == std::array<double, 4>{0.25, 1, 0, 1});
  ctx.texEnvf(gl::TEXTURE_ENV, gl::ALPHA_SCALE, 3.0);
  CHECK(ctx.getError() == gl::INVALID_VALUE);
  ctx.texEnvi(gl::TEXTURE_ENV, gl::OPERAND0_ALPHA, gl::SRC_COLOR);
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  ctx.texEnvi(gl::TEXTURE_ENV, gl::COMBINE_ALPHA, gl::DOT3_RGB);
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  ctx.texEnvi(gl::TEXTURE_2D, gl::TEXTURE_ENV_MODE, gl::REPLACE);
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  CHECK(ctx.texenv(0).alpha_scale == 1);
  CHECK(ctx.texenv(0).mode == gl::COMBINE);
}

TEST_CASE("draw: the planned shading path equals the full path on random textured scenes") {
  std::mt19937 rng(777);
  const GLenum modes[6] = {gl::REPLACE, gl::MODULATE, gl::DECAL, gl::BLEND, gl::ADD, gl::COMBINE};
  const BaseFormat bases[6] = {BaseFormat::Alpha, BaseFormat::Luminance, BaseFormat::LuminanceAlpha,
                               BaseFormat::Intensity, BaseFormat::RGB, BaseFormat::RGBA};
  const GLenum filters[6] = {gl::NEAREST, gl::LINEAR, gl::NEAREST_MIPMAP_NEAREST, gl::LINEAR_MIPMAP_NEAREST,
                             gl::NEAREST_MIPMAP_LINEAR, gl::LINEAR_MIPMAP_LINEAR};
  const GLenum srcs[4] = {gl::TEXTURE, gl::CONSTANT, gl::PRIMARY_COLOR, gl::PREVIOUS};
  for (const char* prof : {"geforce256", "rgba10", "ideal"}) {
    for (int trial = 0; trial < 12; ++trial) {
      Context a(profile_named(prof), 16, 16), b(profile_named(prof), 16, 16);
      b.set_full_shading(true);
      const std::uint32_t seed = static_cast<std::uint32_t>(rng());
      for (Context* c : {&a, &b}) {
        std::mt19937 r(seed);
        ortho_window(*c);
        for (int u = 0; u < c->profile().texture_units; ++u) {
          c->activeTexture(gl::TEXTURE0 + static_cast<GLenum>(u));
          c->bindTexture(gl::TEXTURE_2D, static_cast<std::uint32_t>(u + 1));
          const BaseFormat base = bases[r() % 6];
          for (int l = 0; l <= 2; ++l) {
            const int n = 4 >> l;
            std::vector<std::uint16_t> codes(static_cast<std::size_t>(n * n * component_count(base)));
            for (auto& k : codes) k = static_cast<std::uint16_t>(r() % 256);
            set_level(*c, gl::TEXTURE_2D, l, base, n, n, codes);
          }
          c->texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MIN_FILTER, filters[r() % 6]);
          if (r() % 4 != 0) c->enable(gl::TEXTURE_2D);
          c->texEnvi(gl::TEXTURE_ENV, gl::TEXTURE_ENV_MODE, modes[r() % 6]);
          c->texEnvi(gl::TEXTURE_ENV, gl::SOURCE0_RGB, srcs[r() % 4]);
          c->texEnvi(gl::TEXTURE_ENV, gl::SOURCE1_ALPHA, srcs[r() % 4]);
          c->texEnvi(gl::TEXTURE_ENV, gl::COMBINE_RGB, (r() % 2) ? gl::DOT3_RGB : gl::ADD_SIGNED);
        }
        if (r() % 2) c->enable(gl::COLOR_SUM);
        c->begin(gl::TRIANGLES);
        for (int v = 0; v < 6; ++v) {
          c->color4((r() % 256) / 255.0, (r() % 256) / 255.0, (r() % 256) / 255.0, (r() % 256) / 255.0);
          c->secondaryColor3((r() % 256) / 255.0, (r() % 256) / 255.0, (r() % 256) / 255.0);
          for (int u = 0; u < c->profile().texture_units; ++u)
            c->multiTexCoord4(gl::TEXTURE0 + static_cast<GLenum>(u), (r() % 100) / 25.0 - 2, (r() % 100) / 25.0 - 2, 0,
                              1 + (r() % 3));
          c->vertex2((r() % 170) / 10.0, (r() % 170) / 10.0);
        }
        c->end();
      }
      REQUIRE_MESSAGE(a.framebuffer().codes() == b.framebuffer().codes(), prof << " trial " << trial << "\n" << a.explain_shading());
      REQUIRE(a.framebuffer().values() == b.framebuffer().values());
    }
  }
}

TEST_CASE("draw: the shading plan is reported before each draw") {
  Context ctx(profile_named("geforce256"), 2, 2);
  ortho_window(ctx);
  set_level(ctx, gl::TEXTURE_2D, 0, BaseFormat::RGB, 1, 1, {10, 20, 30});
  ctx.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MIN_FILTER, gl::NEAREST);
  ctx.enable(gl::TEXTURE_2D);
  ctx.activeTexture(gl::TEXTURE1);
  ctx.bindTexture(gl::TEXTURE_2D, 5);
  set_level(ctx, gl::TEXTURE_2D, 0, BaseFormat::RGBA, 1, 1, {1, 2, 3, 4});
  ctx.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MIN_FILTER, gl::NEAREST);
  ctx.enable(gl::TEXTURE_2D);
  ctx.texEnvi(gl::TEXTURE_ENV, gl::TEXTURE_ENV_MODE, gl::REPLACE);
  std::vector<std::string> log;
  ctx.set_explain_callback([&](const std::string& s) { log.push_back(s); });
  quad(ctx, 0, 0, 2, 2);
  REQUIRE(log.size() == 1);
  CHECK(log[0].find("texture unit 2") == std::string::npos);  // geforce256 has 2 units
  CHECK(log[0].find("texture unit 0: skipped") != std::string::npos);
  CHECK(log[0].find("texture unit 1: sample TEXTURE_2D") != std::string::npos);
  CHECK(code_at(ctx, 0, 0, 0) == 1);  // unit 1 REPLACE with RGBA
  CHECK(code_at(ctx, 0, 0, 3) == 4);
}

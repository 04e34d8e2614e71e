// Drawing through the Context: primitive assembly, fill rule, colour
// interpolation, flat shading, errors (sim/draw.cpp, sim/context_geometry.cpp).
#include <doctest/doctest.h>

#include <cmath>

#include "draw_test_util.h"

using namespace ffsim;
using namespace ffsim::test;

TEST_CASE("draw: smooth colour across a quad is the exact barycentric value rounded once") {
  Context ctx(profile_named("geforce256"), 4, 1);
  ortho_window(ctx);
  ctx.begin(gl::QUADS);
  ctx.color3(0, 0, 0);
  ctx.vertex2(0, 0);
  ctx.color3(1, 0, 0);
  ctx.vertex2(4, 0);
  ctx.vertex2(4, 1);
  ctx.color3(0, 0, 0);
  ctx.vertex2(0, 1);
  ctx.end();
  // R at centre x + 1/2 is 255·(x + 1/2)/4: 31.875, 95.625, 159.375, 223.125 -> rounded half up.
  CHECK(code_at(ctx, 0, 0, 0) == 32);
  CHECK(code_at(ctx, 1, 0, 0) == 96);
  CHECK(code_at(ctx, 2, 0, 0) == 159);
  CHECK(code_at(ctx, 3, 0, 0) == 223);
  CHECK(code_at(ctx, 2, 0, 3) == 255);
  CHECK(ctx.getError() == gl::NO_ERROR);
}

TEST_CASE("draw: flat shading takes the provoking vertex of each primitive (GL121 Table 2.9)") {
  Context ctx(profile_named("geforce256"), 8, 2);
  ortho_window(ctx);
  ctx.shadeModel(gl::FLAT);
  // Strip of 2 triangles over x in [0,4]: triangle 0 = v0 v1 v2 (provoking v2), triangle 1 = v1 v2 v3 (v3).
  ctx.begin(gl::TRIANGLE_STRIP);
  ctx.color3(1, 0, 0);
  ctx.vertex2(0, 0);
  ctx.color3(0, 1, 0);
  ctx.vertex2(0, 2);
  ctx.color3(0, 0, 1);
  ctx.vertex2(4, 0);
  ctx.color3(1, 1, 1);
  ctx.vertex2(4, 2);
  ctx.end();
  CHECK(code_at(ctx, 0, 0, 2) == 255);  // below the diagonal: triangle 0, blue
  CHECK(code_at(ctx, 0, 0, 0) == 0);
  CHECK(code_at(ctx, 3, 1, 0) == 255);  // above it: triangle 1, white
  CHECK(code_at(ctx, 3, 1, 1) == 255);
  // POLYGON: the first vertex.
  ctx.begin(gl::POLYGON);
  ctx.color3(1, 0, 1);
  ctx.vertex2(4, 0);
  ctx.color3(0, 0, 0);
  ctx.vertex2(8, 0);
  ctx.vertex2(8, 2);
  ctx.vertex2(4, 2);
  ctx.end();
  CHECK(code_at(ctx, 6, 1, 0) == 255);
  CHECK(code_at(ctx, 6, 1, 2) == 255);
}

TEST_CASE("draw: a triangle fan around a point leaves no pixel inside undrawn") {
  Context ctx(profile_named("geforce256"), 20, 20);
  ortho_window(ctx);
  const double cx = 10.5, cy = 9.5, r = 8.2;
  ctx.begin(gl::TRIANGLE_FAN);
  ctx.vertex2(cx, cy);
  for (int i = 0; i <= 16; ++i) {
    const double a = 2 * 3.14159265358979323846 * i / 16;
    ctx.color3((i % 3) / 2.0, ((i + 1) % 3) / 2.0, 1);  // colours differ per triangle; blue always 1
    ctx.vertex2(cx + r * std::cos(a), cy + r * std::sin(a));
  }
  ctx.end();
  // Every pixel whose centre is within the inscribed circle (radius r·cos(pi/16) minus
  // a pixel of margin) must have been written (blue = 255); corners not.
  int checked = 0;
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 20; ++x) {
      const double d = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
      if (d < r * std::cos(3.14159265358979323846 / 16) - 0.1) {
        ++checked;
        CHECK_MESSAGE(code_at(ctx, x, y, 2) == 255, "pixel " << x << "," << y);
      }
      if (d > r + 0.1) CHECK(code_at(ctx, x, y, 2) == 0);
    }
  CHECK(checked > 180);
}

TEST_CASE("draw: off-screen, degenerate and partial primitives") {
  Context ctx(profile_named("geforce256"), 8, 8);
  ortho_window(ctx);
  quad(ctx, 20, 20, 30, 30);  // entirely outside the view volume
  ctx.begin(gl::TRIANGLES);
  ctx.vertex2(1, 1);
  ctx.vertex2(5, 5);
  ctx.vertex2(3, 3);  // collinear
  ctx.vertex2(1, 1);  // incomplete trailing triangle: ignored
  ctx.end();
  for (auto k : ctx.framebuffer().codes()) REQUIRE(k == 0);
  quad(ctx, -4, -4, 2, 2);  // clipped at the left/bottom planes: pixels (0..1, 0..1)
  int n = 0;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) n += code_at(ctx, x, y, 0) == 255;
  CHECK(n == 4);
  CHECK(ctx.getError() == gl::NO_ERROR);
}

TEST_CASE("draw: the viewport places fragments, depth range is clamped and stored") {
  Context ctx(profile_named("geforce256"), 16, 16);
  ctx.viewport(8, 8, 8, 8);
  ctx.depthRange(0.25, 0.75);
  // Identity matrices: NDC = object. The quad (-1,-1)-(0,0) is the viewport's lower-left quarter.
  ctx.begin(gl::QUADS);
  ctx.vertex2(-1, -1);
  ctx.vertex2(0, -1);
  ctx.vertex2(0, 0);
  ctx.vertex2(-1, 0);
  ctx.end();
  CHECK(code_at(ctx, 8, 8, 0) == 255);
  CHECK(code_at(ctx, 11, 11, 0) == 255);
  CHECK(code_at(ctx, 12, 12, 0) == 0);
  CHECK(code_at(ctx, 7, 7, 0) == 0);
  CHECK(ctx.viewport_box() == std::array<int, 4>{8, 8, 8, 8});
  CHECK(ctx.depth_range() == std::array<double, 2>{0.25, 0.75});
  ctx.depthRange(-1, 2);
  CHECK(ctx.depth_range() == std::array<double, 2>{0, 1});
}

TEST_CASE("draw: GL errors leave state unchanged") {
  Context ctx(profile_named("geforce256"), 4, 4);
  ctx.end();
  CHECK(ctx.getError() == gl::INVALID_OPERATION);
  ctx.begin(gl::POINTS);
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  CHECK_FALSE(ctx.in_begin_end());
  ctx.begin(gl::TRIANGLES);
  ctx.viewport(0, 0, 1, 1);
  CHECK(ctx.getError() == gl::INVALID_OPERATION);
  ctx.begin(gl::TRIANGLES);
  CHECK(ctx.getError() == gl::INVALID_OPERATION);
  ctx.end();
  CHECK(ctx.viewport_box() == std::array<int, 4>{0, 0, 4, 4});
  ctx.viewport(0, 0, -1, 2);
  CHECK(ctx.getError() == gl::INVALID_VALUE);
  ctx.shadeModel(gl::LINEAR);
  CHECK(ctx.getError() == gl::INVALID_ENUM);
  CHECK(ctx.shade_model() == gl::SMOOTH);
  ctx.multiTexCoord2(gl::TEXTURE0 + 2, 1, 1);  // geforce256 has 2 units
  CHECK(ctx.getError() == gl::INVALID_ENUM);
}

TEST_CASE("raster position: window coordinates, validity, colour and texture coordinates") {
  Context ctx(profile_named("geforce256"), 10, 10);
  ortho_window(ctx);
  ctx.color4(0.5, 2.0, -1, 1);
  ctx.texCoord4(1, 2, 3, 4);
  ctx.rasterPos2(3.25, 4.5);
  const RasterPosState& rp = ctx.raster_pos();
  CHECK(rp.valid);
  CHECK(rp.x == doctest::Approx(3.25));
  CHECK(rp.y == doctest::Approx(4.5));
  CHECK(rp.z == doctest::Approx(0.5));  // z = 0 -> NDC 0 -> depth range midpoint
  CHECK(rp.color == std::array<double, 4>{0.5, 1.0, 0.0, 1.0});  // clamped
  CHECK(rp.texcoord[0] == std::array<double, 4>{1, 2, 3, 4});
  ctx.rasterPos2(-1, 5);  // outside the view volume
  CHECK_FALSE(ctx.raster_pos().valid);
  ctx.rasterPos2(10, 10);  // on the boundary: inside
  CHECK(ctx.raster_pos().valid);
}

TEST_CASE("draw: a viewport far outside the window draws nothing and does not overflow") {
  Context ctx(profile_named("geforce256"), 4, 4);
  ctx.viewport(-2147483647 - 1, 2147483647 - 100, 16384, 16384);
  ctx.begin(gl::QUADS);
  ctx.vertex2(-1, -1);
  ctx.vertex2(1, -1);
  ctx.vertex2(1, 1);
  ctx.vertex2(-1, 1);
  ctx.end();
  for (auto k : ctx.framebuffer().codes()) REQUIRE(k == 0);
  CHECK(ctx.getError() == gl::NO_ERROR);
}

TEST_CASE("draw: QUAD_STRIP assembles quads (2i, 2i+1, 2i+3, 2i+2) with the last pair's colour when flat") {
  Context ctx(profile_named("geforce256"), 4, 2);
  ortho_window(ctx);
  ctx.shadeModel(gl::FLAT);
  ctx.begin(gl::QUAD_STRIP);
  ctx.color3(1, 0, 0);
  ctx.vertex2(0, 0);
  ctx.vertex2(0, 2);
  ctx.color3(0, 1, 0);
  ctx.vertex2(2, 0);
  ctx.color3(0, 0, 1);
  ctx.vertex2(2, 2);  // provoking vertex of quad 0 (GL121 Table 2.9: 2i + 2)
  ctx.color3(1, 1, 0);
  ctx.vertex2(4, 0);
  ctx.color3(1, 1, 1);
  ctx.vertex2(4, 2);  // provoking vertex of quad 1
  ctx.end();
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      CHECK(code_at(ctx, x, y, 2) == 255);
      CHECK(code_at(ctx, x, y, 0) == 0);
      CHECK(code_at(ctx, x + 2, y, 0) == 255);
      CHECK(code_at(ctx, x + 2, y, 1) == 255);
      CHECK(code_at(ctx, x + 2, y, 2) == 255);
    }
}

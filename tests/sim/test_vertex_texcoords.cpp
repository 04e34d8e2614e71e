// Texture coordinates through the texture matrix (GL121 §2.10.2): the raster
// position and drawn triangles with the fast paths equal the reference (fast
// paths off) and GLM's product computed here, bit for bit, whatever the
// coordinates (±0, ±inf, NaN, large and small values) and matrices, and drawn
// triangles follow matrix changes between glBegin/glEnd pairs. (Written for an
// identity-matrix shortcut in make_vertex that was measured slower and dropped,
// docs/performance.md 14; kept as a test of the texture matrix.)
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <glm/mat4x4.hpp>

#include "draw_test_util.h"

using namespace ffsim;
using namespace ffsim::test;

namespace {

bool same_bits(const std::array<double, 4>& a, const std::array<double, 4>& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * 4) == 0;
}

void load_texture_matrix(Context& c, int unit, const double m[16]) {
  c.activeTexture(gl::TEXTURE0 + static_cast<GLenum>(unit));
  c.matrixMode(gl::TEXTURE);
  c.loadMatrix(m);
  c.matrixMode(gl::MODELVIEW);
  c.activeTexture(gl::TEXTURE0);
}

}  // namespace

TEST_CASE("texture matrix: the product for every kind of coordinate, with and without the fast paths") {
  const double specials[] = {0.0, -0.0, 1.0, -1.0, 0.5, 1e-310, -1e-310, 1e300, -1e300, INFINITY, -INFINITY, NAN, 3.25};
  const double identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  const double signed_zeros[16] = {1, -0.0, 0, -0.0, -0.0, 1, -0.0, 0, 0, -0.0, 1, -0.0, -0.0, 0, -0.0, 1};
  const double scaled[16] = {2, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 1, 0, 0.25, 0, 0, 1};
  const double* matrices[] = {identity, signed_zeros, scaled};
  std::mt19937 rng(8);
  Context fast(profile_named("geforce256"), 8, 8), ref(profile_named("geforce256"), 8, 8);
  ref.set_fast_paths(false);
  int compared = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int m = static_cast<int>(rng() % 3), unit = static_cast<int>(rng() % 2);
    double tc[4];
    for (double& x : tc) x = specials[rng() % std::size(specials)];
    for (Context* c : {&fast, &ref}) {
      load_texture_matrix(*c, unit, matrices[m]);
      c->multiTexCoord4(gl::TEXTURE0 + static_cast<GLenum>(unit), tc[0], tc[1], tc[2], tc[3]);
      c->rasterPos4(0, 0, 0, 1);
    }
    glm::dmat4 M;
    std::memcpy(&M[0][0], matrices[m], sizeof(double) * 16);
    const glm::dvec4 expect = M * glm::dvec4(tc[0], tc[1], tc[2], tc[3]);
    CAPTURE(trial);
    const auto& got = fast.raster_pos().texcoord[static_cast<std::size_t>(unit)];
    REQUIRE(same_bits(got, ref.raster_pos().texcoord[static_cast<std::size_t>(unit)]));
    // Against GLM compiled here: NaN's sign and payload follow the compiler's
    // operand order, so a NaN only has to be a NaN.
    for (int q = 0; q < 4; ++q) {
      const double e = expect[q], g = got[static_cast<std::size_t>(q)];
      if (std::isnan(e)) REQUIRE(std::isnan(g));
      else REQUIRE(std::memcmp(&e, &g, sizeof e) == 0);
    }
    ++compared;
  }
  CHECK(compared == 3000);
}

TEST_CASE("texture matrix: drawn triangles follow matrix changes between glBegin/glEnd pairs") {
  // A textured quad drawn with the identity, then a scaling texture matrix, then
  // the identity again: the fast context equals the reference after every draw.
  Context fast(profile_named("geforce256"), 16, 16), ref(profile_named("geforce256"), 16, 16);
  ref.set_fast_paths(false);
  std::vector<std::uint16_t> texels(4 * 4 * 4);
  for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = static_cast<std::uint16_t>((i * 37) % 256);
  for (Context* c : {&fast, &ref}) {
    ortho_window(*c);
    set_level(*c, gl::TEXTURE_2D, 0, BaseFormat::RGBA, 4, 4, texels);
    c->texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MIN_FILTER, gl::NEAREST);
    c->texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MAG_FILTER, gl::NEAREST);
    c->enable(gl::TEXTURE_2D);
  }
  const double identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  const double scaled[16] = {3, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1, 0, 0.125, 0.25, 0, 1};
  const double* sequence[] = {identity, scaled, identity, scaled};
  int differ_from_first = 0;
  BufferVector<std::uint16_t> first;
  for (const double* m : sequence) {
    for (Context* c : {&fast, &ref}) {
      load_texture_matrix(*c, 0, m);
      c->begin(gl::QUADS);
      const double corners[4][2] = {{0, 0}, {16, 0}, {16, 16}, {0, 16}};
      for (const auto& p : corners) {
        c->texCoord2(p[0] / 16, p[1] / 16);
        c->vertex2(p[0], p[1]);
      }
      c->end();
    }
    REQUIRE(fast.framebuffer().codes() == ref.framebuffer().codes());
    if (first.empty()) first = fast.framebuffer().codes();
    differ_from_first += fast.framebuffer().codes() != first;
  }
  CHECK(differ_from_first == 2);  // the scaled draws change the image (the test sees the matrix)
}

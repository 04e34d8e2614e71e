// Random scenes for the fast-path tests (tests/sim/test_fast_*.cpp): the same
// seed replays the same GL calls on any Context, so a scene drawn with
// set_fast_paths(true) and with set_fast_paths(false) must leave identical
// buffers (docs/performance.md).
#pragma once
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "draw_test_util.h"
#include "sim/hash.h"

namespace ffsim::test {

inline const char* const kFastProfiles[] = {"geforce256", "rgba10", "rgba12", "float32", "ideal"};

struct SceneRng {
  std::mt19937 g;
  explicit SceneRng(std::uint32_t seed) : g(seed) {}
  int i(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(g); }  // inclusive
  double d(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(g); }
  bool b(int percent = 50) { return i(0, 99) < percent; }
  template <class T, std::size_t N>
  T pick(const T (&a)[N]) { return a[static_cast<std::size_t>(i(0, static_cast<int>(N) - 1))]; }
};

// What a scene may use; tests narrow it to aim at one optimisation.
struct SceneOptions {
  bool textures = true;
  bool combiners = true;   // sometimes enable the register combiners
  bool fragment_ops = true;  // random blend / alpha / stencil / depth / masks
  bool copy_pixels = false;  // also CopyPixels passes
  bool all_modes = true;     // every polygon mode (else GL_TRIANGLES only)
  int triangles = 6;         // 3·triangles vertices per glBegin/glEnd
};

inline void random_texture(Context& c, SceneRng& r, int unit, std::uint32_t name) {
  c.activeTexture(gl::TEXTURE0 + static_cast<GLenum>(unit));
  c.bindTexture(gl::TEXTURE_2D, name);
  static const GLenum kFormats[] = {gl::RGBA8, gl::RGB8, gl::LUMINANCE8, gl::ALPHA8, gl::INTENSITY8,
                                    gl::LUMINANCE8_ALPHA8, gl::RGBA, gl::RGB, gl::LUMINANCE};
  const GLenum ifmt = r.pick(kFormats);
  int w = 1 << r.i(0, 5), h = 1 << r.i(0, 5);
  const bool mip = r.b(25);
  for (int level = 0;; ++level) {
    std::vector<std::uint8_t> data(4 * static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    for (auto& v : data) v = static_cast<std::uint8_t>(r.i(0, 255));
    c.texImage2D(gl::TEXTURE_2D, level, ifmt, w, h, 0, gl::RGBA, gl::UNSIGNED_BYTE, data.data());
    if (!mip || (w == 1 && h == 1)) break;
    w = std::max(1, w / 2);
    h = std::max(1, h / 2);
  }
  static const GLenum kMag[] = {gl::NEAREST, gl::LINEAR};
  static const GLenum kMin[] = {gl::NEAREST, gl::LINEAR, gl::NEAREST_MIPMAP_NEAREST, gl::LINEAR_MIPMAP_LINEAR,
                                gl::NEAREST_MIPMAP_LINEAR, gl::LINEAR_MIPMAP_NEAREST};
  static const GLenum kWrap[] = {gl::REPEAT, gl::CLAMP, gl::CLAMP_TO_EDGE};
  const GLenum mag = r.pick(kMag);
  // Mostly the fast path's case (MIN_FILTER == MAG_FILTER), sometimes λ matters.
  const GLenum min = r.b(70) ? mag : (mip ? r.pick(kMin) : r.pick(kMag));
  c.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MAG_FILTER, mag);
  c.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_MIN_FILTER, min);
  c.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_WRAP_S, r.pick(kWrap));
  c.texParameteri(gl::TEXTURE_2D, gl::TEXTURE_WRAP_T, r.pick(kWrap));
  const double border[4] = {r.d(0, 1), r.d(0, 1), r.d(0, 1), r.d(0, 1)};
  c.texParameterfv(gl::TEXTURE_2D, gl::TEXTURE_BORDER_COLOR, border);
  c.enable(gl::TEXTURE_2D);

  static const GLenum kModes[] = {gl::REPLACE, gl::MODULATE, gl::DECAL, gl::BLEND, gl::ADD, gl::COMBINE};
  const GLenum mode = r.pick(kModes);
  c.texEnvi(gl::TEXTURE_ENV, gl::TEXTURE_ENV_MODE, mode);
  const double env_color[4] = {r.d(0, 1), r.d(0, 1), r.d(0, 1), r.d(0, 1)};
  c.texEnvfv(gl::TEXTURE_ENV, gl::TEXTURE_ENV_COLOR, env_color);
  if (mode == gl::COMBINE) {
    static const GLenum kRgb[] = {gl::REPLACE, gl::MODULATE, gl::ADD, gl::ADD_SIGNED, gl::INTERPOLATE, gl::SUBTRACT,
                                  gl::DOT3_RGB, gl::DOT3_RGBA};
    static const GLenum kAlpha[] = {gl::REPLACE, gl::MODULATE, gl::ADD, gl::ADD_SIGNED, gl::INTERPOLATE, gl::SUBTRACT};
    static const GLenum kSrc[] = {gl::TEXTURE, gl::CONSTANT, gl::PRIMARY_COLOR, gl::PREVIOUS};
    static const GLenum kOpRgb[] = {gl::SRC_COLOR, gl::ONE_MINUS_SRC_COLOR, gl::SRC_ALPHA, gl::ONE_MINUS_SRC_ALPHA};
    static const GLenum kOpA[] = {gl::SRC_ALPHA, gl::ONE_MINUS_SRC_ALPHA};
    c.texEnvi(gl::TEXTURE_ENV, gl::COMBINE_RGB, r.pick(kRgb));
    c.texEnvi(gl::TEXTURE_ENV, gl::COMBINE_ALPHA, r.pick(kAlpha));
    for (GLenum k = 0; k < 3; ++k) {
      c.texEnvi(gl::TEXTURE_ENV, gl::SOURCE0_RGB + k, r.pick(kSrc));
      c.texEnvi(gl::TEXTURE_ENV, gl::SOURCE0_ALPHA + k, r.pick(kSrc));
      c.texEnvi(gl::TEXTURE_ENV, gl::OPERAND0_RGB + k, r.pick(kOpRgb));
      c.texEnvi(gl::TEXTURE_ENV, gl::OPERAND0_ALPHA + k, r.pick(kOpA));
    }
    c.texEnvf(gl::TEXTURE_ENV, gl::RGB_SCALE, 1 << r.i(0, 2));
    c.texEnvf(gl::TEXTURE_ENV, gl::ALPHA_SCALE, 1 << r.i(0, 2));
  }
  c.activeTexture(gl::TEXTURE0);
}

inline void random_combiners(Context& c, SceneRng& r) {
  static const GLenum kReg[] = {gl::ZERO, gl::CONSTANT_COLOR0_NV, gl::CONSTANT_COLOR1_NV, gl::PRIMARY_COLOR_NV,
                                gl::SECONDARY_COLOR_NV, gl::SPARE0_NV, gl::SPARE1_NV, gl::TEXTURE0, gl::TEXTURE1,
                                gl::FOG};
  static const GLenum kMap[] = {gl::UNSIGNED_IDENTITY_NV, gl::UNSIGNED_INVERT_NV, gl::EXPAND_NORMAL_NV,
                                gl::EXPAND_NEGATE_NV,     gl::HALF_BIAS_NORMAL_NV, gl::HALF_BIAS_NEGATE_NV,
                                gl::SIGNED_IDENTITY_NV,   gl::SIGNED_NEGATE_NV};
  static const GLenum kOut[] = {gl::DISCARD_NV, gl::SPARE0_NV, gl::SPARE1_NV, gl::TEXTURE0, gl::PRIMARY_COLOR_NV};
  static const GLenum kScale[] = {gl::NONE, gl::SCALE_BY_TWO_NV, gl::SCALE_BY_FOUR_NV, gl::SCALE_BY_ONE_HALF_NV};
  static const GLenum kVars[] = {gl::VARIABLE_A_NV, gl::VARIABLE_B_NV, gl::VARIABLE_C_NV, gl::VARIABLE_D_NV};
  c.enable(gl::REGISTER_COMBINERS_NV);
  const float c0[4] = {static_cast<float>(r.d(0, 1)), static_cast<float>(r.d(0, 1)), static_cast<float>(r.d(0, 1)),
                       static_cast<float>(r.d(0, 1))};
  const float c1[4] = {static_cast<float>(r.d(0, 1)), static_cast<float>(r.d(0, 1)), static_cast<float>(r.d(0, 1)),
                       static_cast<float>(r.d(0, 1))};
  c.combinerParameterfv(gl::CONSTANT_COLOR0_NV, c0);
  c.combinerParameterfv(gl::CONSTANT_COLOR1_NV, c1);
  c.combinerParameteri(gl::NUM_GENERAL_COMBINERS_NV, r.i(1, 2));
  c.combinerParameteri(gl::COLOR_SUM_CLAMP_NV, r.i(0, 1));
  for (GLenum st = 0; st < 2; ++st)
    for (GLenum portion : {gl::RGB, gl::ALPHA}) {
      for (GLenum v : kVars) {
        GLenum usage = portion == gl::RGB ? (r.b(70) ? gl::RGB : gl::ALPHA) : (r.b(70) ? gl::ALPHA : gl::BLUE);
        c.combinerInput(gl::COMBINER0_NV + st, portion, v, r.pick(kReg), r.pick(kMap), usage);
      }
      const bool rgb = portion == gl::RGB;
      const bool bias = r.b(20), scale_half = false;
      (void)scale_half;
      GLenum ab = r.pick(kOut), cd = r.pick(kOut), sum = r.pick(kOut);
      if (ab != gl::DISCARD_NV && ab == cd) cd = gl::DISCARD_NV;  // distinct outputs (GL error otherwise)
      if (sum != gl::DISCARD_NV && (sum == ab || sum == cd)) sum = gl::DISCARD_NV;
      const GLenum scale = r.pick(kScale);
      c.combinerOutput(gl::COMBINER0_NV + st, portion, ab, cd, sum, scale,
                       bias && scale != gl::SCALE_BY_ONE_HALF_NV ? gl::BIAS_BY_NEGATIVE_ONE_HALF_NV : gl::NONE,
                       rgb && r.b(30), rgb && r.b(30), r.b(20));
    }
  static const GLenum kFinalReg[] = {gl::ZERO, gl::SPARE0_NV, gl::SPARE1_NV, gl::PRIMARY_COLOR_NV, gl::TEXTURE0,
                                     gl::TEXTURE1, gl::CONSTANT_COLOR0_NV, gl::E_TIMES_F_NV,
                                     gl::SPARE0_PLUS_SECONDARY_COLOR_NV, gl::SECONDARY_COLOR_NV};
  static const GLenum kFinalMap[] = {gl::UNSIGNED_IDENTITY_NV, gl::UNSIGNED_INVERT_NV};
  for (GLenum v : {gl::VARIABLE_A_NV, gl::VARIABLE_B_NV, gl::VARIABLE_C_NV, gl::VARIABLE_D_NV}) {
    c.finalCombinerInput(v, r.pick(kFinalReg), r.pick(kFinalMap), gl::RGB);
  }
  for (GLenum v : {gl::VARIABLE_E_NV, gl::VARIABLE_F_NV})
    c.finalCombinerInput(v, r.pick(kReg), r.pick(kFinalMap), r.b(70) ? gl::RGB : gl::ALPHA);
  c.finalCombinerInput(gl::VARIABLE_G_NV, r.pick(kReg), r.pick(kFinalMap), gl::ALPHA);
}

inline void random_fragment_ops(Context& c, SceneRng& r) {
  static const GLenum kFunc[] = {gl::NEVER, gl::LESS, gl::EQUAL, gl::LEQUAL, gl::GREATER, gl::NOTEQUAL, gl::GEQUAL, gl::ALWAYS};
  static const GLenum kFactor[] = {gl::ZERO, gl::ONE, gl::SRC_COLOR, gl::ONE_MINUS_SRC_COLOR, gl::DST_COLOR,
                                   gl::ONE_MINUS_DST_COLOR, gl::SRC_ALPHA, gl::ONE_MINUS_SRC_ALPHA, gl::DST_ALPHA,
                                   gl::ONE_MINUS_DST_ALPHA, gl::CONSTANT_COLOR, gl::CONSTANT_ALPHA, gl::SRC_ALPHA_SATURATE};
  static const GLenum kEq[] = {gl::FUNC_ADD, gl::FUNC_SUBTRACT, gl::FUNC_REVERSE_SUBTRACT, gl::MIN, gl::MAX};
  static const GLenum kSop[] = {gl::KEEP, gl::ZERO, gl::REPLACE, gl::INCR, gl::DECR, gl::INVERT, gl::INCR_WRAP, gl::DECR_WRAP};
  if (r.b(40)) { c.enable(gl::BLEND); c.blendFunc(r.pick(kFactor), r.b(80) ? r.pick(kFactor) : gl::ONE); c.blendEquation(r.pick(kEq)); }
  else c.disable(gl::BLEND);
  c.blendColor(r.d(0, 1), r.d(0, 1), r.d(0, 1), r.d(0, 1));
  if (r.b(30)) { c.enable(gl::ALPHA_TEST); c.alphaFunc(r.pick(kFunc), r.d(0, 1)); } else c.disable(gl::ALPHA_TEST);
  if (r.b(30)) {
    c.enable(gl::STENCIL_TEST);
    c.stencilFunc(r.pick(kFunc), r.i(0, 255), static_cast<std::uint32_t>(r.i(0, 255)));
    c.stencilOp(r.pick(kSop), r.pick(kSop), r.pick(kSop));
  } else c.disable(gl::STENCIL_TEST);
  if (r.b(40)) { c.enable(gl::DEPTH_TEST); c.depthFunc(r.pick(kFunc)); } else c.disable(gl::DEPTH_TEST);
  c.depthMask(r.b(80));
  c.colorMask(r.b(85), r.b(85), r.b(85), r.b(85));
  if (r.b(10)) c.enable(gl::SCISSOR_TEST), c.scissor(r.i(0, 20), r.i(0, 20), r.i(5, 40), r.i(5, 40));
  else c.disable(gl::SCISSOR_TEST);
}

inline void random_projection(Context& c, SceneRng& r) {
  c.matrixMode(gl::PROJECTION);
  c.loadIdentity();
  if (r.b(50)) {
    c.ortho(0, c.framebuffer().width(), 0, c.framebuffer().height(), -1, 1);
    c.matrixMode(gl::MODELVIEW);
    c.loadIdentity();
  } else {  // perspective: the window spans x, y in [-1, 1] at z = -2
    c.frustum(-0.5, 0.5, -0.5, 0.5, 1, 10);
    c.matrixMode(gl::MODELVIEW);
    c.loadIdentity();
    c.translate(0, 0, -2);
    c.scale(2.0 / c.framebuffer().width(), 2.0 / c.framebuffer().height(), 1);
    c.translate(-c.framebuffer().width() / 2.0, -c.framebuffer().height() / 2.0, 0);
  }
}

inline void random_vertex(Context& c, SceneRng& r, bool texel_aligned) {
  c.color4(r.d(-0.1, 1.1), r.d(0, 1), r.d(0, 1), r.d(0, 1));
  c.secondaryColor3(r.d(0, 1), r.d(0, 1), r.d(0, 1));
  const double W = c.framebuffer().width(), H = c.framebuffer().height();
  const double x = texel_aligned ? r.i(0, 4) * W / 4 : r.d(-0.2 * W, 1.2 * W);
  const double y = texel_aligned ? r.i(0, 4) * H / 4 : r.d(-0.2 * H, 1.2 * H);
  for (GLenum u = 0; u < 2; ++u) {
    if (texel_aligned) c.multiTexCoord2(gl::TEXTURE0 + u, x / W, y / H);
    else c.multiTexCoord4(gl::TEXTURE0 + u, r.d(-2, 2), r.d(-2, 2), 0, r.b(80) ? 1.0 : r.d(0.5, 2));
  }
  c.vertex3(x, y, r.d(-0.9, 0.9));
}

// With `percent` % chance a random texture `name` on `unit`, else the unit's 2D
// texturing off (the active unit is left at 0 either way).
inline void random_texture_or_off(Context& c, SceneRng& r, int unit, std::uint32_t name, int percent) {
  if (r.b(percent)) {
    random_texture(c, r, unit, name);
    return;
  }
  c.activeTexture(gl::TEXTURE0 + static_cast<GLenum>(unit));
  c.disable(gl::TEXTURE_2D);
  c.activeTexture(gl::TEXTURE0);
}

// Random clear values (depth in [depth_lo, 1]), every buffer cleared, then a
// random projection: how every random scene starts.
inline void random_clear_and_projection(Context& c, SceneRng& r, double depth_lo) {
  c.clearColor(r.d(0, 1), r.d(0, 1), r.d(0, 1), r.d(0, 1));
  c.clearStencil(r.i(0, 255));
  c.clearDepth(r.d(depth_lo, 1));
  c.clear(gl::COLOR_BUFFER_BIT | gl::STENCIL_BUFFER_BIT | gl::DEPTH_BUFFER_BIT);
  random_projection(c, r);
}

// One scene: state, then triangles (and pixel copies). Everything from `seed`.
inline void draw_random_scene(Context& c, std::uint32_t seed, const SceneOptions& opt = {}) {
  SceneRng r(seed);
  random_clear_and_projection(c, r, 0);
  for (int pass = 0; pass < 2; ++pass) {
    if (opt.textures)
      for (int u = 0; u < 2; ++u) random_texture_or_off(c, r, u, static_cast<std::uint32_t>(1 + u + 2 * pass), 60);
    if (opt.combiners && r.b(35)) random_combiners(c, r);
    else c.disable(gl::REGISTER_COMBINERS_NV);
    if (r.b(30)) c.enable(gl::COLOR_SUM); else c.disable(gl::COLOR_SUM);
    c.shadeModel(r.b(80) ? gl::SMOOTH : gl::FLAT);
    if (opt.fragment_ops) random_fragment_ops(c, r);
    const bool aligned = r.b(30);
    static const GLenum kModes[] = {gl::TRIANGLES, gl::TRIANGLE_STRIP, gl::TRIANGLE_FAN,
                                    gl::QUADS,     gl::QUAD_STRIP,     gl::POLYGON};
    c.begin(opt.all_modes ? r.pick(kModes) : gl::TRIANGLES);
    for (int k = 0; k < 3 * opt.triangles; ++k) random_vertex(c, r, aligned);
    c.end();
    if (opt.copy_pixels) {
      c.rasterPos2(r.i(0, 8), r.i(0, 8));
      c.copyPixels(r.i(0, 8), r.i(0, 8), r.i(1, c.framebuffer().width()), r.i(1, c.framebuffer().height()),
                   r.b(70) ? gl::COLOR : gl::STENCIL);
    }
  }
}

inline std::string buffer_hashes(const Context& c) {
  const Framebuffer& fb = c.framebuffer();
  return hash_hex(buffer_hash(fb, BufferKind::Color)) + " " + hash_hex(buffer_hash(fb, BufferKind::Stencil)) + " " +
         hash_hex(buffer_hash(fb, BufferKind::Depth));
}

}  // namespace ffsim::test

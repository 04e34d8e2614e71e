// Helpers shared by the tests/sim/test_draw_*.cpp files.
#pragma once
#include <vector>

#include "sim/context.h"

namespace ffsim::test {

inline const Profile& profile_named(const char* name) { return *find_builtin_profile(name); }

// Window-aligned orthographic projection: object (x, y) = window (x, y).
inline void ortho_window(Context& ctx) {
  ctx.matrixMode(gl::PROJECTION);
  ctx.loadIdentity();
  ctx.ortho(0, ctx.framebuffer().width(), 0, ctx.framebuffer().height(), -1, 1);
  ctx.matrixMode(gl::MODELVIEW);
  ctx.loadIdentity();
}

// Texture data written straight into the bound texture's level (glTexImage is
// the pixel path's work): 8-bit codes; values filled too for float profiles.
inline void set_level(Context& ctx, GLenum target, int level, BaseFormat base, int w, int h,
                      const std::vector<std::uint16_t>& codes, int border = 0) {
  TextureObject& t = ctx.bound_texture(ctx.active_texture_unit(), target);
  if (static_cast<int>(t.levels.size()) <= level) t.levels.resize(static_cast<std::size_t>(level) + 1);
  TextureImage& im = t.levels[static_cast<std::size_t>(level)];
  im.width = w;
  im.height = h;
  im.border = border;
  im.base = base;
  im.bits = 8;
  im.codes = codes;
  im.values.clear();
  for (auto k : codes) im.values.push_back(k / 255.0);
  ++t.version;
}

inline std::uint16_t code_at(const Context& ctx, int x, int y, int c) {
  return ctx.framebuffer().codes()[4 * ctx.framebuffer().index(x, y) + static_cast<std::size_t>(c)];
}

inline void quad(Context& ctx, double x0, double y0, double x1, double y1) {
  ctx.begin(gl::QUADS);
  ctx.vertex2(x0, y0);
  ctx.vertex2(x1, y0);
  ctx.vertex2(x1, y1);
  ctx.vertex2(x0, y1);
  ctx.end();
}

}  // namespace ffsim::test

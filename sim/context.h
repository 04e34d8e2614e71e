// The simulated GL context: all GL state, the framebuffer, and the GL entry
// points, named after the GL calls (ctx.blendEquation(gl::FUNC_SUBTRACT)).
//
// One file per area implements the entry points (sim/context_*.cpp); the state
// each area owns is a plain struct from pipeline/ so that stages are functions of
// (state, input span) and can be tested without a Context.
//
// GL semantics kept throughout: a call that raises an error has no other effect
// (§2.5); errors are recorded once (getError returns and clears the first) and
// each one is also reported through the error callback with the call site, like a
// debug context.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <map>

#include "pipeline/fragment/fragment_span.h"
#include "pipeline/geometry/matrix_stack.h"
#include "pipeline/gl/enums.h"
#include "pipeline/number/profile.h"
#include "pipeline/texture/texture_object.h"
#include "sim/framebuffer.h"
#include "sim/gl_error.h"
#include "sim/probe.h"

namespace ffsim {

using GLbitfield = std::uint32_t;

// Write masks and scissor (GL 1.2.1 §4.1.2, §4.2.2); used by glClear and by every
// fragment write.
struct WriteMaskState {
  std::array<bool, 4> color{true, true, true, true};  // glColorMask
  std::uint32_t stencil = 0xFFFFFFFFu;                // glStencilMask (low s bits used)
  bool depth = true;                                  // glDepthMask
};
struct ScissorState {
  bool enabled = false;
  Rect box{0, 0, 0, 0};  // initial: the window size (set by the Context constructor)
};
struct ClearState {
  std::array<double, 4> color{0, 0, 0, 0};  // clamped to [0,1] when set (§4.2.3)
  std::uint32_t stencil = 0;
  double depth = 1.0;  // clamped to [0,1] when set
};

// Current raster position (GL121 §2.12), set by glRasterPos*; read by
// DrawPixels/CopyPixels/Bitmap. Window coordinates.
struct RasterPosState {
  bool valid = true;
  double x = 0, y = 0, z = 0;  // window x, y and depth in [0,1]
  double w = 1;                // clip w (for texcoord division)
  std::array<double, 4> color{1, 1, 1, 1};
  std::array<double, 4> secondary_color{0, 0, 0, 1};
  std::array<std::array<double, 4>, 4> texcoord{{{0, 0, 0, 1}, {0, 0, 0, 1}, {0, 0, 0, 1}, {0, 0, 0, 1}}};
};

// Per texture unit binding and enables (GL121 §3.8.8, ARB_multitexture). Texture
// environment state is added by the texturing code.
struct TextureUnitBinding {
  std::uint32_t bound_1d = 0, bound_2d = 0;  // texture object names; 0 = default texture
  bool enabled_1d = false, enabled_2d = false;
};

inline constexpr int kMaxTextureUnits = 4;

class Context {
 public:
  // Throws FramebufferError for an impossible framebuffer size.
  Context(const Profile& profile, int width, int height);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  const Profile& profile() const { return profile_; }
  Framebuffer& framebuffer() { return fb_; }
  const Framebuffer& framebuffer() const { return fb_; }

  // ---- errors -------------------------------------------------------------
  GLenum getError();  // returns and clears the recorded error (GL_NO_ERROR if none)
  void set_call_site(SourceLoc where) { call_site_ = std::move(where); }
  const SourceLoc& call_site() const { return call_site_; }
  void set_error_callback(std::function<void(const GLErrorEvent&)> cb) { on_error_ = std::move(cb); }
  const std::vector<GLErrorEvent>& error_log() const { return error_log_; }
  // Record an error raised by `function`; returns false so callers can write
  // `return ctx.error(...)`-style early exits in bool helpers.
  bool error(GLenum code, const char* function, std::string message);

  // ---- capabilities (sim/context.cpp dispatches to the owning area) --------
  void enable(GLenum cap);
  void disable(GLenum cap);
  bool isEnabled(GLenum cap);

  // ---- framebuffer control (sim/context_clear.cpp) -------------------------
  void clearColor(double r, double g, double b, double a);
  void clearStencil(std::int64_t s);
  void clearDepth(double d);
  void colorMask(bool r, bool g, bool b, bool a);
  void stencilMask(std::uint32_t mask);
  void depthMask(bool flag);
  void scissor(int x, int y, int width, int height);
  void clear(GLbitfield mask);

  // ---- texture objects and units (storage; binding calls live with texturing) --
  int active_texture_unit() const { return active_unit_; }
  TextureUnitBinding& texture_unit(int unit) { return units_[unit]; }
  const TextureUnitBinding& texture_unit(int unit) const { return units_[unit]; }
  // The texture object bound to `target` (TEXTURE_1D/2D) on `unit`; name 0 is the
  // default texture of that target (shared by all units, GL121 §3.8.12).
  TextureObject& bound_texture(int unit, GLenum target);
  // Named texture objects (created on first bind).
  std::map<std::uint32_t, TextureObject>& texture_objects() { return textures_; }

  // ---- raster position (set by glRasterPos*, read by the pixel rectangle calls) --
  RasterPosState& raster_pos() { return raster_pos_; }
  const RasterPosState& raster_pos() const { return raster_pos_; }

  // ---- fragment sink for pixel rectangles (DrawPixels / CopyPixels) ----------
  // Fragments produced by the pixel path after final conversion (colour already
  // clamped and converted to the fragment format, GL121 §3.6.4). The per-fragment
  // operations own this: texturing with the raster position's texture coordinates
  // when enabled, then scissor, alpha, stencil, depth, blend, masks
  // (GL121 §3.6.4 "Conversion to Fragments", §4.1).
  void pixel_fragments(FragmentSpan& span);
  // Shaded fragments (colour final, depth set) into the per-fragment operations
  // (GL121 §4.1: scissor, alpha test, stencil test, depth test, blending,
  // dithering, masks) and the framebuffer. Called by the rasterizer and by
  // pixel_fragments.
  void write_fragments(FragmentSpan& span);

  // ---- matrices (sim/context_matrix.cpp, GL121 §2.10.2) ---------------------
  void matrixMode(GLenum mode);  // MODELVIEW, PROJECTION, TEXTURE, COLOR
  void loadIdentity();
  void loadMatrix(const double m[16]);  // column-major, as glLoadMatrixd
  void multMatrix(const double m[16]);
  void pushMatrix();
  void popMatrix();
  void translate(double x, double y, double z);
  void scale(double x, double y, double z);
  void rotate(double angle_degrees, double x, double y, double z);
  void ortho(double l, double r, double b, double t, double n, double f);
  void frustum(double l, double r, double b, double t, double n, double f);
  GLenum matrix_mode() const { return matrix_mode_; }
  const MatrixStack& modelview() const { return modelview_; }
  const MatrixStack& projection() const { return projection_; }
  const MatrixStack& texture_matrix(int unit) const { return texture_matrix_[unit]; }
  const MatrixStack& color_matrix() const { return color_matrix_; }

  const WriteMaskState& write_masks() const { return masks_; }
  const ScissorState& scissor_state() const { return scissor_; }
  const ClearState& clear_state() const { return clear_; }
  // The rectangle writes may touch: the window, intersected with the scissor box
  // when the scissor test is enabled.
  Rect write_rect() const;

  // Each area adds its entry points and accessors below its own marker, so that
  // work on different areas merges without conflicts.

  // ==== [issue 3] pixel transfer and pixel rectangles: entry points ====


  // ==== [issue 4a] geometry, rasterization, texturing, texture environment ====


  // ==== [issue 4b] per-fragment operations ====


  // ==== [issue 5] register combiners ====


  // ==== [issue 6] traces: hooks ====
  // Worker threads a stage may use (at least 1; `ffsim replay --threads N`).
  // Results never depend on it: the trace tests compare hashes for 1 and 2 threads.
  void set_threads(int n) { threads_ = n < 1 ? 1 : n; }
  int threads() const { return threads_; }
  // Single-pixel tracing (`--probe X,Y`, sim/probe.h): stages record what they did
  // at the probed pixel; the trace executor prints and clears the records per pass.
  ProbeLog& probe() { return probe_; }
  const ProbeLog& probe() const { return probe_; }
  // "color codes (...) = (...), stencil 3, depth 16777215" at (x, y), for probe records.
  std::string probe_describe_buffers(int x, int y) const;


 private:
  bool set_capability(GLenum cap, bool on, const char* function);
  MatrixStack& current_stack();

  Profile profile_;
  Framebuffer fb_;
  GLenum pending_error_ = gl::NO_ERROR;
  SourceLoc call_site_;
  std::function<void(const GLErrorEvent&)> on_error_;
  std::vector<GLErrorEvent> error_log_;

  int active_unit_ = 0;
  std::array<TextureUnitBinding, kMaxTextureUnits> units_{};
  std::map<std::uint32_t, TextureObject> textures_;
  TextureObject default_1d_, default_2d_;
  RasterPosState raster_pos_;

  WriteMaskState masks_;
  ScissorState scissor_;
  ClearState clear_;

  GLenum matrix_mode_ = gl::MODELVIEW;
  MatrixStack modelview_{kModelviewStackDepth};
  MatrixStack projection_{kProjectionStackDepth};
  std::array<MatrixStack, kMaxTextureUnits> texture_matrix_{MatrixStack{kTextureStackDepth}, MatrixStack{kTextureStackDepth},
                                                            MatrixStack{kTextureStackDepth}, MatrixStack{kTextureStackDepth}};
  MatrixStack color_matrix_{kColorStackDepth};

  // Area state, below per-area markers (see the public section).

  // ==== [issue 3] state ====


  // ==== [issue 4a] state ====


  // ==== [issue 4b] state ====


  // ==== [issue 5] state ====


  // ==== [issue 6] state ====
  int threads_ = 1;
  ProbeLog probe_;

};

}  // namespace ffsim

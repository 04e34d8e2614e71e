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
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <map>

#include "pipeline/combiners/combiner_plan.h"
#include "pipeline/combiners/register_combiners.h"
#include "pipeline/fragment/fragment_plan.h"
#include "pipeline/fragment/fragment_span.h"
#include "pipeline/geometry/clip.h"
#include "pipeline/geometry/matrix_stack.h"
#include "pipeline/gl/enums.h"
#include "pipeline/number/profile.h"
#include "pipeline/pixel_transfer/byte_texels.h"
#include "pipeline/pixel_transfer/pixel_image.h"
#include "pipeline/pixel_transfer/pixel_state.h"
#include "pipeline/pixel_transfer/transfer_plan.h"
#include "pipeline/raster/triangle.h"
#include "pipeline/texenv/shading.h"
#include "pipeline/texture/texture_object.h"
#include "sim/framebuffer.h"
#include "sim/geometry_memo.h"
#include "sim/gl_error.h"
#include "sim/probe.h"
#include "sim/raster_cache.h"
#include "sim/uninitialized_allocator.h"
#include "sim/upload_cache.h"
#include "sim/vertex_run_memo.h"

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
static_assert(kMaxTextureUnits == kClipTexUnits);

struct WindowVertex;       // sim/draw_span.h
// The draw path's window vertices: resized without a fill (every member is
// written before it is read, tcw only for the units the plan samples, the only
// ones read; sim/draw_span.h, Context::window_attributes_n).
using WindowVertices = FilledVector<WindowVertex>;  // (sim/uninitialized_allocator.h)
class WorkerPool;          // sim/worker_pool.h
// Runs for the span path: `count` fragments in `runs` runs of length[0],
// length[1], ...; run r's weights are first[r] + i·dwdx at its i-th fragment
// (the TriangleCoverage of the run's triangle).
struct FastRuns {
  const std::array<std::int64_t, 3>* first = nullptr;  // per run: the weights at its first fragment
  const int* length = nullptr;                         // per run: its fragments
  int runs = 0, count = 0;                             // runs; fragments of all runs
};
// A triangle of a span-path group (sim/draw.cpp): its window vertices and
// coverage, and where its runs start in the group: runs [run_begin, the next
// triangle's run_begin), fragments from fragment_begin on.
struct GroupTriangle {
  std::array<const WindowVertex*, 3> tv{};
  TriangleCoverage cov;
  int run_begin = 0, fragment_begin = 0;
};

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
  void set_call_site(SourceLoc where) {
    call_site_ = std::move(where);
    call_site_ref_ = nullptr;
  }
  // The same without a copy (the trace executor, once per step): `where` must
  // outlive every later GL call until the next set_call_site*.
  void set_call_site_ref(const SourceLoc& where) { call_site_ref_ = &where; }
  const SourceLoc& call_site() const { return call_site_ref_ ? *call_site_ref_ : call_site_; }
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
  // The framebuffer's arrays as the fragment operations take them.
  FragmentBuffers fragment_buffers();

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
  // sim/context_pixel_state.cpp (GL121 §3.6.1-3.6.3, imaging subset)
  void pixelStorei(GLenum pname, std::int64_t param);
  void pixelStoref(GLenum pname, double param);
  void pixelTransferf(GLenum pname, double param);
  void pixelTransferi(GLenum pname, std::int64_t param);
  void pixelMapfv(GLenum map, int mapsize, const double* values);
  void pixelZoom(double xfactor, double yfactor);
  void colorTable(GLenum target, GLenum internalformat, int width, GLenum format, GLenum type, const void* data);
  void colorTableParameterfv(GLenum target, GLenum pname, const double params[4]);
  void copyColorTable(GLenum target, GLenum internalformat, int x, int y, int width);
  void convolutionFilter1D(GLenum target, GLenum internalformat, int width, GLenum format, GLenum type,
                           const void* data);
  void convolutionFilter2D(GLenum target, GLenum internalformat, int width, int height, GLenum format,
                           GLenum type, const void* data);
  void separableFilter2D(GLenum target, GLenum internalformat, int width, int height, GLenum format,
                         GLenum type, const void* row, const void* column);
  void convolutionParameteri(GLenum target, GLenum pname, std::int64_t param);
  void convolutionParameterfv(GLenum target, GLenum pname, const double params[4]);
  // sim/context_pixel_texture.cpp (GL121 §3.8.1-3.8.2)
  void texImage1D(GLenum target, int level, GLenum internalformat, int width, int border, GLenum format,
                  GLenum type, const void* data);
  void texImage2D(GLenum target, int level, GLenum internalformat, int width, int height, int border,
                  GLenum format, GLenum type, const void* data);
  void texSubImage1D(GLenum target, int level, int xoffset, int width, GLenum format, GLenum type,
                     const void* data);
  void texSubImage2D(GLenum target, int level, int xoffset, int yoffset, int width, int height, GLenum format,
                     GLenum type, const void* data);
  void copyTexImage1D(GLenum target, int level, GLenum internalformat, int x, int y, int width, int border);
  void copyTexImage2D(GLenum target, int level, GLenum internalformat, int x, int y, int width, int height,
                      int border);
  void copyTexSubImage1D(GLenum target, int level, int xoffset, int x, int y, int width);
  void copyTexSubImage2D(GLenum target, int level, int xoffset, int yoffset, int x, int y, int width, int height);
  // sim/context_pixel_rect.cpp (GL121 §3.6.4, §4.3.2, §4.3.3)
  void drawPixels(int width, int height, GLenum format, GLenum type, const void* data);
  void readPixels(int x, int y, int width, int height, GLenum format, GLenum type, void* data);
  void copyPixels(int x, int y, int width, int height, GLenum type);

  const pixel::PixelStoreState& pixel_store() const { return pixel_store_; }
  const pixel::PixelTransferState& pixel_transfer() const { return pixel_transfer_; }
  const pixel::ImagingState& imaging() const { return imaging_; }
  std::array<double, 2> pixel_zoom() const { return pixel_zoom_; }
  // The transfer plan the current state gives for a 1D or 2D image, printable with
  // plan.str(transfer_inputs()).
  pixel::TransferInputs transfer_inputs() const;
  pixel::TransferPlan transfer_plan(pixel::ImageDims dims) const;
  // Bytes a client image of this size, format and type occupies under the current
  // UNPACK (pack = false) or PACK store modes: what a trace must supply or allocate
  // for glTexImage*/glDrawPixels/glColorTable or glReadPixels. 0 for unknown enums.
  std::size_t pixel_client_bytes(bool pack, int width, int height, GLenum format, GLenum type) const;


  // ==== [issue 4a] geometry, rasterization, texturing, texture environment ====
  // Immediate mode (GL121 §2.6, sim/context_geometry.cpp). Primitives are
  // assembled at glEnd: TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN, QUADS,
  // QUAD_STRIP, POLYGON. Points and lines raise INVALID_ENUM (not modelled).
  void begin(GLenum mode);
  void end();
  void vertex2(double x, double y);
  void vertex3(double x, double y, double z);
  void vertex4(double x, double y, double z, double w);
  void color3(double r, double g, double b);
  void color4(double r, double g, double b, double a);
  void secondaryColor3(double r, double g, double b);
  void texCoord2(double s, double t);
  void texCoord4(double s, double t, double r, double q);
  void multiTexCoord2(GLenum texture, double s, double t);
  void multiTexCoord4(GLenum texture, double s, double t, double r, double q);
  void normal3(double x, double y, double z);
  void viewport(int x, int y, int width, int height);
  void depthRange(double n, double f);
  void shadeModel(GLenum mode);
  void rasterPos2(double x, double y);
  void rasterPos3(double x, double y, double z);
  void rasterPos4(double x, double y, double z, double w);
  bool in_begin_end() const { return in_begin_; }
  const std::array<double, 4>& current_color() const { return current_.color; }
  const std::array<double, 4>& current_secondary_color() const { return current_.secondary; }
  const std::array<double, 4>& current_normal() const { return current_.normal; }
  const std::array<double, 4>& current_texcoord(int unit) const { return current_.texcoord[unit]; }

  // Texture objects, units and environments (sim/context_texture.cpp).
  void bindTexture(GLenum target, std::uint32_t name);
  void genTextures(int n, std::uint32_t* names);
  void deleteTextures(int n, const std::uint32_t* names);
  void texParameteri(GLenum target, GLenum pname, std::int64_t param);
  void texParameterf(GLenum target, GLenum pname, double param);
  void texParameterfv(GLenum target, GLenum pname, const double* params);  // BORDER_COLOR: 4 values
  void activeTexture(GLenum texture);        // TEXTURE0 + i, i < profile().texture_units
  void clientActiveTexture(GLenum texture);  // stored (vertex arrays are not modelled)
  int client_active_texture_unit() const { return client_active_unit_; }
  void texEnvi(GLenum target, GLenum pname, std::int64_t param);
  void texEnvf(GLenum target, GLenum pname, double param);
  void texEnvfv(GLenum target, GLenum pname, const double* params);  // TEXTURE_ENV_COLOR: 4 values
  const TexEnvState& texenv(int unit) const { return texenv_[unit]; }

  // Shading (sim/draw.cpp). The state resolved for a draw (enabled, complete
  // textures; environments), its plan, and the plan as text for --explain.
  ShadingState shading_state();
  // With REGISTER_COMBINERS_NV enabled the plan samples exactly the enabled units
  // the combiner plan reads and runs no texture environment or colour sum.
  ShadingPlan shading_plan(const ShadingState& st);
  std::string explain_shading();
  // Run the full path instead of the plan (tests compare the two).
  void set_full_shading(bool on) { full_shading_ = on; }
  // Called with explain_shading()'s text before every draw that shades fragments.
  void set_explain_callback(std::function<void(const std::string&)> cb) { on_explain_ = std::move(cb); }
  // One fragment through the shading stages: fetch_texels (step 1) then the
  // colour stage (texture environments + colour sum, step 2). With
  // REGISTER_COMBINERS_NV enabled the register combiners replace step 2 and
  // consume the same texels and colours (RC §3.8.11).
  Rgba shade_fragment(const ShadingState& st, const ShadingPlan& plan, const Rgba& primary, const Rgba& secondary,
                      const UnitTexCoords& tc);
  // --probe: while non-null, shade_fragment appends what it computed for the
  // current fragment (filtered texels, combiner registers) to this text.
  std::string* shade_probe_ = nullptr;
  // The register-combiner colour stage for one fragment (sim/draw.cpp).
  Rgba combine_fragment(const ShadingState& st, const ShadingPlan& plan, const Rgba& primary, const Rgba& secondary,
                        const UnitTexels& texels);
  void probe_registers(const combiners::RegisterTrace& trace);
  // Whether fragments need shade_fragment at all (otherwise the primary colour is
  // the fragment colour). Register combiners make this true whenever enabled.
  bool shading_active(const ShadingPlan& plan) const {
    return combiners_.enabled || plan.any_texturing() || plan.color_sum;
  }
  GLenum shade_model() const { return shade_model_; }
  const std::array<int, 4>& viewport_box() const { return viewport_; }
  std::array<double, 2> depth_range() const { return {depth_near_, depth_far_}; }


  // ==== [issue 4b] per-fragment operations ====
  // sim/context_fragment.cpp (GL121 §4.1.3-§4.1.8, EXT_blend_color/_minmax/_subtract,
  // EXT_stencil_wrap). Enables: ALPHA_TEST, STENCIL_TEST, DEPTH_TEST, BLEND, DITHER,
  // COLOR_LOGIC_OP.
  void alphaFunc(GLenum func, double ref);
  void stencilFunc(GLenum func, std::int32_t ref, std::uint32_t mask);
  void stencilOp(GLenum sfail, GLenum dpfail, GLenum dppass);
  void depthFunc(GLenum func);
  void blendFunc(GLenum sfactor, GLenum dfactor);
  void blendEquation(GLenum mode);
  void blendColor(double r, double g, double b, double a);
  void logicOp(GLenum opcode);
  // The per-fragment state as the stages see it (write masks and scissor included)
  // and the buffers' format.
  FragmentOpsState fragment_ops_state() const;
  FragmentTarget fragment_target() const;
  // The plan for the current state, built or fetched from the cache by its
  // canonical key; and the constants of the current state.
  const FragmentPlan& fragment_plan();
  const FragmentConstants& fragment_plan_constants();
  std::size_t fragment_plan_cache_size() const { return fragment_plans_.size(); }
  // describe() of the current plan, for --explain / per-draw logs.
  std::string explain_fragment_ops();
  // For a glEnd pass: when nothing shades and the colour stage, fed the current
  // colour's codes, keeps every destination of the channels it writes, a line
  // saying so (docs/performance.md 34.1); else "".
  std::string explain_constant_source();


  // ==== [issue 5] register combiners ====
  // NV_register_combiners / NV_register_combiners2 (sim/context_combiners.cpp).
  // Enable/Disable REGISTER_COMBINERS_NV and PER_STAGE_CONSTANTS_NV go through enable().
  void combinerParameterfv(GLenum pname, const float* params);
  void combinerParameterf(GLenum pname, float param);
  void combinerParameteriv(GLenum pname, const std::int32_t* params);
  void combinerParameteri(GLenum pname, std::int32_t param);
  void combinerInput(GLenum stage, GLenum portion, GLenum variable, GLenum input, GLenum mapping,
                     GLenum componentUsage);
  void combinerOutput(GLenum stage, GLenum portion, GLenum abOutput, GLenum cdOutput, GLenum sumOutput, GLenum scale,
                      GLenum bias, bool abDotProduct, bool cdDotProduct, bool muxSum);
  void finalCombinerInput(GLenum variable, GLenum input, GLenum mapping, GLenum componentUsage);
  void combinerStageParameterfv(GLenum stage, GLenum pname, const float* params);
  void getCombinerInputParameterfv(GLenum stage, GLenum portion, GLenum variable, GLenum pname, float* params);
  void getCombinerInputParameteriv(GLenum stage, GLenum portion, GLenum variable, GLenum pname, std::int32_t* params);
  void getCombinerOutputParameterfv(GLenum stage, GLenum portion, GLenum pname, float* params);
  void getCombinerOutputParameteriv(GLenum stage, GLenum portion, GLenum pname, std::int32_t* params);
  void getFinalCombinerInputParameterfv(GLenum variable, GLenum pname, float* params);
  void getFinalCombinerInputParameteriv(GLenum variable, GLenum pname, std::int32_t* params);
  void getCombinerStageParameterfv(GLenum stage, GLenum pname, float* params);
  // All combiner state (NUM_GENERAL_COMBINERS_NV, COLOR_SUM_CLAMP_NV, constants, ...).
  const combiners::CombinerState& combiner_state() const { return combiners_; }
  // The plan for the current combiner state and profile (cached; rebuilt after any
  // combiner state change). The rasterizer shades a span with
  // combiners::shade_span(ctx.combiner_plan(), inputs, fog_color, out).
  const combiners::CombinerPlan& combiner_plan();
  // Arithmetic switches that are not GL state (docs/numerics.md §10).
  void set_combiner_rounding(combiners::CombinerRounding r);
  void set_combiner_rc2_secondary_alpha(bool on);
  // The active combiner setup as equations (for --explain).
  std::string describe_combiners();


  // ==== [issue 6] traces: hooks ====
  // Worker threads a stage may use (at least 1; `ffsim replay --threads N`).
  // Results never depend on it: the trace tests compare hashes for 1 and 2 threads.
  void set_threads(int n) {
    flush_deferred();
    threads_ = n < 1 ? 1 : n;
  }
  int threads() const { return threads_; }
  // The least work worth splitting over the threads, in fragments (estimated: a
  // batch's triangles' areas, a CopyPixels' image). Below it a draw stays on the
  // calling thread, where it is faster (docs/performance.md 20). The tests lower
  // it to split small scenes; the default is measured.
  static constexpr std::int64_t kSplitFragments = 4096;
  void set_split_fragments(std::int64_t n) {
    flush_deferred();
    split_fragments_ = n < 1 ? 1 : n;
  }
  std::int64_t split_fragments() const { return split_fragments_; }
  // Every split task on the calling thread, the pool's workers left idle: the
  // threads' code path (batches, bands, their recordings) on one core, with the
  // same output. A diagnostic: it measures what the split work itself costs
  // beside one thread's frame (ffsim bench --perf --trace F --threads 1,2,
  // docs/performance.md 38).
  void set_split_on_caller(bool on) {
    flush_deferred();
    split_on_caller_ = on;
  }
  bool split_on_caller() const { return split_on_caller_; }
  // Deferred draws (threads > 1, no probe): a glEnd leaves its batch of
  // triangles pending, so the next glEnd's polygons join it and the pool splits
  // one large batch instead of one per strip (docs/performance.md). The caller
  // that turns this on promises to call flush_deferred() before anything other
  // than glBegin, glEnd and vertex data (current colour, texture coordinates,
  // normal, vertex) reaches the Context, and before reading the framebuffer: the
  // trace executor does (CommandDef::vertex_data). Off by default.
  void set_defer_draws(bool on) {
    if (!on) flush_deferred();
    defer_draws_ = on;
  }
  void flush_deferred();
  // Single-pixel tracing (`--probe X,Y`, sim/probe.h): stages record what they did
  // at the probed pixel; the trace executor prints and clears the records per pass.
  ProbeLog& probe() { return probe_; }
  const ProbeLog& probe() const { return probe_; }
  // "color codes (...) = (...), stencil 3, depth 16777215" at (x, y), for probe records.
  std::string probe_describe_buffers(int x, int y) const;
  // Fragments that have entered the per-fragment operations since construction
  // (every write_fragments span; `ffsim bench --perf` divides bytes and time by it).
  std::uint64_t fragments_written() const { return fragments_written_; }


  // ==== [issue 10] performance ====
  // Specialised span paths (docs/performance.md): a run of fragments is shaded
  // at once (SoA interpolation by exact DDA, span texture sampling, integer
  // texture-environment and combiner kernels). Off: every fragment takes the
  // generic per-fragment path. Results are identical either way; the
  // tests/*/test_fast_*.cpp tests draw random scenes both ways and compare.
  void set_fast_paths(bool on) { fast_paths_ = on; }
  // The raster cache (sim/raster_cache.h, docs/performance.md 13.2): a glEnd's
  // triangles drawn again at the same window positions and depths replay the
  // runs, groups and depth codes of the first time instead of rasterizing again
  // (span path only; on by default). Off: every draw is rasterized.
  void set_raster_cache(bool on) {
    raster_cache_on_ = on;
    if (!on) raster_cache_.clear();
  }
  const RasterCache& raster_cache() const { return raster_cache_; }
  // The geometry memo (sim/geometry_memo.h, docs/performance.md 18.1): a glEnd
  // whose object positions and transformation equal an earlier one's takes that
  // one's window positions and depth codes (span path, every vertex inside the
  // view volume; on by default). Off: every glEnd transforms its vertices.
  void set_geometry_memo(bool on) {
    settle_window_fills();  // (before an entry they read goes)
    geometry_memo_on_ = on;
    if (!on) geometry_memo_.clear();
  }
  const GeometryMemo& geometry_memo() const { return geometry_memo_; }
  // The vertex-run memo (sim/vertex_run_memo.h, docs/performance.md 25.1): a
  // run of vertex-data calls named `id` by the trace (equal ids: equal calls)
  // that used the attributes as `usage` says. vertex_run_replay applies the
  // run's recorded effect and returns true when the state it depends on equals
  // the recording's; otherwise it returns false, the caller makes the calls and
  // then calls vertex_run_record with the same id. With the fast paths only (on
  // by default). Off: every run is called.
  bool vertex_run_replay(std::uint64_t id, const VertexRunUsage& usage);
  void vertex_run_record(std::uint64_t id);
  void set_vertex_run_memo(bool on) {
    vertex_run_memo_on_ = on;
    copy_pending_run();  // (before its record goes)
    settle_window_fills();  // (likewise)
    if (!on) vertex_run_memo_.clear();
  }
  const VertexRunMemo& vertex_run_memo() const { return vertex_run_memo_; }
  bool fast_paths() const { return fast_paths_; }
  // glTexImage1D/2D of client data through the upload cache (sim/upload_cache.h;
  // with the fast paths only: off, every upload is computed).
  const UploadCache& upload_cache() const { return upload_cache_; }
  // Runs of fragments the span path has shaded so far (tests check it is taken).
  std::uint64_t fast_runs() const { return fast_runs_; }
  // Threads (threads() > 1, no probe): the polygons of a glEnd are prepared in
  // batches of up to kBatchTriangles triangles; a batch whose triangles' areas
  // sum to at least split_fragments() pixels is rasterized in row bands on the
  // pool. Batches so split, and the triangles they held.
  std::uint64_t split_batches() const { return split_batches_; }
  std::uint64_t split_triangles() const { return split_triangles_; }
  // glEnds whose batch triangles came from their geometry memo entry (BatchMemo).
  std::uint64_t batch_memo_uses() const { return batch_memo_uses_; }
  // Deferred glEnds that reused the pending batch's shading state, plan and
  // set-up instead of making them again (Context::end; docs/performance.md 33).
  std::uint64_t deferred_setup_reuses() const { return deferred_setup_reuses_; }
  // glEnds whose window vertices were left to the batch's flush, which fills
  // them over the pool (WindowFill; docs/performance.md 35).
  std::uint64_t deferred_window_fills() const { return deferred_window_fills_; }
  // Flushes that filled them over the pool, and memo changes that had them
  // filled first on this thread (settle_window_fills).
  std::uint64_t split_window_fills() const { return split_window_fills_; }
  std::uint64_t settled_window_fills() const { return settled_window_fills_; }
  // Pixel rectangles (CopyPixels) whose rows went through the fragment
  // operations in bands on the pool (docs/performance.md 19.6).
  std::uint64_t split_pixel_rects() const { return split_pixel_rects_; }
  // Texture uploads (and sub-images) unpacked, transferred and stored in row
  // bands on the pool (upload_in_bands, docs/performance.md 24.2).
  std::uint64_t split_uploads() const { return split_uploads_; }
  // glClears whose rows were written in bands on the pool (docs/performance.md 27.1).
  std::uint64_t split_clears() const { return split_clears_; }
  // Wall time, in seconds, the calling thread has spent in the pool's runs (the
  // four kinds of split above): the rest of a frame's time is its serial part,
  // which bounds the speed-up of more threads (Amdahl; ffsim bench --perf's
  // threads table, docs/performance.md 31). 0 with one thread.
  double pool_seconds() const { return std::chrono::duration<double>(pool_time_).count(); }
  // Of pool_seconds, the time the calling thread waited in the pool's runs after
  // its own last task for the other threads' (WorkerPool::last_wait).
  double pool_wait_seconds() const { return std::chrono::duration<double>(pool_wait_).count(); }
  // The pool's runs on more than one thread (not set_split_on_caller's), and the
  // sum over them of how long after each began another thread took its first
  // task (WorkerPool::last_start): against pool_wait_seconds, whether the waits
  // are late starts or the last tasks' tails (docs/performance.md 40.2).
  std::uint64_t pool_runs() const { return pool_runs_; }
  double pool_start_seconds() const { return std::chrono::duration<double>(pool_start_).count(); }
  // glEnds whose vertices were put in window form once and shared by their
  // polygons (span path, smooth shading, every vertex inside the view volume).
  std::uint64_t shared_vertex_draws() const { return shared_vertex_draws_; }
  // glEnds whose vertices were all one replayed run's and whose window
  // attributes were read from the run's record (VertexRunFill; never copied).
  std::uint64_t run_record_reads() const { return run_record_reads_; }
  // glEnds skipped whole because their geometry memo entry has every vertex at
  // one window position (GeometryEntry::one_point: no triangle has area).
  std::uint64_t one_point_draws() const { return one_point_draws_; }
  // Span-path groups (sim/draw.cpp): triangles whose runs joined a group already
  // holding an earlier triangle's, and groups closed because a run met one of
  // their pixels.
  struct SpanGroupStats {
    std::uint64_t joined = 0, met = 0;
    std::uint64_t coords_recorded = 0;  // groups whose texture coordinates came from a recording
    std::uint64_t depth_reused = 0;     // groups whose depth test took a replay's comparisons (RecordedGroup::depth_test)
    // Groups left out because they could change no buffer: one source colour
    // that the colour stage keeps (colour_stage_keeps), and no depth or stencil
    // write (docs/performance.md 34.1); their fragments are counted as written.
    std::uint64_t unwritten = 0;
  };
  SpanGroupStats span_group_stats() const;

 private:
  bool set_capability(GLenum cap, bool on, const char* function);
  MatrixStack& current_stack();

  Profile profile_;
  Framebuffer fb_;
  GLenum pending_error_ = gl::NO_ERROR;
  SourceLoc call_site_;
  const SourceLoc* call_site_ref_ = nullptr;  // set_call_site_ref; overrides call_site_
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
  pixel::PixelStoreState pixel_store_;
  pixel::PixelTransferState pixel_transfer_;
  pixel::ImagingState imaging_;
  std::array<double, 2> pixel_zoom_{1.0, 1.0};
  // Helpers of the pixel path (sim/context_pixel_*.cpp).
  bool pixel_capability(GLenum cap, bool on);
  int pixel_is_enabled(GLenum cap) const;  // -1: not a pixel-path capability
  pixel::ConvolutionFilter* convolution_target(GLenum target);
  // Framebuffer colour (x, y, w, h) as RGBA groups in the evaluation precision,
  // pixels outside the window read as 0 (their values are undefined, GL121 §4.3.2).
  template <class T>
  pixel::RgbaImage<T> read_color_rect(int x, int y, int w, int h) const;
  template <class T>
  pixel::RgbaImage<T> transfer(pixel::RgbaImage<T> img, pixel::ImageDims dims) const;
  template <class T>
  void emit_color_rect(const pixel::RgbaImage<T>& img);
  // emit_color_rect's fragments of a width x height rectangle whose final codes
  // are known (fixed profiles): row m's 4·width codes from row_codes(m, to).
  template <class RowCodes>
  void emit_color_code_rows(int width, int height, RowCodes row_codes);
  // Threads: emit_color_code_rows' rows (image row, window row) through the
  // fragment operations in bands on the pool; row r's fragments are its codes
  // from column `first` on, at window x0.
  template <class RowCodes>
  void code_rows_in_bands(const std::vector<std::array<int, 2>>& rows, int width, int x0, int first,
                          int row_fragments, std::uint32_t z, RowCodes& row_codes_of);
  template <class T>
  std::optional<pixel::ByteTexelTables> byte_texel_tables(int dims, GLenum format, GLenum type,
                                                          const TextureImage& shape) const;
  // Threads: client data whose transfer is per pixel (no convolution), of at least
  // kSplitUploadTexels, unpacked, transferred and stored at (x0, y0) of the level
  // `target()` gives, in row bands on the pool (docs/performance.md 24.2). False,
  // doing nothing (target not called), when that does not apply.
  static constexpr std::int64_t kSplitUploadTexels = 4096;
  template <class T>
  bool upload_in_bands(const void* data, int width, int height, GLenum format, GLenum type, pixel::ImageDims dims,
                       int x0, int y0, const std::function<TextureImage&()>& target);
  template <class T>
  bool tex_image(const char* fn, int dims, GLenum target, int level, GLenum internalformat, int width, int height,
                 int border, GLenum format, GLenum type, const void* data, const int* copy_xy);
  template <class T>
  bool tex_sub_image(const char* fn, int dims, GLenum target, int level, int xoffset, int yoffset, int width,
                     int height, GLenum format, GLenum type, const void* data, const int* copy_xy);
  template <class T>
  void draw_pixels(int width, int height, GLenum format, GLenum type, const void* data);
  template <class T>
  void read_pixels(int x, int y, int width, int height, GLenum format, GLenum type, void* data);
  template <class T>
  void copy_pixels(int x, int y, int width, int height, GLenum type);
  template <class T>
  void color_table(const char* fn, GLenum target, GLenum internalformat, int width, GLenum format, GLenum type,
                   const void* data, const int* copy_xy);
  template <class T>
  void convolution_filter(const char* fn, pixel::FilterKind kind, GLenum target, GLenum internalformat, int width,
                          int height, GLenum format, GLenum type, const void* data, const void* column);
  void write_stencil_rect(int x0, int y0, int w, int h, const std::vector<std::int64_t>& idx);
  void write_depth_fragments(int w, int h, const std::vector<double>& z);
  // Fragment rectangle of group (n, m) under the current raster position and zoom
  // (GL121 §3.6.4 "Conversion to Fragments"): columns [x0, x1), rows [y0, y1).
  void group_extent(int n, int m, int& x0, int& x1, int& y0, int& y1) const;


  // ==== [issue 4a] state ====
  CurrentAttribs current_;  // GL121 §2.7 current values (sim/vertex_run_memo.h)
  // The current colours clamped to [0, 1] as every vertex takes them (§2.13.6),
  // kept by color4 and secondaryColor3 (clamped once per colour, not per vertex).
  std::array<double, 4> current_color_clamped_{1, 1, 1, 1}, current_secondary_clamped_{0, 0, 0, 0};
  bool in_begin_ = false;
  GLenum begin_mode_ = gl::TRIANGLES;
  std::vector<ClipVertex> begin_vertices_;  // the first begin_count_ are this glBegin's
  std::size_t begin_count_ = 0;
  std::array<int, 4> viewport_{0, 0, fb_.width(), fb_.height()};  // x, y, width, height (§2.10.1: the window)
  double depth_near_ = 0, depth_far_ = 1;
  GLenum shade_model_ = gl::SMOOTH;
  int client_active_unit_ = 0;
  std::array<TexEnvState, kMaxTextureUnits> texenv_{};
  std::vector<std::uint32_t> generated_names_;  // glGenTextures names not yet bound
  bool color_sum_ = false;
  bool full_shading_ = false;
  std::function<void(const std::string&)> on_explain_;
  ClipVertex make_vertex(const glm::dvec4& object) const;
  // A vertex's current colours (clamped) and the profile's units' texture
  // coordinates (after the texture matrices) into `cv`, its position left to the
  // caller; unused_units: the units past the profile's, once per vertex made.
  void vertex_attributes(ClipVertex& cv) const;
  void unused_units(ClipVertex& cv) const;
  void set_texture_enable(GLenum target, bool on);
  bool reject_in_begin(const char* function);
  // The unit index of GL_TEXTUREi, or -1 after an INVALID_ENUM error naming
  // `function` (the error path out of line: glMultiTexCoord is called for every
  // vertex, and building the message needs a large stack frame).
  int texture_unit(const char* function, GLenum texture) {
    const int unit = static_cast<int>(texture) - static_cast<int>(gl::TEXTURE0);
    if (unit >= 0 && unit < profile_.texture_units) [[likely]] return unit;
    not_a_texture_unit(function, texture);
    return -1;
  }
  [[gnu::cold, gnu::noinline]] void not_a_texture_unit(const char* function, GLenum texture);
  bool tex_parameter(const char* function, GLenum target, GLenum pname, const double* v, int count);
  bool tex_env(const char* function, GLenum target, GLenum pname, const double* v, int count);
  // Drawing (sim/draw.cpp). One glEnd's constants: nothing in them can change
  // inside glBegin/glEnd.
  struct DrawSetup {
    const ShadingState* st = nullptr;
    const ShadingPlan* plan = nullptr;
    bool flat = false, shade = false, has_depth = false;
    int vx = 0, vy = 0;                      // viewport corner
    double hw = 0, hh = 0;                   // viewport half width and height
    double area_scale = 0;                   // 2^-(2S+1): a snapped cross product to pixels of area (S subpixel bits)
    int cx0 = 0, cy0 = 0, cx1 = 0, cy1 = 0;  // the window, relative to the viewport corner
    bool bands = false;                      // threads: polygons batched and rows split (no probe)
    bool direct_writes = false;              // no probe: spans go to run_fragment_plan directly
    FragmentBuffers buffers;                 // direct_writes: the framebuffer's arrays
  };
  // Shared state made ready here when `direct_writes` (fragment plan, combiner
  // plan, buffers) and `bands` (the pool).
  DrawSetup draw_setup(const ShadingState& st, const ShadingPlan& plan);
  // Flat-shading copy, clipping, window coordinates: appends the polygon's window
  // vertices to `out` (a fan) and returns true, or leaves `out` alone and returns
  // false when nothing of it is left.
  bool prepare_polygon(std::vector<ClipVertex>& poly, std::size_t provoking, const DrawSetup& ds,
                       WindowVertices& out);
  // One vertex's window form (§2.10.1 viewport, snapped; depth and colour codes;
  // texture coordinates over w).
  void window_vertex(const ClipVertex& c, const DrawSetup& ds, WindowVertex& w) const;
  // Its two halves: the snapped position and depth code from the clip position
  // (and iw = 1 / w_c), and the colour codes and texture coordinates over w.
  void window_position(const glm::dvec4& clip, double iw, const DrawSetup& ds, WindowVertex& w) const;
  void window_attributes(const ClipVertex& c, double iw, const DrawSetup& ds, WindowVertex& w) const;
  // window_attributes of n vertices (a glEnd's shared vertices): the colour
  // format checked once, not per vertex. `fill`: c is a replayed run's record,
  // whose vertices hold fill's values where the run does not write them.
  // `memo`: the two colour conversions kept (null: color_memo_; a pool task
  // passes its own).
  struct ColorMemo;
  void window_attributes_n(const ClipVertex* c, const double* iw, std::size_t n, const DrawSetup& ds,
                           WindowVertex* w, const VertexRunFill* fill = nullptr, ColorMemo* memo = nullptr) const;
  // The window vertices [i0, i1) of a glEnd whose geometry memo entry `geo` has
  // its positions: the entry's snapped positions and depth codes, and the
  // attributes of the vertices c (fill: a replayed run's record) into w.
  void memo_window_vertices(const GeometryEntry& geo, const ClipVertex* c, const VertexRunFill* fill, std::size_t i0,
                            std::size_t i1, const DrawSetup& ds, WindowVertex* w, ColorMemo* memo = nullptr) const;
  // Threads: the batch's window vertices left to fill (a replayed run's glEnd
  // whose memo entry gave its triangles: nothing reads them before the flush),
  // filled by flush_batch over the pool before the bands (docs/performance.md 35).
  struct WindowFill {
    std::size_t base = 0, n = 0;       // batch_vertices_[base, base + n)
    const GeometryEntry* geo = nullptr;  // (settle_window_fills before the memo may drop it)
    VertexRunFill fill;                  // (fill.pending: the record, likewise)
  };
  // One more, for the batch's flush. (Out of line: with the push inlined in
  // glEnd, the compiler inlined less of glEnd's own loops and four one-thread
  // terrain frames took 0.6 M more instructions, performance.md 35.)
  void leave_window_fill(const WindowFill& f);
  // Fills them all: over the pool when `split` and there are enough, else here.
  void run_window_fills(const DrawSetup& ds, bool split);
  // Fills them here, now: before the geometry or vertex-run memo inserts or
  // clears (which may drop an entry or record a fill reads). They belong to the
  // pending batch, whose set-up is deferred_ds_.
  void settle_window_fills();
  // The rows [y0, y1) (relative to the viewport corner) of one triangle, shaded
  // into `span` and written; `band` >= 0: on a worker, into that band's scratch
  // and counters (write_fragments without its plan update and probe).
  void raster_triangle(const DrawSetup& ds, const std::array<const WindowVertex*, 3>& tv, int y0, int y1,
                       FragmentSpan& span, int band);
  // One thread (or the probe): prepare and rasterize a polygon at once.
  void draw_polygon(std::vector<ClipVertex>& poly, std::size_t provoking, const DrawSetup& ds);
  // Threads: prepare a polygon into the batch (flushed when full), and rasterize
  // the batch in row bands on the pool (or on this thread when it is small).
  void batch_polygon(std::vector<ClipVertex>& poly, std::size_t provoking, const DrawSetup& ds);
  // The triangle of batch_vertices_[a], [b], [c] into the batch (left out when its
  // bounding box misses the window).
  void batch_triangle(std::size_t a, std::size_t b, std::size_t c, const DrawSetup& ds);
  void flush_batch(const DrawSetup& ds);
  // The pool, borrowed (again) when it is missing or sized for other than threads().
  WorkerPool& pool();
  // pool().run(n, fn) (every task on this thread with split_on_caller_), its
  // wall time added to pool_time_ and the caller's wait for the others to pool_wait_.
  void run_split(int n, const std::function<void(int)>& fn);
  // The pool, and scratch, spans and counters for at least `bands` bands.
  void ready_bands(int bands);
  // The bands' fragment and run counts added to the Context's, and zeroed.
  void sum_band_counts();
  void clear_batch();
  // Triangles in drawing order, as raster_triangle takes them.
  using TriangleRef = std::array<const WindowVertex*, 3>;
  // The triangles' rows [ds.cy0, ds.cy1) on this thread through the raster cache
  // (sim/draw_replay.cpp): replayed when the cache holds them, else rasterized
  // (and recorded when the cache applies); the last group is shaded.
  // `geometry`: the geometry memo's serial naming the triangles' positions and
  // depth codes (one glEnd's own, from the memo), or 0.
  void draw_sequence(const DrawSetup& ds, const std::vector<TriangleRef>& tris, FragmentSpan& span,
                     std::uint64_t geometry = 0);
  // Whether the raster cache applies to a draw: the span path with direct writes
  // (or a worker) for every triangle of it.
  bool raster_cache_applies(const DrawSetup& ds) const;
  // What a recording depends on (sim/raster_cache.h): the draw's window and rows
  // (`rows`), then per triangle its snapped positions and depth codes, then its
  // coords_reuse_mask labels as runs; with `geometry` words (one glEnd's memo
  // serial, or a batch's (serial, triangles) pairs: its glEnds in order), the
  // words in place of the positions and depth codes. `tris` is read for the
  // positions (no `geometry`) and for the masks (coords_may_be_reused) only.
  std::vector<std::int64_t> raster_key(const DrawSetup& ds, const TriangleRef* tris, std::size_t count,
                                       std::initializer_list<std::int64_t> rows,
                                       std::span<const std::uint64_t> geometry = {}) const;
  // Rasterize `tris` (rows [y0, y1)) into `rec`, or replay `rec`; both end with
  // the last group shaded.
  void record_sequence(const DrawSetup& ds, const std::vector<TriangleRef>& tris, int y0, int y1, FragmentSpan& span,
                       int band, RasterRecording& rec);
  void replay_sequence(const DrawSetup& ds, const std::vector<TriangleRef>& tris, const RasterRecording& rec,
                       FragmentSpan& span, int band);
  // A run of kLongRun fragments or more, shaded and written on its own.
  void shade_long_run(const DrawSetup& ds, const TriangleRef& tv, const TriangleCoverage& cov, int y, int x0, int n,
                      const std::array<std::int64_t, 3>& first, FragmentSpan& span, int band);


  // ==== [issue 4b] state ====
  AlphaTestState alpha_test_;
  StencilState stencil_;
  DepthState depth_;
  BlendState blend_;
  LogicOpState logic_op_;
  bool dither_ = true;  // GL initial state (§4.1.7)
  std::map<FragmentPlanKey, FragmentPlan> fragment_plans_;
  // The state the current plan and constants were made for; rebuilt when it differs.
  bool fragment_current_valid_ = false;
  FragmentOpsState fragment_current_state_;
  const FragmentPlan* fragment_current_plan_ = nullptr;
  FragmentConstants fragment_current_constants_;
  void update_fragment_plan();


  // ==== [issue 5] state ====
  combiners::CombinerState combiners_;
  combiners::CombinerRounding combiner_rounding_ = combiners::CombinerRounding::PerStage;
  bool combiner_rc2_secondary_alpha_ = false;
  std::unique_ptr<combiners::CombinerPlan> combiner_plan_;  // cache; reset by every combiner state change


  // ==== [issue 6] state ====
  int threads_ = 1;
  // set_defer_draws: the pending batch's state and set-up (the state cannot
  // change while it is pending; the next glEnd recomputes the same).
  bool defer_draws_ = false, batch_pending_ = false;
  ShadingState deferred_st_;
  ShadingPlan deferred_plan_;
  DrawSetup deferred_ds_;
  ProbeLog probe_;
  std::uint64_t fragments_written_ = 0;

  // ==== [issue 10] state ====
  bool fast_paths_ = true;
  UploadCache upload_cache_;
  bool raster_cache_on_ = true;
  RasterCache raster_cache_;
  bool geometry_memo_on_ = true;
  GeometryMemo geometry_memo_;
  bool vertex_run_memo_on_ = true;
  VertexRunMemo vertex_run_memo_;
  struct VertexRunStart {  // a run being recorded: its id, entry state and first vertex
    std::uint64_t id = 0;  // 0: none
    CurrentAttribs entry;
    std::size_t first = 0;
    std::uint8_t written = 0;  // VertexRunUsage::written
  } vertex_run_start_;
  // A replay whose vertices begin this glBegin, not copied yet; or a run just
  // recorded whose vertices are all the glBegin's (in_place).
  VertexRunFill run_fill_;
  // The fill of a run's vertices that does not write `written` (the current state's values).
  VertexRunFill current_fill(std::uint8_t written) const;
  // A replay's vertices: the record's, the attributes it does not write filled
  // in from f (vertex_run_replay). copy_pending_run: run_fill_'s, when pending,
  // into the glBegin's array (before anything else reads or adds vertices).
  void run_vertices(const VertexRunMemo::Record& r, const VertexRunFill& f, ClipVertex* out) const;
  void copy_pending_run();
  std::vector<glm::dvec4> object_scratch_;  // a glEnd's object positions, for the memo
  std::vector<TriangleRef> sequence_scratch_;  // a glEnd's triangles (one thread)
  std::vector<TriangleRef> covering_scratch_;  // draw_sequence: those that may make fragments
  std::uint64_t fast_runs_ = 0, split_batches_ = 0, split_triangles_ = 0, shared_vertex_draws_ = 0, batch_memo_uses_ = 0,
                run_record_reads_ = 0;
  std::uint64_t split_pixel_rects_ = 0;
  std::uint64_t split_uploads_ = 0;
  std::uint64_t split_clears_ = 0;
  std::uint64_t one_point_draws_ = 0, deferred_setup_reuses_ = 0, deferred_window_fills_ = 0, split_window_fills_ = 0,
                settled_window_fills_ = 0;
  std::chrono::steady_clock::duration pool_time_{0};  // pool_seconds()
  std::chrono::steady_clock::duration pool_wait_{0};  // pool_wait_seconds()
  std::chrono::steady_clock::duration pool_start_{0};  // pool_start_seconds()
  std::uint64_t pool_runs_ = 0;                         // pool_runs()
  bool split_on_caller_ = false;                     // set_split_on_caller
  // Scratch of the span path, reused from run to run (sim/draw_span.cpp).
  // (alignas(64): the bands' scratch never share a cache line, so two threads'
  // writes to their own members do not take the line from each other; the same
  // for band_spans_, band_counts_ and the bands' RasterRecording)
  // (The arrays the span path writes whole before reading them are FilledVector:
  // sized per group without a fill.)
  struct alignas(64) SpanScratch {
    FilledVector<std::uint16_t> primary, secondary;
    std::array<FilledVector<std::uint16_t>, kMaxTextureUnits> texels;
    FilledVector<float> s, t;  // s/q, t/q rounded to binary32 (texture_coordinates)
    FilledVector<std::uint32_t> lane;
    // A group of runs (sim/draw.cpp), from one triangle or several: first
    // weights, rows, first pixels, lengths (one per run), and the shaded codes and
    // depths, all runs one after the other; the triangles they come from.
    std::vector<std::array<std::int64_t, 3>> weight;
    std::vector<int> run_y, run_x0, run_length;
    FilledVector<std::uint16_t> codes;
    FilledVector<std::uint32_t> depth;
    FilledVector<std::uint32_t> pixel;  // the group's fragments' pixel indices (y·width + x)
    std::vector<GroupTriangle> triangles;
    int group_fragments = 0;
    unsigned coords_reuse = 0;  // coords_reuse_mask of every triangle of the group
    // The group's pixels, one bit each, `taken_words` 64-bit words per window row
    // (empty: groups end with their triangle); `marked`: the group's bits are set.
    std::vector<std::uint64_t> taken;
    std::size_t taken_words = 0;
    bool marked = false;
    std::uint64_t joined = 0, met = 0;  // span_group_stats
    std::uint64_t coords_recorded = 0;  // span_group_stats
    std::uint64_t depth_reused = 0;     // span_group_stats
    std::uint64_t unwritten = 0;        // span_group_stats
    // The raster cache: the recording being made (null: none), the index in the
    // sequence of the triangle being rasterized, and that index for each of
    // `triangles`.
    RasterRecording* recording = nullptr;
    int sequence_index = 0;
    std::vector<int> triangle_index;
    // Texture coordinates and the raster cache, for the group being shaded
    // (shade_group_runs sets them, clear_group empties them): a replay's recorded
    // group whose coordinates may be taken, and the group being recorded, which
    // keeps the first ones computed (docs/performance.md 16.6).
    const RecordedGroup* coords_from = nullptr;
    RecordedGroup* coords_to = nullptr;
    std::vector<TriangleRef> sequence;  // a band's triangles (flush_batch)
    CoverageRun coverage_run;            // rasterize_triangle's run, its buffer kept
  };
  SpanScratch span_scratch_;
  // glEnd's polygons (clip coordinates, then window vertices) in buffers reused
  // from polygon to polygon: no allocation per triangle. prepare_polygon clips in
  // place (clip_polygon hands the same buffer back when nothing is clipped).
  std::vector<ClipVertex> polygon_scratch_;
  WindowVertices window_scratch_;
  // window_vertex's last primary and secondary colour conversions (a run of
  // vertices of one colour converts it once).
  struct ColorMemo {
    bool valid = false;
    ColorFormat format;
    std::array<double, 4> in{};
    Rgba out;
  };
  mutable std::array<ColorMemo, 2> color_memo_;
  // Threads: the pool (borrowed again when threads() changes) and per-band
  // scratch. A batch whose triangles' areas (each at most its box clipped to the
  // window) sum to at least split_fragments_ pixels is split into bands of rows.
  std::int64_t split_fragments_ = kSplitFragments;
  static constexpr std::size_t kBatchTriangles = 2048;  // bounds the batch's memory
  static constexpr std::size_t kSplitWindowFill = 1024;  // fewer vertices to fill at a flush: filled on the caller (performance.md 35)
  // The span path shades a run of this many fragments or more on its own, not in
  // a group (sim/draw.cpp raster_triangle).
  static constexpr int kLongRun = 64;
  std::shared_ptr<WorkerPool> pool_;
  std::vector<SpanScratch> band_scratch_;
  struct alignas(64) BandSpan {
    FragmentSpan span;
  };
  std::vector<BandSpan> band_spans_;
  struct alignas(64) BandCounts {  // summed after each split
    std::uint64_t fragments = 0, fast_runs = 0;
  };
  std::vector<BandCounts> band_counts_;
  // The batch: window vertices of its polygons, and its triangles in drawing
  // order (a fan of each polygon) with the rows [r0, r1) their bounding boxes may
  // cover; the rows of all of them, and the summed bounding-box area.
  // (the type a geometry memo entry keeps them in, indices relative to its
  // glEnd's first vertex: appended by rebase_triangles)
  using BatchTriangle = BatchMemo::Triangle;
  WindowVertices batch_vertices_;
  FilledVector<BatchTriangle> batch_triangles_;  // (a memo'd glEnd's are sized, then each written: context_geometry.cpp)
  // The batch's glEnds as (geometry memo serial, triangles it added) pairs, in
  // order, for the raster key; batch_unkeyed_: some triangle of the batch came
  // without a serial (the key then holds every triangle's positions).
  std::vector<std::uint64_t> batch_geometry_;
  bool batch_unkeyed_ = false;
  std::vector<WindowFill> window_fills_;  // (WindowFill, above)
  int batch_r0_ = 0, batch_r1_ = 0;
  std::int64_t batch_area_ = 0;
  // A run shaded at once into `span` (fixed profiles); false when the run needs
  // the generic per-fragment path (float profiles, λ needed, the probe inside it).
  // The span path (sim/draw_span.cpp): whether it applies to this draw (a fixed
  // profile, every sampled texture one sample_span_fixed takes), and the shading
  // of runs of one triangle: colour codes into out (4 per fragment, the runs one
  // after the other), depth codes into depth (when the framebuffer has depth).
  bool span_path_supported(const ShadingState& st, const ShadingPlan& plan, bool shade) const;
  // The runs may come from several triangles (`tris`, in run order), whose
  // coords_reuse_mask must be the same.
  void shade_runs_fast(const ShadingState& st, const ShadingPlan& plan, const GroupTriangle* tris, int triangles,
                       const FastRuns& runs, bool flat, bool shade, std::uint16_t* out, std::uint32_t* depth,
                       SpanScratch& scratch);
  // The span path's group of runs (sim/draw.cpp): shaded and written, then
  // emptied; every caller of raster_triangle calls it once its triangles are
  // done (a group may hold runs of earlier triangles of the same glEnd).
  SpanScratch& scratch_of(int band) { return band < 0 ? span_scratch_ : band_scratch_[static_cast<std::size_t>(band)]; }
  void shade_group(const DrawSetup& ds, FragmentSpan& span, int band);
  // A group's runs where shade_group_runs reads them: the scratch's arrays, or a
  // raster-cache recording's with its depth codes and pixel list (null: computed).
  struct GroupRuns {
    const std::array<std::int64_t, 3>* weight;
    const int *run_y, *run_x0, *length;
    int runs, fragments;
    const std::uint32_t* depth = nullptr;
    const std::uint32_t* pixel = nullptr;
    const RecordedGroup* from = nullptr;  // a replay's recorded group (its texture coordinates)
    const RasterRecording* from_recording = nullptr;  // ... and its recording (whose arena keeps its depth comparisons)
  };
  // The group's triangles are sc.triangles; `recorded` (or null) receives the
  // depth codes and pixel list computed.
  void shade_group_runs(const DrawSetup& ds, FragmentSpan& span, int band, const GroupRuns& g, RecordedGroup* recorded);
  void clear_group(SpanScratch& sc);
  // The group in `sc` appended to sc.recording (its depth codes follow once shaded).
  static RecordedGroup* record_group(SpanScratch& sc);
  void write_span(const DrawSetup& ds, FragmentSpan& span, int band);
  void count_written(int band, std::uint64_t fragments, std::uint64_t fast_runs);

};

}  // namespace ffsim

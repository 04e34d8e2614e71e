// glClear and the state it reads: clear values, write masks, scissor box
// (GL 1.2.1 §4.2.2 "Fine Control of Buffer Updates", §4.2.3 "Clearing the Buffers").
#include <algorithm>

#include "sim/context.h"
#include "sim/worker_pool.h"

namespace ffsim {

namespace {
double clamp01(double v) { return std::clamp(v, 0.0, 1.0); }
}  // namespace

std::string Context::probe_describe_buffers(int x, int y) const {
  std::string s = std::string("color ") + describe_color(fb_, x, y);
  if (fb_.has_stencil()) s += std::string(", stencil ") + std::to_string(fb_.stencil()[fb_.index(x, y)]);
  if (fb_.has_depth()) s += std::string(", depth ") + std::to_string(fb_.depth()[fb_.index(x, y)]);
  return s;
}

void Context::clearColor(double r, double g, double b, double a) {
  if (reject_in_begin("glClearColor")) return;
  clear_.color = {clamp01(r), clamp01(g), clamp01(b), clamp01(a)};  // §4.2.3: clamped when specified
}

void Context::clearStencil(std::int64_t s) {
  if (reject_in_begin("glClearStencil")) return;
  // §4.2.3: masked to the number of stencil bits when used; keep the low 32 bits.
  clear_.stencil = static_cast<std::uint32_t>(s);
}

void Context::clearDepth(double d) {
  if (reject_in_begin("glClearDepth")) return;
  clear_.depth = clamp01(d);
}

void Context::colorMask(bool r, bool g, bool b, bool a) {
  if (reject_in_begin("glColorMask")) return;
  masks_.color = {r, g, b, a};
}
void Context::stencilMask(std::uint32_t mask) {
  if (reject_in_begin("glStencilMask")) return;
  masks_.stencil = mask;
}
void Context::depthMask(bool flag) {
  if (reject_in_begin("glDepthMask")) return;
  masks_.depth = flag;
}

void Context::scissor(int x, int y, int width, int height) {
  if (reject_in_begin("glScissor")) return;
  if (width < 0 || height < 0) {
    error(gl::INVALID_VALUE, "glScissor", "width and height must not be negative (got " +
                                              std::to_string(width) + ", " + std::to_string(height) + ")");
    return;
  }
  scissor_.box = {x, y, width, height};
}

void Context::clear(GLbitfield mask) {
  if (reject_in_begin("glClear")) return;
  constexpr GLbitfield known = gl::COLOR_BUFFER_BIT | gl::DEPTH_BUFFER_BIT | gl::STENCIL_BUFFER_BIT |
                               gl::ACCUM_BUFFER_BIT;
  if (mask & ~known) {
    error(gl::INVALID_VALUE, "glClear", "mask has bits other than the buffer bits");
    return;
  }
  const Rect r = write_rect();  // §4.2.3: clear honours pixel ownership, scissor and masks
  const bool probed = probe_.inside(r);
  std::string before;
  if (probed) before = probe_describe_buffers(probe_.x(), probe_.y());
  ClearValues v;
  v.color = mask & gl::COLOR_BUFFER_BIT;
  v.rgba = clear_.color;
  v.color_mask = masks_.color;
  v.stencil = mask & gl::STENCIL_BUFFER_BIT;
  v.stencil_value = clear_.stencil;
  v.stencil_mask = masks_.stencil;
  v.depth = (mask & gl::DEPTH_BUFFER_BIT) && masks_.depth;
  v.depth01 = clear_.depth;
  // ACCUM_BUFFER_BIT: this context has no accumulation buffer, so nothing to clear.
  const ClearPlan plan = fb_.plan_clear(r, v);
  const int height = plan.r.height;
  // Threads (docs/performance.md 27.1): a large clear's rows in bands on the
  // pool, cut as a draw over the same rows cuts them, so each band's memory is
  // first written by the thread that will draw it. Rows are disjoint: the same
  // values as in order.
  if (threads_ > 1 && !probed && height >= 2 && std::int64_t{plan.r.width} * height >= split_fragments_) {
    const int bands = std::min(4 * threads_, height);
    ++split_clears_;
    run_split(bands, [&](int k) {
      fb_.clear_rows(plan, plan.r.y + height * k / bands, plan.r.y + height * (k + 1) / bands);
    });
  } else {
    fb_.clear_rows(plan, plan.r.y, plan.r.y + height);
  }
  if (probed)
    probe_.record("clear", before + " -> " + probe_describe_buffers(probe_.x(), probe_.y()));
}

}  // namespace ffsim

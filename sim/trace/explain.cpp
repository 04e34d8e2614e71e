#include "sim/trace/explain.h"

#include <cstdio>

#include "pipeline/gl/enums.h"

namespace ffsim::trace {

std::string explain_writes(const Context& ctx, const PassInfo& pass) {
  std::string s;
  if (pass.step.name == "glClear" && !pass.step.args.empty()) {
    const auto mask = static_cast<std::uint32_t>(pass.step.args[0].i);
    std::string bufs;
    if (mask & gl::COLOR_BUFFER_BIT) bufs += " color";
    if (mask & gl::STENCIL_BUFFER_BIT) bufs += " stencil";
    if ((mask & gl::DEPTH_BUFFER_BIT) && ctx.write_masks().depth) bufs += " depth";
    const Rect r = ctx.write_rect();
    s += cat("clear", bufs.empty() ? std::string(" nothing") : bufs, " in (", std::to_string(r.x), ", ",
             std::to_string(r.y), ") ", std::to_string(r.width), "x", std::to_string(r.height), "\n");
  }
  const auto& m = ctx.write_masks();
  std::string rgba;
  const char* names = "RGBA";
  for (int c = 0; c < 4; ++c)
    if (m.color[c]) rgba += names[c];
  char st[32];
  std::snprintf(st, sizeof st, "0x%X", static_cast<unsigned>(m.stencil & ctx.framebuffer().stencil_max()));
  s += cat("writes: color ", rgba.empty() ? std::string("none") : rgba, ", stencil mask ", st, ", depth ",
           m.depth ? "on" : "off", "; scissor ");
  if (ctx.scissor_state().enabled) {
    const Rect& b = ctx.scissor_state().box;
    s += cat("(", std::to_string(b.x), ", ", std::to_string(b.y), ") ", std::to_string(b.width), "x",
             std::to_string(b.height));
  } else {
    s += "off";
  }
  return s + "\n";
}

namespace {
ExplainerRegistry build() {
  ExplainerRegistry r;
  r.add("framebuffer", explain_writes);
  // ==== [issue 3] pixel transfer plan ====

  // ==== [issue 4a] rasterization, texturing, texture environment ====

  // ==== [issue 4b] per-fragment operations (blend equations) ====

  // ==== [issue 5] register combiners (stage equations) ====

  return r;
}
}  // namespace

const ExplainerRegistry& explainers() {
  static const ExplainerRegistry r = build();
  return r;
}

}  // namespace ffsim::trace

#include "sim/trace/explain.h"

#include <cstdio>

#include "pipeline/gl/enums.h"
#include "sim/trace/expr.h"

namespace ffsim::trace {

std::string explain_writes(const Context& ctx, const PassInfo& pass) {
  if (!pass.is_pass) return "";
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
bool shades(const std::string& name) { return name == "glEnd" || name == "glDrawPixels" || name == "glCopyPixels"; }
std::string with_newline(std::string s) {
  if (!s.empty() && s.back() != '\n') s += '\n';
  return s;
}
}  // namespace

std::string explain_pixel_transfer(Context& ctx, const PassInfo& pass) {
  const std::string& n = pass.step.name;
  if (n.rfind("glTex", 0) == 0 || n.rfind("glCopyTex", 0) == 0) {
    // Texture images run the transfer plan of their dimensionality (GL121 §3.8.1).
    const bool one_d = n.find("1D") != std::string::npos;
    return with_newline(ctx.transfer_plan(one_d ? pixel::ImageDims::OneD : pixel::ImageDims::TwoD).str(ctx.transfer_inputs()));
  }
  if (n != "glDrawPixels" && n != "glCopyPixels") return "";
  // DrawPixels and CopyPixels of colour run the 2D transfer plan (GL121 §3.6.3).
  const auto z = ctx.pixel_zoom();
  const auto& rp = ctx.raster_pos();
  std::string s = cat("raster position (", format_number(rp.x), ", ", format_number(rp.y), ")", rp.valid ? "" : " invalid: nothing drawn",
                      ", zoom ", format_number(z[0]), " x ", format_number(z[1]), "\n");
  // Stencil and depth rectangles do not go through the colour transfer plan.
  const auto& a = pass.step.args;
  const GLenum what = pass.step.name == "glCopyPixels" ? (a.size() > 4 ? static_cast<GLenum>(a[4].i) : gl::COLOR)
                                                       : (a.size() > 2 ? static_cast<GLenum>(a[2].i) : gl::RGBA);
  if (what == gl::STENCIL || what == gl::STENCIL_INDEX) return s + "stencil indices: no colour transfer\n";
  if (what == gl::DEPTH || what == gl::DEPTH_COMPONENT) return s + "depth values: no colour transfer\n";
  return s + with_newline(ctx.transfer_plan(pixel::ImageDims::TwoD).str(ctx.transfer_inputs()));
}

std::string explain_shading_pass(Context& ctx, const PassInfo& pass) {
  if (!pass.is_pass || !shades(pass.step.name)) return "";
  return with_newline(ctx.explain_shading());
}

std::string explain_fragment_pass(Context& ctx, const PassInfo& pass) {
  if (!pass.is_pass || pass.step.name == "glClear") return "";
  return with_newline(ctx.explain_fragment_ops()) + (pass.step.name == "glEnd" ? ctx.explain_constant_source() : "");
}

std::string explain_combiners_pass(Context& ctx, const PassInfo& pass) {
  if (!pass.is_pass || !shades(pass.step.name) || !ctx.isEnabled(gl::REGISTER_COMBINERS_NV)) return "";
  return with_newline(ctx.describe_combiners());
}

namespace {
ExplainerRegistry build() {
  ExplainerRegistry r;
  r.add("framebuffer", explain_writes);
  // ==== [issue 3] pixel transfer plan ====
  r.add("pixel transfer", explain_pixel_transfer);

  // ==== [issue 4a] rasterization, texturing, texture environment ====
  r.add("shading", explain_shading_pass);

  // ==== [issue 4b] per-fragment operations (blend equations) ====
  r.add("fragment", explain_fragment_pass);

  // ==== [issue 5] register combiners (stage equations) ====
  r.add("combiners", explain_combiners_pass);

  return r;
}
}  // namespace

const ExplainerRegistry& explainers() {
  static const ExplainerRegistry r = build();
  return r;
}

}  // namespace ffsim::trace

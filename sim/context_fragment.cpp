// Per-fragment operation state and the entry points that set it (GL 1.2.1 §4.1.3
// alpha test, §4.1.4 stencil, §4.1.5 depth, §4.1.6 blending with EXT_blend_color,
// EXT_blend_minmax, EXT_blend_subtract, §4.1.8 logic op; EXT_stencil_wrap).
// The enables are in sim/context.cpp; the stages are pipeline/fragment/.
// A call with an invalid token raises INVALID_ENUM and changes nothing (§2.5).
#include <algorithm>

#include "pipeline/fragment/constant_source.h"
#include "pipeline/gl/enum_names.h"
#include "sim/context.h"

namespace ffsim {

namespace {
std::string bad(const char* what, GLenum v) { return gl::enum_name(v) + " is not a valid " + what; }
}  // namespace

void Context::alphaFunc(GLenum func, double ref) {
  if (reject_in_begin("glAlphaFunc")) return;
  if (!valid_test_func(func)) {
    error(gl::INVALID_ENUM, "glAlphaFunc", bad("comparison function", func));
    return;
  }
  alpha_test_.func = func;
  alpha_test_.ref = clamp01(ref);  // §4.1.3: clamped to [0,1] when specified
}

void Context::stencilFunc(GLenum func, std::int32_t ref, std::uint32_t mask) {
  if (reject_in_begin("glStencilFunc")) return;
  if (!valid_test_func(func)) {
    error(gl::INVALID_ENUM, "glStencilFunc", bad("comparison function", func));
    return;
  }
  stencil_.func = func;
  stencil_.ref = ref;  // clamped to [0, 2^s - 1] when used (§4.1.4)
  stencil_.value_mask = mask;
}

void Context::stencilOp(GLenum sfail, GLenum dpfail, GLenum dppass) {
  if (reject_in_begin("glStencilOp")) return;
  for (GLenum op : {sfail, dpfail, dppass})
    if (!valid_stencil_op(op)) {
      error(gl::INVALID_ENUM, "glStencilOp", bad("stencil operation", op));
      return;
    }
  stencil_.sfail = sfail;
  stencil_.dpfail = dpfail;
  stencil_.dppass = dppass;
}

void Context::depthFunc(GLenum func) {
  if (reject_in_begin("glDepthFunc")) return;
  if (!valid_test_func(func)) {
    error(gl::INVALID_ENUM, "glDepthFunc", bad("comparison function", func));
    return;
  }
  depth_.func = func;
}

void Context::blendFunc(GLenum sfactor, GLenum dfactor) {
  if (reject_in_begin("glBlendFunc")) return;
  if (!valid_blend_src_factor(sfactor)) {
    error(gl::INVALID_ENUM, "glBlendFunc", bad("source blend factor", sfactor));
    return;
  }
  if (!valid_blend_dst_factor(dfactor)) {
    error(gl::INVALID_ENUM, "glBlendFunc",
          bad("destination blend factor", dfactor) +
              (dfactor == gl::SRC_ALPHA_SATURATE ? " (SRC_ALPHA_SATURATE is a source factor only in OpenGL 1.2.1)" : ""));
    return;
  }
  blend_.src = sfactor;
  blend_.dst = dfactor;
}

void Context::blendEquation(GLenum mode) {
  if (reject_in_begin("glBlendEquation")) return;
  if (!valid_blend_equation(mode)) {
    error(gl::INVALID_ENUM, "glBlendEquation", bad("blend equation", mode));
    return;
  }
  blend_.equation = mode;
}

void Context::blendColor(double r, double g, double b, double a) {
  if (reject_in_begin("glBlendColor")) return;
  blend_.color = {clamp01(r), clamp01(g), clamp01(b), clamp01(a)};  // EXT_blend_color: clamped when specified
}

void Context::logicOp(GLenum opcode) {
  if (reject_in_begin("glLogicOp")) return;
  if (!valid_logic_op(opcode)) {
    error(gl::INVALID_ENUM, "glLogicOp", bad("logic op", opcode));
    return;
  }
  logic_op_.op = opcode;
}

FragmentOpsState Context::fragment_ops_state() const {
  FragmentOpsState s;
  s.scissor = {scissor_.enabled, scissor_.box.x, scissor_.box.y, scissor_.box.width, scissor_.box.height};
  s.alpha = alpha_test_;
  s.stencil = stencil_;
  s.depth = depth_;
  s.blend = blend_;
  s.logic = logic_op_;
  s.dither = dither_;
  s.color_mask = masks_.color;
  s.stencil_writemask = masks_.stencil;
  s.depth_mask = masks_.depth;
  return s;
}

FragmentTarget Context::fragment_target() const {
  const FramebufferFormat& f = fb_.format();
  return {f.width, f.height, f.color_arith, f.color_bits, f.stencil_bits, f.depth_bits};
}

void Context::update_fragment_plan() {
  FragmentOpsState s = fragment_ops_state();
  if (fragment_current_valid_ && s == fragment_current_state_) return;
  const FragmentTarget t = fragment_target();
  const FragmentPlanKey key = fragment_plan_key(s, t);
  auto it = fragment_plans_.find(key);
  if (it == fragment_plans_.end()) it = fragment_plans_.emplace(key, build_fragment_plan(key)).first;
  fragment_current_plan_ = &it->second;  // std::map nodes are stable
  fragment_current_constants_ = fragment_constants(s, t);
  fragment_current_state_ = std::move(s);
  fragment_current_valid_ = true;
}

const FragmentPlan& Context::fragment_plan() {
  update_fragment_plan();
  return *fragment_current_plan_;
}

const FragmentConstants& Context::fragment_plan_constants() {
  update_fragment_plan();
  return fragment_current_constants_;
}

std::string Context::explain_fragment_ops() {
  update_fragment_plan();
  return describe(*fragment_current_plan_, fragment_current_constants_);
}

std::string Context::explain_constant_source() {
  const ShadingState st = shading_state();
  if (shading_active(shading_plan(st)) || st.color.arith != Arithmetic::Fixed) return "";
  update_fragment_plan();
  const FragmentPlan& plan = *fragment_current_plan_;
  // (the codes window_attributes_n gives a vertex of the current colour)
  const std::array<std::uint32_t, 4> code = rgba_from_values(current_color_clamped_, st.color).code;
  if (!plan.write_color || !colour_stage_keeps(plan.key, fragment_current_constants_, code)) return "";
  return "  colour: with the colour codes (" + std::to_string(code[0]) + ", " + std::to_string(code[1]) + ", " +
         std::to_string(code[2]) + ", " + std::to_string(code[3]) +
         ") at every vertex, each written channel stores back its destination: the span path leaves out the "
         "groups whose depth and stencil tests write nothing too\n";
}

}  // namespace ffsim

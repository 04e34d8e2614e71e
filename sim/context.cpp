#include "sim/context.h"
#include "sim/draw_span.h"  // WindowVertex (the batch of the draw path)

#include "pipeline/gl/enum_names.h"

namespace ffsim {

std::string SourceLoc::str() const {
  std::string s = file;
  s.append(":").append(std::to_string(line));
  if (column > 0) s.append(":").append(std::to_string(column));
  return s;
}

std::string GLErrorEvent::str() const {
  std::string s;
  if (!where.empty()) s += where.str() + ": ";
  s += function + ": " + gl::enum_name(error) + ": " + message;
  return s;
}

Context::Context(const Profile& profile, int width, int height)
    : profile_(profile), fb_(FramebufferFormat::from_profile(profile, width, height)) {
  validate_profile(profile_, profile_.name);
  scissor_.box = {0, 0, width, height};  // §4.1.2: initially the window size
}

Context::~Context() = default;

GLenum Context::getError() {
  const GLenum e = pending_error_;
  pending_error_ = gl::NO_ERROR;
  return e;
}

bool Context::error(GLenum code, const char* function, std::string message) {
  // §2.5: only the first error is latched until getError; later ones are still
  // reported to the debug callback and the log.
  if (pending_error_ == gl::NO_ERROR) pending_error_ = code;
  GLErrorEvent ev{code, function, std::move(message), call_site()};
  if (on_error_) on_error_(ev);
  error_log_.push_back(std::move(ev));
  return false;
}

bool Context::set_capability(GLenum cap, bool on, const char* function) {
  switch (cap) {
    case gl::SCISSOR_TEST: scissor_.enabled = on; return true;
    // ==== [issue 3] capabilities ====
    case gl::COLOR_TABLE:
    case gl::POST_CONVOLUTION_COLOR_TABLE:
    case gl::POST_COLOR_MATRIX_COLOR_TABLE:
    case gl::CONVOLUTION_1D:
    case gl::CONVOLUTION_2D:
    case gl::SEPARABLE_2D: return pixel_capability(cap, on);


    // ==== [issue 4a] capabilities ====
    case gl::TEXTURE_1D:
    case gl::TEXTURE_2D: set_texture_enable(cap, on); return true;  // per active unit
    case gl::COLOR_SUM: color_sum_ = on; return true;

    // ==== [issue 4b] capabilities ====
    case gl::ALPHA_TEST: alpha_test_.enabled = on; return true;
    case gl::STENCIL_TEST: stencil_.enabled = on; return true;
    case gl::DEPTH_TEST: depth_.enabled = on; return true;
    case gl::BLEND: blend_.enabled = on; return true;
    case gl::DITHER: dither_ = on; return true;
    case gl::COLOR_LOGIC_OP: logic_op_.enabled = on; return true;

    // ==== [issue 5] capabilities ====
    case gl::REGISTER_COMBINERS_NV: combiners_.enabled = on; combiner_plan_.reset(); return true;
    case gl::PER_STAGE_CONSTANTS_NV: combiners_.per_stage_constants = on; combiner_plan_.reset(); return true;


    default:
      return error(gl::INVALID_ENUM, function, gl::enum_name(cap) + " is not a capability this context knows");
  }
}

void Context::enable(GLenum cap) {
  if (reject_in_begin("glEnable")) return;
  set_capability(cap, true, "glEnable");
}
void Context::disable(GLenum cap) {
  if (reject_in_begin("glDisable")) return;
  set_capability(cap, false, "glDisable");
}

bool Context::isEnabled(GLenum cap) {
  if (reject_in_begin("glIsEnabled")) return false;
  switch (cap) {
    case gl::SCISSOR_TEST: return scissor_.enabled;
    // ==== [issue 3] capabilities ====
    case gl::COLOR_TABLE:
    case gl::POST_CONVOLUTION_COLOR_TABLE:
    case gl::POST_COLOR_MATRIX_COLOR_TABLE:
    case gl::CONVOLUTION_1D:
    case gl::CONVOLUTION_2D:
    case gl::SEPARABLE_2D: return pixel_is_enabled(cap) == 1;


    // ==== [issue 4a] capabilities ====
    case gl::TEXTURE_1D: return units_[active_unit_].enabled_1d;
    case gl::TEXTURE_2D: return units_[active_unit_].enabled_2d;
    case gl::COLOR_SUM: return color_sum_;

    // ==== [issue 4b] capabilities ====
    case gl::ALPHA_TEST: return alpha_test_.enabled;
    case gl::STENCIL_TEST: return stencil_.enabled;
    case gl::DEPTH_TEST: return depth_.enabled;
    case gl::BLEND: return blend_.enabled;
    case gl::DITHER: return dither_;
    case gl::COLOR_LOGIC_OP: return logic_op_.enabled;

    // ==== [issue 5] capabilities ====
    case gl::REGISTER_COMBINERS_NV: return combiners_.enabled;
    case gl::PER_STAGE_CONSTANTS_NV: return combiners_.per_stage_constants;


    default:
      error(gl::INVALID_ENUM, "glIsEnabled", gl::enum_name(cap) + " is not a capability this context knows");
      return false;
  }
}

Rect Context::write_rect() const {
  return scissor_.enabled ? intersect(fb_.bounds(), scissor_.box) : fb_.bounds();
}

}  // namespace ffsim

#include "sim/context.h"

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
  GLErrorEvent ev{code, function, std::move(message), call_site_};
  if (on_error_) on_error_(ev);
  error_log_.push_back(std::move(ev));
  return false;
}

bool Context::set_capability(GLenum cap, bool on, const char* function) {
  switch (cap) {
    case gl::SCISSOR_TEST: scissor_.enabled = on; return true;
    // ==== [issue 3] capabilities ====


    // ==== [issue 4a] capabilities ====


    // ==== [issue 4b] capabilities ====


    // ==== [issue 5] capabilities ====
    case gl::REGISTER_COMBINERS_NV: combiners_.enabled = on; combiner_plan_.reset(); return true;
    case gl::PER_STAGE_CONSTANTS_NV: combiners_.per_stage_constants = on; combiner_plan_.reset(); return true;


    default:
      return error(gl::INVALID_ENUM, function, gl::enum_name(cap) + " is not a capability this context knows");
  }
}

void Context::enable(GLenum cap) { set_capability(cap, true, "glEnable"); }
void Context::disable(GLenum cap) { set_capability(cap, false, "glDisable"); }

bool Context::isEnabled(GLenum cap) {
  switch (cap) {
    case gl::SCISSOR_TEST: return scissor_.enabled;
    // ==== [issue 3] capabilities ====


    // ==== [issue 4a] capabilities ====


    // ==== [issue 4b] capabilities ====


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

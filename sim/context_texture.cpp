// Texture objects, texture units and texture environments: glBindTexture,
// glGenTextures, glDeleteTextures, glTexParameter, glActiveTexture,
// glClientActiveTexture, glTexEnv (GL121 §3.8.4, §3.8.9, §3.8.12;
// ARB_multitexture; ARB/EXT_texture_env_combine, _dot3; ARB_texture_env_add).
// Storage (glTexImage*) is the pixel path's; sampling is pipeline/texture.
#include <algorithm>
#include <cmath>

#include "pipeline/gl/enum_names.h"
#include "sim/context.h"

namespace ffsim {

namespace {

bool is_texture_target(GLenum t) { return t == gl::TEXTURE_1D || t == gl::TEXTURE_2D; }

// An enum-valued parameter given as a number (glTexParameterf / glTexEnvf).
GLenum as_enum(double v) { return (v >= 0 && v <= 4294967295.0 && v == std::floor(v)) ? static_cast<GLenum>(v) : 0xFFFFFFFFu; }

double clamp01(double v) { return std::isnan(v) ? 0.0 : std::clamp(v, 0.0, 1.0); }

}  // namespace

void Context::set_texture_enable(GLenum target, bool on) {
  TextureUnitBinding& u = units_[active_unit_];
  (target == gl::TEXTURE_1D ? u.enabled_1d : u.enabled_2d) = on;
}

void Context::bindTexture(GLenum target, std::uint32_t name) {
  if (reject_in_begin("glBindTexture")) return;
  if (!is_texture_target(target)) {
    error(gl::INVALID_ENUM, "glBindTexture", gl::enum_name(target) + " is not TEXTURE_1D or TEXTURE_2D");
    return;
  }
  if (name != 0) {
    auto it = textures_.find(name);
    if (it != textures_.end() && it->second.target != 0 && it->second.target != target) {
      error(gl::INVALID_OPERATION, "glBindTexture",
            "texture " + std::to_string(name) + " is a " + gl::enum_name(it->second.target) + " texture");
      return;
    }
    TextureObject& obj = textures_[name];  // created on first bind (§3.8.12)
    obj.target = target;
    std::erase(generated_names_, name);
  }
  TextureUnitBinding& u = units_[active_unit_];
  (target == gl::TEXTURE_1D ? u.bound_1d : u.bound_2d) = name;
}

void Context::genTextures(int n, std::uint32_t* names) {
  if (reject_in_begin("glGenTextures")) return;
  if (n < 0) {
    error(gl::INVALID_VALUE, "glGenTextures", "negative count");
    return;
  }
  std::uint32_t next = 1;
  for (int i = 0; i < n; ++i) {
    while (textures_.count(next) != 0 || std::find(generated_names_.begin(), generated_names_.end(), next) !=
                                             generated_names_.end())
      ++next;
    generated_names_.push_back(next);
    names[i] = next;
  }
}

void Context::deleteTextures(int n, const std::uint32_t* names) {
  if (reject_in_begin("glDeleteTextures")) return;
  if (n < 0) {
    error(gl::INVALID_VALUE, "glDeleteTextures", "negative count");
    return;
  }
  for (int i = 0; i < n; ++i) {
    const std::uint32_t name = names[i];
    if (name == 0) continue;  // silently ignored (§3.8.12)
    textures_.erase(name);
    std::erase(generated_names_, name);
    for (TextureUnitBinding& u : units_) {  // a deleted bound texture reverts to 0
      if (u.bound_1d == name) u.bound_1d = 0;
      if (u.bound_2d == name) u.bound_2d = 0;
    }
  }
}

bool Context::tex_parameter(const char* fn, GLenum target, GLenum pname, const double* v, int count) {
  if (reject_in_begin(fn)) return false;
  if (!is_texture_target(target))
    return error(gl::INVALID_ENUM, fn, gl::enum_name(target) + " is not TEXTURE_1D or TEXTURE_2D");
  TextureObject& obj = bound_texture(active_unit_, target);
  TextureParams& p = obj.params;
  const GLenum e = as_enum(v[0]);
  auto bad_value = [&]() {
    return error(gl::INVALID_ENUM, fn, gl::enum_name(e) + " is not a value of " + gl::enum_name(pname));
  };
  switch (pname) {
    case gl::TEXTURE_MIN_FILTER:
      if (e != gl::NEAREST && e != gl::LINEAR && !is_mipmap_filter(e)) return bad_value();
      p.min_filter = e;
      break;
    case gl::TEXTURE_MAG_FILTER:
      if (e != gl::NEAREST && e != gl::LINEAR) return bad_value();
      p.mag_filter = e;
      break;
    case gl::TEXTURE_WRAP_S:
    case gl::TEXTURE_WRAP_T:
      if (e != gl::REPEAT && e != gl::CLAMP && e != gl::CLAMP_TO_EDGE) return bad_value();
      (pname == gl::TEXTURE_WRAP_S ? p.wrap_s : p.wrap_t) = e;
      break;
    case gl::TEXTURE_BORDER_COLOR:
      if (count != 4) return error(gl::INVALID_ENUM, fn, "TEXTURE_BORDER_COLOR needs glTexParameterfv with 4 values");
      for (int c = 0; c < 4; ++c) p.border_color[c] = clamp01(v[c]);  // §3.8.4: clamped when specified
      break;
    case gl::TEXTURE_MIN_LOD: p.min_lod = v[0]; break;
    case gl::TEXTURE_MAX_LOD: p.max_lod = v[0]; break;
    case gl::TEXTURE_BASE_LEVEL:
    case gl::TEXTURE_MAX_LEVEL: {
      if (v[0] < 0 || v[0] != std::floor(v[0]) || v[0] > 1000000)
        return error(gl::INVALID_VALUE, fn, gl::enum_name(pname) + " must be a non-negative integer");
      (pname == gl::TEXTURE_BASE_LEVEL ? p.base_level : p.max_level) = static_cast<int>(v[0]);
      break;
    }
    case gl::TEXTURE_PRIORITY: p.priority = clamp01(v[0]); break;
    default: return error(gl::INVALID_ENUM, fn, gl::enum_name(pname) + " is not a texture parameter");
  }
  ++obj.version;
  return true;
}

void Context::texParameteri(GLenum target, GLenum pname, std::int64_t param) {
  const double v = static_cast<double>(param);
  tex_parameter("glTexParameteri", target, pname, &v, 1);
}
void Context::texParameterf(GLenum target, GLenum pname, double param) {
  tex_parameter("glTexParameterf", target, pname, &param, 1);
}
void Context::texParameterfv(GLenum target, GLenum pname, const double* params) {
  tex_parameter("glTexParameterfv", target, pname, params, pname == gl::TEXTURE_BORDER_COLOR ? 4 : 1);
}

void Context::not_a_texture_unit(const char* function, GLenum texture) {
  error(gl::INVALID_ENUM, function,
        gl::enum_name(texture) + " is not a texture unit (" + std::to_string(profile_.texture_units) + " units)");
}

void Context::activeTexture(GLenum texture) {
  if (reject_in_begin("glActiveTexture")) return;
  const int unit = texture_unit("glActiveTexture", texture);
  if (unit >= 0) active_unit_ = unit;
}

void Context::clientActiveTexture(GLenum texture) {
  const int unit = texture_unit("glClientActiveTexture", texture);
  if (unit >= 0) client_active_unit_ = unit;
}

bool Context::tex_env(const char* fn, GLenum target, GLenum pname, const double* v, int count) {
  if (reject_in_begin(fn)) return false;
  if (target != gl::TEXTURE_ENV) return error(gl::INVALID_ENUM, fn, gl::enum_name(target) + " is not TEXTURE_ENV");
  TexEnvState& env = texenv_[active_unit_];
  const GLenum e = as_enum(v[0]);
  auto bad_value = [&]() {
    return error(gl::INVALID_ENUM, fn, gl::enum_name(e) + " is not a value of " + gl::enum_name(pname));
  };
  auto one_of = [&](std::initializer_list<GLenum> ok) { return std::find(ok.begin(), ok.end(), e) != ok.end(); };
  switch (pname) {
    case gl::TEXTURE_ENV_MODE:
      if (!one_of({gl::REPLACE, gl::MODULATE, gl::DECAL, gl::BLEND, gl::ADD, gl::COMBINE})) return bad_value();
      env.mode = e;
      return true;
    case gl::TEXTURE_ENV_COLOR:
      if (count != 4) return error(gl::INVALID_ENUM, fn, "TEXTURE_ENV_COLOR needs glTexEnvfv with 4 values");
      for (int c = 0; c < 4; ++c) env.color[c] = clamp01(v[c]);  // §3.8.9: clamped when specified
      return true;
    case gl::COMBINE_RGB:
      if (!one_of({gl::REPLACE, gl::MODULATE, gl::ADD, gl::ADD_SIGNED, gl::INTERPOLATE, gl::SUBTRACT, gl::DOT3_RGB,
                   gl::DOT3_RGBA, gl::DOT3_RGB_EXT, gl::DOT3_RGBA_EXT}))
        return bad_value();
      env.combine_rgb = e;
      return true;
    case gl::COMBINE_ALPHA:
      if (!one_of({gl::REPLACE, gl::MODULATE, gl::ADD, gl::ADD_SIGNED, gl::INTERPOLATE, gl::SUBTRACT})) return bad_value();
      env.combine_alpha = e;
      return true;
    case gl::RGB_SCALE:
    case gl::ALPHA_SCALE:
      if (v[0] != 1 && v[0] != 2 && v[0] != 4)
        return error(gl::INVALID_VALUE, fn, gl::enum_name(pname) + " must be 1.0, 2.0 or 4.0");
      (pname == gl::RGB_SCALE ? env.rgb_scale : env.alpha_scale) = v[0];
      return true;
    default: break;
  }
  if (pname >= gl::SOURCE0_RGB && pname <= gl::SOURCE2_RGB) {
    if (!one_of({gl::TEXTURE, gl::CONSTANT, gl::PRIMARY_COLOR, gl::PREVIOUS})) return bad_value();
    env.source_rgb[pname - gl::SOURCE0_RGB] = e;
    return true;
  }
  if (pname >= gl::SOURCE0_ALPHA && pname <= gl::SOURCE2_ALPHA) {
    if (!one_of({gl::TEXTURE, gl::CONSTANT, gl::PRIMARY_COLOR, gl::PREVIOUS})) return bad_value();
    env.source_alpha[pname - gl::SOURCE0_ALPHA] = e;
    return true;
  }
  if (pname >= gl::OPERAND0_RGB && pname <= gl::OPERAND2_RGB) {
    if (!one_of({gl::SRC_COLOR, gl::ONE_MINUS_SRC_COLOR, gl::SRC_ALPHA, gl::ONE_MINUS_SRC_ALPHA})) return bad_value();
    env.operand_rgb[pname - gl::OPERAND0_RGB] = e;
    return true;
  }
  if (pname >= gl::OPERAND0_ALPHA && pname <= gl::OPERAND2_ALPHA) {
    if (!one_of({gl::SRC_ALPHA, gl::ONE_MINUS_SRC_ALPHA})) return bad_value();
    env.operand_alpha[pname - gl::OPERAND0_ALPHA] = e;
    return true;
  }
  return error(gl::INVALID_ENUM, fn, gl::enum_name(pname) + " is not a texture environment parameter");
}

void Context::texEnvi(GLenum target, GLenum pname, std::int64_t param) {
  const double v = static_cast<double>(param);
  tex_env("glTexEnvi", target, pname, &v, 1);
}
void Context::texEnvf(GLenum target, GLenum pname, double param) { tex_env("glTexEnvf", target, pname, &param, 1); }
void Context::texEnvfv(GLenum target, GLenum pname, const double* params) {
  tex_env("glTexEnvfv", target, pname, params, pname == gl::TEXTURE_ENV_COLOR ? 4 : 1);
}

}  // namespace ffsim

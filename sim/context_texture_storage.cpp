// Texture object lookup shared by the pixel path and texturing (GL121 §3.8.12).
#include "sim/context.h"

namespace ffsim {

TextureObject& Context::bound_texture(int unit, GLenum target) {
  const TextureUnitBinding& u = units_[unit];
  const std::uint32_t name = target == gl::TEXTURE_1D ? u.bound_1d : u.bound_2d;
  if (name == 0) return target == gl::TEXTURE_1D ? default_1d_ : default_2d_;
  TextureObject& obj = textures_[name];
  if (obj.target == 0) obj.target = target;
  return obj;
}

}  // namespace ffsim

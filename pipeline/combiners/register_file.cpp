#include "pipeline/combiners/register_file.h"

namespace ffsim::combiners {

int register_index(GLenum reg) {
  switch (reg) {
    case gl::ZERO: return kZero;
    case gl::CONSTANT_COLOR0_NV: return kConstantColor0;
    case gl::CONSTANT_COLOR1_NV: return kConstantColor1;
    case gl::FOG: return kFog;
    case gl::PRIMARY_COLOR_NV: return kPrimaryColor;
    case gl::SECONDARY_COLOR_NV: return kSecondaryColor;
    case gl::SPARE0_NV: return kSpare0;
    case gl::SPARE1_NV: return kSpare1;
    case gl::TEXTURE0: return kTexture0;
    case gl::TEXTURE1: return kTexture1;
    case gl::TEXTURE2: return kTexture2;
    case gl::TEXTURE3: return kTexture3;
    case gl::E_TIMES_F_NV: return kETimesF;
    case gl::SPARE0_PLUS_SECONDARY_COLOR_NV: return kSpare0PlusSecondary;
    default: return -1;
  }
}

GLenum register_enum(int index) {
  static constexpr GLenum names[] = {gl::ZERO,           gl::CONSTANT_COLOR0_NV, gl::CONSTANT_COLOR1_NV,
                                     gl::FOG,            gl::PRIMARY_COLOR_NV,   gl::SECONDARY_COLOR_NV,
                                     gl::SPARE0_NV,      gl::SPARE1_NV,          gl::TEXTURE0,
                                     gl::TEXTURE1,       gl::TEXTURE2,           gl::TEXTURE3,
                                     gl::E_TIMES_F_NV,   gl::SPARE0_PLUS_SECONDARY_COLOR_NV};
  return index >= 0 && index <= kSpare0PlusSecondary ? names[index] : gl::NONE;
}

const char* register_short_name(int index) {
  static constexpr const char* names[] = {"zero",   "const0", "const1", "fog",  "primary", "secondary",
                                          "spare0", "spare1", "tex0",   "tex1", "tex2",    "tex3",
                                          "(e*f)",  "(spare0+secondary)"};
  return index >= 0 && index <= kSpare0PlusSecondary ? names[index] : "?";
}

}  // namespace ffsim::combiners

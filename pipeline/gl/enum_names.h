// Name <-> value lookup for GLenum tokens (trace parsing, error messages).
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "pipeline/gl/enums.h"

namespace ffsim::gl {

struct EnumName {
  const char* name;  // with the GL_ prefix, as in <GL/gl.h>
  GLenum value;
};
extern const EnumName kEnumNames[];
extern const std::size_t kEnumNameCount;

// Value of a token name. Accepts "GL_FUNC_SUBTRACT" and "FUNC_SUBTRACT"; extension
// aliases (GL_FUNC_SUBTRACT_EXT, GL_TEXTURE0_ARB) resolve to the same value.
std::optional<GLenum> enum_value(std::string_view name);

// Preferred name of a value for messages: the core (unsuffixed) name when one
// exists, otherwise the extension name; "0x1234" when the value is unknown.
// Several tokens share a value (GL_ZERO, GL_NONE, GL_FALSE); `hint` picks among
// them by prefix when given (e.g. "GL_TEXTURE").
std::string enum_name(GLenum value, std::string_view hint = {});

}  // namespace ffsim::gl

#include <doctest/doctest.h>

#include "pipeline/gl/enum_names.h"

using namespace ffsim;

TEST_CASE("gl enums: names resolve with and without prefix, aliases share values") {
  // Values from the OpenGL registry (glext.h), e.g. EXT_blend_subtract: FUNC_SUBTRACT_EXT 0x800A.
  CHECK(gl::enum_value("GL_FUNC_SUBTRACT") == 0x800Au);
  CHECK(gl::enum_value("FUNC_SUBTRACT") == 0x800Au);
  CHECK(gl::enum_value("GL_FUNC_SUBTRACT_EXT") == 0x800Au);
  CHECK(gl::enum_value("GL_TEXTURE0_ARB") == gl::TEXTURE0);
  CHECK(gl::enum_value("GL_COMBINER0_NV") == 0x8550u);
  CHECK(gl::enum_value("GL_POST_COLOR_MATRIX_COLOR_TABLE") == 0x80D2u);
  CHECK_FALSE(gl::enum_value("GL_NOT_A_TOKEN").has_value());
}

TEST_CASE("gl enums: preferred names for messages") {
  CHECK(gl::enum_name(0x800A) == "GL_FUNC_SUBTRACT");
  CHECK(gl::enum_name(gl::INVALID_ENUM) == "GL_INVALID_ENUM");
  CHECK(gl::enum_name(0x8550) == "GL_COMBINER0_NV");
  CHECK(gl::enum_name(0xFFFF1234u) == "0xFFFF1234");
}

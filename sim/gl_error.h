// GL error reporting (GL 1.2.1 §2.5), plus what a debug context adds: every error
// is also reported as an event carrying the GL call and the trace line that made it.
#pragma once
#include <string>

#include "pipeline/gl/enums.h"

namespace ffsim {

// Where a call came from: a trace file position (file:line:column) or empty.
struct SourceLoc {
  std::string file;
  int line = 0;
  int column = 0;
  bool empty() const { return file.empty(); }
  std::string str() const;  // "file:line:column" (column omitted when 0)
};

struct GLErrorEvent {
  GLenum error = gl::NO_ERROR;  // INVALID_ENUM, INVALID_VALUE, INVALID_OPERATION, ...
  std::string function;         // "glBlendEquation"
  std::string message;          // what was wrong, in words
  SourceLoc where;              // the trace line, when known
  // "file:line: glBlendEquation: GL_INVALID_ENUM: mode 0x1234 is not a blend equation"
  std::string str() const;
};

}  // namespace ffsim

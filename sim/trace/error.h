// Trace errors: every problem in a trace (syntax, unknown command, bad argument,
// failed expression, missing file, include cycle) is one TraceError carrying the
// position file:line:column and the offending line, so the command line can print
//
//   shadow.trace:12:14: unknown parameter `lz`
//     glClearColor lz 0 0 1
//                  ^
#pragma once
#include <stdexcept>
#include <string>
#include <string_view>

#include "sim/gl_error.h"

namespace ffsim::trace {

class TraceError : public std::runtime_error {
 public:
  // `line_text` is the whole source line (without newline), or empty.
  TraceError(SourceLoc where, std::string message, std::string line_text = {});
  const SourceLoc& where() const { return where_; }
  const std::string& message() const { return message_; }
  const std::string& line_text() const { return line_text_; }
  // The source line and a caret under the column ("" when no line text is known).
  std::string excerpt() const;

 private:
  SourceLoc where_;
  std::string message_;
  std::string line_text_;
};

}  // namespace ffsim::trace

namespace ffsim::trace {
// Concatenation by appending (GCC 12's -Wrestrict misfires on `"literal" + string`
// chains at -O2, so messages are built with this).
template <class... T>
std::string cat(const T&... parts) {
  std::string s;
  (s.append(std::string_view(parts)), ...);
  return s;
}
}  // namespace ffsim::trace

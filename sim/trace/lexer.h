// Splitting one trace line into tokens, each with its 1-based column.
//
// Tokens are separated by spaces or tabs. A parenthesis keeps a token together
// until it closes, so `(lx * 0.5)` or `0.5*(4*x - 1)^2` is one token; a double-quoted
// string ("my file.png", with \" and \\ escapes) is one token. `#` outside a string
// starts a comment. Control characters other than tab are rejected.
#pragma once
#include <string>
#include <vector>

#include "sim/trace/error.h"

namespace ffsim::trace {

struct Token {
  std::string text;  // without the quotes for a quoted token
  int column = 1;    // 1-based column of the first character (the quote for strings)
  bool quoted = false;
};

// `where` gives file and line (its column is ignored). Throws TraceError.
std::vector<Token> tokenize_line(const std::string& line, const SourceLoc& where);

}  // namespace ffsim::trace

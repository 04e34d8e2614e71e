#include "sim/trace/lexer.h"

#include <cstdio>

namespace ffsim::trace {

namespace {
SourceLoc at(const SourceLoc& where, std::size_t index) {
  return {where.file, where.line, static_cast<int>(index) + 1};
}
}  // namespace

std::vector<Token> tokenize_line(const std::string& line, const SourceLoc& where) {
  std::vector<Token> out;
  std::size_t i = 0;
  const std::size_t n = line.size();
  while (i < n) {
    const char c = line[i];
    if (c == ' ' || c == '\t') { ++i; continue; }
    if (c == '#') break;
    const std::size_t start = i;
    Token t;
    t.column = static_cast<int>(start) + 1;
    if (c == '"') {
      t.quoted = true;
      ++i;
      bool closed = false;
      while (i < n) {
        const char d = line[i];
        if (d == '"') { closed = true; ++i; break; }
        if (d == '\\' && i + 1 < n && (line[i + 1] == '"' || line[i + 1] == '\\')) {
          t.text += line[i + 1];
          i += 2;
          continue;
        }
        if (static_cast<unsigned char>(d) < 0x20 && d != '\t') {
          char buf[48];
          std::snprintf(buf, sizeof buf, "invalid character 0x%02X", static_cast<unsigned>(static_cast<unsigned char>(d)));
          throw TraceError(at(where, i), buf, line);
        }
        t.text += d;
        ++i;
      }
      if (!closed) throw TraceError(at(where, start), "unterminated string", line);
      if (i < n && line[i] != ' ' && line[i] != '\t' && line[i] != '#')
        throw TraceError(at(where, i), "expected a space after the closing quote", line);
      out.push_back(std::move(t));
      continue;
    }
    int depth = 0;
    std::size_t open_at = 0;
    while (i < n) {
      const char d = line[i];
      if (depth == 0 && (d == ' ' || d == '\t' || d == '#')) break;
      if (static_cast<unsigned char>(d) < 0x20 && d != '\t') {
        char buf[48];
        std::snprintf(buf, sizeof buf, "invalid character 0x%02X", static_cast<unsigned>(static_cast<unsigned char>(d)));
        throw TraceError(at(where, i), buf, line);
      }
      if (d == '"') throw TraceError(at(where, i), "a quote may only start a token", line);
      if (d == '(') {
        if (depth == 0) open_at = i;
        ++depth;
      } else if (d == ')' && depth > 0) {
        --depth;
      }
      t.text += d;
      ++i;
    }
    if (depth > 0) throw TraceError(at(where, open_at), "unclosed parenthesis", line);
    out.push_back(std::move(t));
  }
  return out;
}

}  // namespace ffsim::trace

#include "sim/trace/error.h"

namespace ffsim::trace {

namespace {
std::string prefix(const SourceLoc& w) { return w.empty() ? std::string() : w.str() + ": "; }
}  // namespace

TraceError::TraceError(SourceLoc where, std::string message, std::string line_text)
    : std::runtime_error(prefix(where) + message),
      where_(std::move(where)),
      message_(std::move(message)),
      line_text_(std::move(line_text)) {}

std::string TraceError::excerpt() const {
  if (line_text_.empty()) return {};
  std::string s = std::string("  ") + line_text_ + "\n  ";
  for (int i = 1; i < where_.column && i <= static_cast<int>(line_text_.size()); ++i)
    s += line_text_[static_cast<std::size_t>(i - 1)] == '\t' ? '\t' : ' ';
  s += "^\n";
  return s;
}

}  // namespace ffsim::trace

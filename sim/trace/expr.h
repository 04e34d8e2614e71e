// Arithmetic in trace arguments, evaluated in IEEE binary64 (docs/trace-format.md,
// "Expressions").
//
//   expr    := term (('+' | '-') term)*
//   term    := unary (('*' | '/') unary)*
//   unary   := ('-' | '+') unary | power
//   power   := primary ('^' unary)?          right-associative; -2^2 = -4
//   primary := NUMBER | NAME | NAME '(' expr (',' expr)* ')' | '(' expr ')'
//
// NUMBER is decimal (1, 0.25, 1e-3) or hexadecimal integer (0xFF). NAME is a
// parameter, `pi`, or (in table expressions) a table variable. Functions: sqrt,
// sin, cos, tan, atan2, min, max, clamp(v, lo, hi), pow, abs, floor, ceil.
// Division by zero and any NaN or infinite intermediate result are errors naming
// the column of the operator or function that produced them. Nesting is limited
// to kMaxExprDepth levels and the size to kMaxExprNodes terms (evaluation recurses).
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sim/trace/error.h"

namespace ffsim::trace {

inline constexpr int kMaxExprDepth = 64;     // nested parentheses, calls and signs
inline constexpr int kMaxExprNodes = 1024;   // numbers, names and operators per expression

class Expression {
 public:
  // Parses `text`, which starts at `start` (file, line, column of its first
  // character) within `line_text`. Throws TraceError for syntax errors.
  static Expression parse(std::string_view text, const SourceLoc& start, const std::string& line_text);

  // Looks up a name; nullopt = unknown.
  using Lookup = std::function<std::optional<double>(const std::string&)>;
  // Throws TraceError (unknown name, division by zero, non-finite result).
  double eval(const Lookup& lookup) const;

  // True when the expression is one number literal (no names, no operators).
  bool is_literal() const { return nodes_.size() == 1 && nodes_[0].op == Op::Num; }

 private:
  enum class Op { Num, Var, Neg, Add, Sub, Mul, Div, Pow, Call };
  struct Node {
    Op op = Op::Num;
    double num = 0;
    std::string name;       // Var and Call
    std::vector<int> kids;  // indices into nodes_
    int column = 0;         // where errors about this node point
  };
  double eval_node(int i, const Lookup& lookup) const;
  [[noreturn]] void fail(int column, const std::string& message) const;

  std::vector<Node> nodes_;
  int root_ = 0;
  SourceLoc start_;
  std::string line_text_;
  friend class ExprParser;
};

// Formats a double the way messages show numbers: shortest round-trip text.
std::string format_number(double v);

}  // namespace ffsim::trace

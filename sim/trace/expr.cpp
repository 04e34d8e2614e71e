#include "sim/trace/expr.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>

namespace ffsim::trace {

std::string format_number(double v) {
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

namespace {
struct FunctionInfo {
  const char* name;
  int arity;
};
constexpr FunctionInfo kFunctions[] = {
    {"sqrt", 1}, {"sin", 1}, {"cos", 1}, {"tan", 1}, {"atan2", 2}, {"min", 2}, {"max", 2},
    {"clamp", 3}, {"pow", 2}, {"abs", 1}, {"floor", 1}, {"ceil", 1},
};
const FunctionInfo* find_function(const std::string& name) {
  for (const auto& f : kFunctions)
    if (name == f.name) return &f;
  return nullptr;
}
bool is_name_start(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool is_name_char(char c) { return is_name_start(c) || (c >= '0' && c <= '9'); }
bool is_digit(char c) { return c >= '0' && c <= '9'; }
}  // namespace

class ExprParser {
 public:
  ExprParser(Expression& e, std::string_view text) : e_(e), s_(text) {}

  void run() {
    skip();
    if (pos_ >= s_.size()) fail_here("empty expression");
    e_.root_ = expr(0);
    skip();
    if (pos_ < s_.size()) {
      if (s_[pos_] == ')') fail_here("unexpected `)`");
      fail_here(std::string("unexpected `") + s_[pos_] + "` after a complete expression");
    }
  }

 private:
  using Op = Expression::Op;
  int col() const { return e_.start_.column + static_cast<int>(pos_); }
  [[noreturn]] void fail_here(const std::string& m) const { e_.fail(col(), m); }
  void skip() {
    while (pos_ < s_.size() && (s_[pos_] == ' ' || s_[pos_] == '\t')) ++pos_;
  }
  int add(Expression::Node n) {
    if (e_.nodes_.size() >= static_cast<std::size_t>(kMaxExprNodes))
      e_.fail(n.column, std::string("expression too long (more than ") + std::to_string(kMaxExprNodes) + " terms)");
    e_.nodes_.push_back(std::move(n));
    return static_cast<int>(e_.nodes_.size()) - 1;
  }
  int binary(Op op, int column, int a, int b) {
    Expression::Node n;
    n.op = op;
    n.column = column;
    n.kids = {a, b};
    return add(std::move(n));
  }
  void enter(int depth) const {
    if (depth > kMaxExprDepth)
      e_.fail(col(), std::string("expression nested too deeply (more than ") + std::to_string(kMaxExprDepth) + " levels)");
  }

  int expr(int depth) {
    enter(depth);
    int left = term(depth);
    for (;;) {
      skip();
      if (pos_ >= s_.size() || (s_[pos_] != '+' && s_[pos_] != '-')) return left;
      const Op op = s_[pos_] == '+' ? Op::Add : Op::Sub;
      const int c = col();
      ++pos_;
      left = binary(op, c, left, term(depth));
    }
  }
  int term(int depth) {
    enter(depth);
    int left = unary(depth);
    for (;;) {
      skip();
      if (pos_ >= s_.size() || (s_[pos_] != '*' && s_[pos_] != '/')) return left;
      const Op op = s_[pos_] == '*' ? Op::Mul : Op::Div;
      const int c = col();
      ++pos_;
      left = binary(op, c, left, unary(depth));
    }
  }
  int unary(int depth) {
    enter(depth);
    skip();
    if (pos_ < s_.size() && (s_[pos_] == '-' || s_[pos_] == '+')) {
      const bool neg = s_[pos_] == '-';
      const int c = col();
      ++pos_;
      const int k = unary(depth + 1);
      if (!neg) return k;
      Expression::Node n;
      n.op = Op::Neg;
      n.column = c;
      n.kids = {k};
      return add(std::move(n));
    }
    return power(depth);
  }
  int power(int depth) {
    enter(depth);
    const int base = primary(depth);
    skip();
    if (pos_ < s_.size() && s_[pos_] == '^') {
      const int c = col();
      ++pos_;
      return binary(Op::Pow, c, base, unary(depth + 1));
    }
    return base;
  }
  int primary(int depth) {
    enter(depth);
    skip();
    if (pos_ >= s_.size()) fail_here("unexpected end of expression");
    const char c = s_[pos_];
    const int start_col = col();
    if (c == '(') {
      ++pos_;
      const int k = expr(depth + 1);
      skip();
      if (pos_ >= s_.size() || s_[pos_] != ')') fail_here("expected `)`");
      ++pos_;
      return k;
    }
    if (is_digit(c) || (c == '.' && pos_ + 1 < s_.size() && is_digit(s_[pos_ + 1]))) return number();
    if (is_name_start(c)) {
      std::size_t e = pos_;
      while (e < s_.size() && is_name_char(s_[e])) ++e;
      std::string name(s_.substr(pos_, e - pos_));
      pos_ = e;
      skip();
      if (pos_ < s_.size() && s_[pos_] == '(') {
        const FunctionInfo* f = find_function(name);
        if (!f) e_.fail(start_col, std::string("unknown function `") + name + "`");
        ++pos_;
        Expression::Node n;
        n.op = Op::Call;
        n.name = name;
        n.column = start_col;
        for (;;) {
          n.kids.push_back(expr(depth + 1));
          skip();
          if (pos_ < s_.size() && s_[pos_] == ',') { ++pos_; continue; }
          if (pos_ < s_.size() && s_[pos_] == ')') { ++pos_; break; }
          fail_here(std::string("expected `,` or `)` in the arguments of `") + name + "`");
        }
        if (static_cast<int>(n.kids.size()) != f->arity)
          e_.fail(start_col, std::string("`") + name + "` takes " + std::to_string(f->arity) + " argument" +
                                 std::string(f->arity == 1 ? "" : "s") + ", got " + std::to_string(n.kids.size()));
        return add(std::move(n));
      }
      Expression::Node n;
      n.op = Op::Var;
      n.name = std::move(name);
      n.column = start_col;
      return add(std::move(n));
    }
    if (c == ')') fail_here("unexpected `)`");
    fail_here(std::string("unexpected `") + c + "`; expected a number, a name or `(`");
  }
  int number() {
    const std::size_t start = pos_;
    const int start_col = col();
    Expression::Node n;
    n.column = start_col;
    if (s_[pos_] == '0' && pos_ + 1 < s_.size() && (s_[pos_ + 1] == 'x' || s_[pos_ + 1] == 'X')) {
      std::size_t e = pos_ + 2;
      std::uint64_t v = 0;
      const char* b = s_.data() + e;
      while (e < s_.size() && std::isxdigit(static_cast<unsigned char>(s_[e]))) ++e;
      auto r = std::from_chars(b, s_.data() + e, v, 16);
      if (e == pos_ + 2 || r.ec != std::errc() || v > 0xFFFFFFFFull) {
        pos_ = start;
        fail_here("bad hexadecimal number (0x followed by 1 to 8 hex digits)");
      }
      pos_ = e;
      n.num = static_cast<double>(v);
    } else {
      std::size_t e = pos_;
      while (e < s_.size() && (is_digit(s_[e]) || s_[e] == '.')) ++e;
      if (e < s_.size() && (s_[e] == 'e' || s_[e] == 'E')) {
        std::size_t f = e + 1;
        if (f < s_.size() && (s_[f] == '+' || s_[f] == '-')) ++f;
        if (f < s_.size() && is_digit(s_[f])) {
          while (f < s_.size() && is_digit(s_[f])) ++f;
          e = f;
        }
      }
      double v = 0;
      auto r = std::from_chars(s_.data() + pos_, s_.data() + e, v);
      if (r.ec == std::errc::result_out_of_range && r.ptr == s_.data() + e)
        fail_here(cat("number `", s_.substr(pos_, e - pos_), "` is out of range"));
      if (r.ec != std::errc() || r.ptr != s_.data() + e) fail_here(cat("bad number `", s_.substr(pos_, e - pos_), "`"));
      if (!std::isfinite(v)) fail_here(std::string("number `") + std::string(s_.substr(pos_, e - pos_)) + "` is out of range");
      pos_ = e;
      n.num = v;
    }
    if (pos_ < s_.size() && is_name_char(s_[pos_])) fail_here(std::string("unexpected `") + s_[pos_] + "` after a number");
    return add(std::move(n));
  }

  Expression& e_;
  std::string_view s_;
  std::size_t pos_ = 0;
};

Expression Expression::parse(std::string_view text, const SourceLoc& start, const std::string& line_text) {
  Expression e;
  e.start_ = start;
  e.line_text_ = line_text;
  ExprParser(e, text).run();
  return e;
}

void Expression::fail(int column, const std::string& message) const {
  throw TraceError({start_.file, start_.line, column}, message, line_text_);
}

double Expression::eval(const Lookup& lookup) const { return eval_node(root_, lookup); }

double Expression::eval_node(int i, const Lookup& lookup) const {
  const Node& n = nodes_[static_cast<std::size_t>(i)];
  auto arg = [&](std::size_t k) { return eval_node(n.kids[k], lookup); };
  double r = 0;
  const char* what = nullptr;
  switch (n.op) {
    case Op::Num: return n.num;
    case Op::Var: {
      if (auto v = lookup(n.name)) return *v;
      if (n.name == "pi") return 3.14159265358979323846;
      fail(n.column, std::string("unknown parameter `") + n.name + "`");
    }
    case Op::Neg: return -arg(0);
    case Op::Add: r = arg(0) + arg(1); what = "`+`"; break;
    case Op::Sub: r = arg(0) - arg(1); what = "`-`"; break;
    case Op::Mul: r = arg(0) * arg(1); what = "`*`"; break;
    case Op::Div: {
      const double a = arg(0), b = arg(1);
      if (b == 0) fail(n.column, "division by zero");
      r = a / b;
      what = "`/`";
      break;
    }
    case Op::Pow: r = std::pow(arg(0), arg(1)); what = "`^`"; break;
    case Op::Call: {
      const std::string& f = n.name;
      what = f.c_str();
      if (f == "sqrt") {
        const double a = arg(0);
        if (a < 0) fail(n.column, std::string("sqrt of a negative number (") + format_number(a) + ")");
        r = std::sqrt(a);
      } else if (f == "sin") r = std::sin(arg(0));
      else if (f == "cos") r = std::cos(arg(0));
      else if (f == "tan") r = std::tan(arg(0));
      else if (f == "atan2") { const double y = arg(0); r = std::atan2(y, arg(1)); }
      else if (f == "min") { const double a = arg(0); r = std::min(a, arg(1)); }
      else if (f == "max") { const double a = arg(0); r = std::max(a, arg(1)); }
      else if (f == "clamp") {
        const double v = arg(0), lo = arg(1), hi = arg(2);
        if (lo > hi) fail(n.column, std::string("clamp: low bound ") + format_number(lo) + " is above high bound " + format_number(hi));
        r = std::min(std::max(v, lo), hi);
      } else if (f == "pow") { const double a = arg(0); r = std::pow(a, arg(1)); }
      else if (f == "abs") r = std::fabs(arg(0));
      else if (f == "floor") r = std::floor(arg(0));
      else r = std::ceil(arg(0));  // ceil: the parser admits only the functions above
      break;
    }
  }
  const std::string op = n.op == Op::Call ? cat("`", what, "`") : std::string(what);
  if (std::isnan(r)) fail(n.column, cat("result of ", op, " is not a number (NaN)"));
  if (std::isinf(r)) fail(n.column, cat("result of ", op, " is infinite"));
  return r;
}

}  // namespace ffsim::trace

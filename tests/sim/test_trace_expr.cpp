// Trace expressions (sim/trace/expr.h): binary64 arithmetic, precedence, functions,
// and each error with its exact column. Expected values are hand-derived.
#include <doctest/doctest.h>

#include <cmath>
#include <map>

#include "sim/trace/expr.h"

using namespace ffsim;
using namespace ffsim::trace;

namespace {
double ev(const std::string& text, std::map<std::string, double> vars = {}) {
  const auto e = Expression::parse(text, {"t.trace", 3, 10}, "line");
  return e.eval([&](const std::string& n) -> std::optional<double> {
    auto it = vars.find(n);
    if (it == vars.end()) return std::nullopt;
    return it->second;
  });
}
std::string err(const std::string& text) {
  try {
    ev(text, {{"lx", 0.3}});
  } catch (const TraceError& e) {
    return e.what();
  }
  return "no error";
}
}  // namespace

TEST_CASE("trace expr: precedence, associativity and unary minus") {
  CHECK(ev("1+2*3") == 7);
  CHECK(ev("(1+2)*3") == 9);
  CHECK(ev("8/2/2") == 2);            // left-associative
  CHECK(ev("2^3^2") == 512);          // right-associative: 2^(3^2)
  CHECK(ev("-2^2") == -4);            // unary minus binds looser than ^
  CHECK(ev("2^-1") == 0.5);
  CHECK(ev("--3") == 3);
  CHECK(ev("+4") == 4);
  CHECK(ev(" 1 + 2 ") == 3);
  CHECK(ev("0x10") == 16);
  CHECK(ev("0xFFFFFFFF") == 4294967295.0);
  CHECK(ev("1e-3") == 0.001);
  CHECK(ev(".5") == 0.5);
}

TEST_CASE("trace expr: names and functions") {
  CHECK(ev("lx*2", {{"lx", 0.25}}) == 0.5);
  CHECK(ev("pi") == 3.14159265358979323846);
  CHECK(ev("sqrt(16)") == 4);
  CHECK(ev("min(3, 4)") == 3);
  CHECK(ev("max(3,4)") == 4);
  CHECK(ev("clamp(5, 0, 1)") == 1);
  CHECK(ev("clamp(-5, 0, 1)") == 0);
  CHECK(ev("pow(2, 10)") == 1024);
  CHECK(ev("abs(-2)") == 2);
  CHECK(ev("floor(2.5)") == 2);
  CHECK(ev("ceil(2.5)") == 3);
  CHECK(ev("atan2(1, 1)") == std::atan2(1.0, 1.0));
  CHECK(ev("sin(0)+cos(0)+tan(0)") == 1);
  // The paper's lookup table (equation 4.2) at a = 0.75: (4*0.75-1)^2/2 = 2.
  CHECK(ev("0.5*(4*x-1)^2", {{"x", 0.75}}) == 2);
}

TEST_CASE("trace expr: syntax errors name the column") {
  // The expression starts at column 10 of line 3.
  CHECK(err("") == "t.trace:3:10: empty expression");
  CHECK(err("1+") == "t.trace:3:12: unexpected end of expression");
  CHECK(err("(1+2") == "t.trace:3:14: expected `)`");
  CHECK(err("1+2)") == "t.trace:3:13: unexpected `)`");
  CHECK(err("1 2") == "t.trace:3:12: unexpected `2` after a complete expression");
  CHECK(err("1..2") == "t.trace:3:10: bad number `1..2`");
  CHECK(err("2x") == "t.trace:3:11: unexpected `x` after a number");
  CHECK(err("0x") == "t.trace:3:10: bad hexadecimal number (0x followed by 1 to 8 hex digits)");
  CHECK(err("0x100000000") == "t.trace:3:10: bad hexadecimal number (0x followed by 1 to 8 hex digits)");
  CHECK(err("1e999") == "t.trace:3:10: number `1e999` is out of range");
  CHECK(err("1 $ 2") == "t.trace:3:12: unexpected `$` after a complete expression");
  CHECK(err("*2") == "t.trace:3:10: unexpected `*`; expected a number, a name or `(`");
  CHECK(err("foo(1)") == "t.trace:3:10: unknown function `foo`");
  CHECK(err("min(1)") == "t.trace:3:10: `min` takes 2 arguments, got 1");
  CHECK(err("sqrt(1,2)") == "t.trace:3:10: `sqrt` takes 1 argument, got 2");
  CHECK(err("min(1;2)") == "t.trace:3:15: expected `,` or `)` in the arguments of `min`");
}

TEST_CASE("trace expr: evaluation errors name the operator") {
  CHECK(err("lz") == "t.trace:3:10: unknown parameter `lz`");
  CHECK(err("1+lz*2") == "t.trace:3:12: unknown parameter `lz`");
  CHECK(err("1/(lx-lx)") == "t.trace:3:11: division by zero");
  CHECK(err("0/0") == "t.trace:3:11: division by zero");
  CHECK(err("sqrt(-1)") == "t.trace:3:10: sqrt of a negative number (-1)");
  CHECK(err("pow(-8, 1/3)") == "t.trace:3:10: result of `pow` is not a number (NaN)");
  CHECK(err("10^400") == "t.trace:3:12: result of `^` is infinite");
  CHECK(err("1e300*1e300") == "t.trace:3:15: result of `*` is infinite");
  CHECK(err("clamp(1, 2, 0)") == "t.trace:3:10: clamp: low bound 2 is above high bound 0");
}

TEST_CASE("trace expr: nesting is capped") {
  std::string deep(200, '(');
  deep += std::string("1") + std::string(200, ')');
  const std::string m = err(deep);
  CHECK(m.find("expression nested too deeply (more than 64 levels)") != std::string::npos);
  std::string minus(5000, '-');
  CHECK(err(minus + "1").find("expression nested too deeply") != std::string::npos);
  // 20 levels are fine.
  CHECK(ev(std::string(20, '(') + "2" + std::string(20, ')')) == 2);
}

TEST_CASE("trace expr: length is capped") {
  std::string sum = "1";
  for (int k = 0; k < 2000; ++k) sum += "+1";
  CHECK(err(sum).find("expression too long (more than 1024 terms)") != std::string::npos);
  std::string ok = "1";
  for (int k = 0; k < 300; ++k) ok += "+1";
  CHECK(ev(ok) == 301);
}

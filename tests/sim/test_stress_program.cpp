// `ffsim stress` (sim/stress/stress.cpp): the report's format, reproducibility
// (the same seed and case count give the same report), --repro, and usage errors.
#include <doctest/doctest.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "sim/stress/stress.h"

namespace {

const std::string kTraces = std::string(FFSIM_SOURCE_DIR) + "/traces";

struct Out {
  int code = 0;
  std::string out, err;
};

Out run(std::vector<std::string> args) {
  std::ostringstream o, e;
  Out r;
  r.code = ffsim::stress::run(args, o, e);
  r.out = o.str();
  r.err = e.str();
  return r;
}

// The report without its last line (the elapsed time).
std::string without_elapsed(const std::string& s) {
  const auto p = s.rfind("elapsed: ");
  return p == std::string::npos ? s : s.substr(0, p);
}

}  // namespace

TEST_CASE("stress program: a few cases give the report sections, exit 0, and the same output for the same seed") {
  const std::vector<std::string> args = {"--cases", "6", "--seed", "12", "--traces", kTraces};
  const Out a = run(args), b = run(args);
  CAPTURE(a.out);
  CAPTURE(a.err);
  CHECK(a.code == 0);
  CHECK(a.err.empty());
  CHECK(a.out.rfind("ffsim stress: master seed 12, 6 cases, kinds ellipse, light, field, trace\n", 0) == 0);
  CHECK(a.out.find("cases: 6  ellipse 2  light 2  field 1  trace 1\n") != std::string::npos);
  CHECK(a.out.find("range violations (the paper's assumptions") != std::string::npos);
  CHECK(a.out.find("worst case per metric") != std::string::npos);
  CHECK(a.out.find("combiner geforce256 err/bound: ") != std::string::npos);
  CHECK(a.out.find("--repro 0x") != std::string::npos);
  CHECK(a.out.find("hard invariant violations: 0\n") != std::string::npos);
  CHECK(a.out.find("elapsed: ") != std::string::npos);
  CHECK(without_elapsed(a.out) == without_elapsed(b.out));
  // Another seed gives other cases.
  const Out c = run({"--cases", "6", "--seed", "13", "--traces", kTraces});
  CHECK(without_elapsed(c.out) != without_elapsed(a.out));
}

TEST_CASE("stress program: --repro replays one case verbosely and identically") {
  const Out a = run({"--cases", "1", "--case", "ellipse", "--seed", "5", "--verbose"});
  CHECK(a.code == 0);
  const auto p = a.out.find("seed 0x");
  REQUIRE(p != std::string::npos);
  const std::string seed = a.out.substr(p + 5, 18);
  const Out r1 = run({"--case", "ellipse", "--repro", seed}), r2 = run({"--case", "ellipse", "--repro", seed});
  CAPTURE(r1.out);
  CHECK(r1.code == 0);
  CHECK(r1.out.rfind("case ellipse seed " + seed + ": 24 ellipses ", 0) == 0);
  CHECK(r1.out.find("  light (") != std::string::npos);
  CHECK(r1.out.find("  ellipse C=(") != std::string::npos);
  CHECK(r1.out.find("  combiner ") != std::string::npos);
  CHECK(r1.out == r2.out);
}

TEST_CASE("stress program: bad options give a one-line usage error and exit 2") {
  for (const auto& args : std::vector<std::vector<std::string>>{{"--bogus"},
                                                               {"--seconds"},
                                                               {"--seconds", "-1"},
                                                               {"--seconds", "x"},
                                                               {"--cases", "3", "--seconds", "1"},
                                                               {"--case", "nope"},
                                                               {"--seed", "-4"},
                                                               {"--repro", "zz"}}) {
    const Out r = run(args);
    CAPTURE(args.front());
    CHECK(r.code == 2);
    CHECK(r.out.empty());
    CHECK(r.err.rfind("ffsim stress: ", 0) == 0);
    CHECK(r.err.find("usage: ffsim stress") != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
  const Out h = run({"--help"});
  CHECK(h.code == 0);
  CHECK(h.out.rfind("usage: ffsim stress", 0) == 0);
}

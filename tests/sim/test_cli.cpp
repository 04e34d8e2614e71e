#include <doctest/doctest.h>

#include <sstream>

#include "cli_test_util.h"
#include "sim/cli/cli.h"

using namespace ffsim;

namespace {
using test::Run;
using test::run;
}  // namespace

TEST_CASE("cli: --version and --help") {
  const Run v = run({"--version"});
  CHECK(v.code == 0);
  CHECK(v.out == "ffsim " FFSIM_VERSION "\n");
  const Run h = run({"--help"});
  CHECK(h.code == 0);
  for (const char* sub : {"replay", "diff", "bench", "bumpshadow", "profiles", "demo"})
    CHECK(h.out.find(std::string("  ") + sub) != std::string::npos);
  // Every command's line: the name, at least two spaces, the summary (the
  // longest name, paper-report, once ran into its summary).
  const std::size_t list = h.out.find("commands:\n");
  REQUIRE(list != std::string::npos);
  std::size_t at = list + 10, lines = 0;
  for (std::size_t end; (end = h.out.find('\n', at)) != std::string::npos && end > at; at = end + 1, ++lines) {
    const std::string line = h.out.substr(at, end - at);
    INFO(line);
    REQUIRE(line.rfind("  ", 0) == 0);
    const std::size_t gap = line.find("  ", 2);
    CHECK(gap != std::string::npos);
    CHECK(line.find(' ', 2) == gap);  // the name has no space; the gap follows it
  }
  CHECK(lines >= 10);
  CHECK(h.out.find("  paper-report  ") != std::string::npos);
}

TEST_CASE("cli: unknown flags and subcommands are one-line errors with exit code 2") {
  const Run a = run({"--frobnicate"});
  CHECK(a.code == 2);
  CHECK(a.err == "ffsim: unknown option `--frobnicate` (see `ffsim --help`)\n");
  const Run b = run({"frobnicate"});
  CHECK(b.code == 2);
  CHECK(b.err == "ffsim: unknown command `frobnicate` (see `ffsim --help`)\n");
  const Run c = run({"demo", "--bogus"});
  CHECK(c.code == 2);
  CHECK(c.err == "ffsim demo: unknown argument `--bogus` (see `ffsim demo --help`)\n");
  const Run d = run({});
  CHECK(d.code == 2);
}

TEST_CASE("cli: profiles lists and prints profiles, a bad name is a failure") {
  const Run l = run({"profiles"});
  CHECK(l.code == 0);
  CHECK(l.out.find("geforce256\t") == 0);
  const Run p = run({"profiles", "geforce256"});
  CHECK(p.out.find("combiner_bits = 9\n") != std::string::npos);
  const Run bad = run({"profiles", "/no/such/profile"});
  CHECK(bad.code == 1);
}

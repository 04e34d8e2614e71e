// Comparing two replays of one trace (tests/sim/test_*.cpp): the same outcome,
// every `hash` step's value, the final buffers and the GL errors.
#pragma once
#include <doctest/doctest.h>

#include "sim/trace/executor.h"

namespace ffsim::test {

inline void check_same_run(const trace::RunResult& a, const trace::RunResult& b) {
  REQUIRE(a.ok);
  REQUIRE(b.ok);
  REQUIRE(a.hashes.size() == b.hashes.size());
  for (std::size_t k = 0; k < a.hashes.size(); ++k) {
    INFO("hash step at ", a.hashes[k].where.str());
    CHECK(a.hashes[k].hex == b.hashes[k].hex);
  }
  CHECK(a.final_hashes == b.final_hashes);
  CHECK(a.gl_errors == b.gl_errors);
}

}  // namespace ffsim::test

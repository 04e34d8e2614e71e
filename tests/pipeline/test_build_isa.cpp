// The build's instruction set must not change a result (CMakeLists.txt,
// FFSIM_ARCH; docs/performance.md "Build"). This is the reproducer that keeps
// AVX-512 out of the default: GCC 12.2 with -march=x86-64-v4 (or native on an
// AVX-512 machine) compiles the comparison below to false at -O2 and -O3, which
// first showed as a failing convolution test. Every golden hash of the suite
// checks the rest of the pipeline under the chosen -march.
#include <doctest/doctest.h>

#include <vector>

namespace {

volatile double g_three = 3.0;  // opaque to the optimiser

__attribute__((noinline)) std::vector<double> three_threes(double x) {
  std::vector<double> v(4, 0.0);
  v[0] = v[1] = v[2] = x;
  return v;
}

}  // namespace

TEST_CASE("build: vector<double> equality survives the instruction set (GCC 12 AVX-512 miscompile guard)") {
  const std::vector<double> v = three_threes(g_three);
  CHECK(v == std::vector<double>{3, 3, 3, 0});
  CHECK(three_threes(g_three) == std::vector<double>{3, 3, 3, 0});
}

// Preloaded into ffsim only under valgrind, only where valgrind cannot start it
// otherwise (tests/memcheck.sh): libhwy 1.0 (OpenImageIO -> libjxl -> libhwy)
// calibrates its cycle timer in a load-time initialiser with RDTSCP, which
// valgrind 3.19 refuses when the CPUID it sees hides RDTSCP (AMD Zen 4 virtual
// machines), killing the process before main. This definition takes the
// place of hwy::platform::TimerResolution (a timer ffsim never reads: libjxl
// uses libhwy for its SIMD dispatch), so memcheck can check ffsim's own code.
#include <cstdint>

namespace hwy::platform {
std::uint64_t TimerResolution() { return 1; }
}  // namespace hwy::platform

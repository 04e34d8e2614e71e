// ffsim: thin entry point; everything lives in sim/cli (tested directly).
#include <exception>
#include <iostream>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "sim/cli/cli.h"

int main(int argc, char** argv) {
#if defined(__GLIBC__)
  // Large blocks (a framebuffer, a CopyPixels image: megabytes) come from the
  // heap and stay there when freed, instead of being mapped and unmapped each
  // time: a Context per frame (ffsim bench, paper) then reuses warm pages rather
  // than faulting in fresh ones every frame (kautz-imaging-hard at 1024^2 spent
  // a third of its time in page faults; docs/performance.md 20.4). Freed memory
  // beyond 1 GiB at the heap's top is still returned. No computed value depends
  // on it. The library itself leaves the process's allocator alone.
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
  try {
    return ffsim::cli::run(std::vector<std::string>(argv + 1, argv + argc), std::cout, std::cerr);
  } catch (const std::exception& e) {
    std::cerr << "ffsim: internal error: " << e.what() << "\n";
    return 1;
  }
}

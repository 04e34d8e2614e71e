// The one translation unit that instantiates doctest's runner for a test binary.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#ifdef FFSIM_SANITIZE
// Sanitizer defaults baked into the test binaries, so `ctest` and a direct run of
// a test binary behave the same (environment variables still override them).
extern "C" const char* __asan_default_options() {
  // Full stacks on malloc, so the suppression below can match frames inside libraries.
  return "detect_leaks=1:abort_on_error=1:fast_unwind_on_malloc=0";
}
extern "C" const char* __ubsan_default_options() { return "print_stacktrace=1:halt_on_error=1"; }
// Third-party leaks only. OpenImageIO 2.4's PNG reader reports a truncated file
// from libpng's read callback; libpng then longjmps out, skipping the destructor
// of the error string (31 bytes per corrupt PNG; tests/sim/test_image_io.cpp).
extern "C" const char* __lsan_default_suppressions() {
  return "leak:OpenImageIO_v2_4::PNGInput::PngReadCallback\n";
}
#endif

// The one translation unit that instantiates doctest's runner for a test binary.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cstdio>
#include <string>

namespace {

// CTest runs each test case as `binary --test-case=NAME`. A filter that selects
// nothing passes in doctest, so a name CTest split or changed (a ';' in it:
// tests/CMakeLists.txt) would be a test that never runs and never fails. The
// listener counts the test cases that passed the filters; main fails when a
// --test-case filter selected none.
unsigned selected_test_cases = 0;

struct SelectedCount : doctest::IReporter {
  explicit SelectedCount(const doctest::ContextOptions&) {}
  void report_query(const doctest::QueryData&) override {}
  void test_run_start() override {}
  void test_run_end(const doctest::TestRunStats& s) override { selected_test_cases = s.numTestCasesPassingFilters; }
  void test_case_start(const doctest::TestCaseData&) override {}
  void test_case_reenter(const doctest::TestCaseData&) override {}
  void test_case_end(const doctest::CurrentTestCaseStats&) override {}
  void test_case_exception(const doctest::TestCaseException&) override {}
  void subcase_start(const doctest::SubcaseSignature&) override {}
  void subcase_end() override {}
  void log_assert(const doctest::AssertData&) override {}
  void log_message(const doctest::MessageData&) override {}
  void test_case_skipped(const doctest::TestCaseData&) override {}
};
DOCTEST_REGISTER_LISTENER("selected_count", 1, SelectedCount);

bool has_test_case_filter(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    for (const char* f : {"--test-case=", "-tc=", "--dt-test-case=", "--dt-tc="})
      if (a.rfind(f, 0) == 0) return true;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  doctest::Context context(argc, argv);
  const int rc = context.run();
  if (context.shouldExit()) return rc;  // (a query: --list-test-cases, --help, ...)
  if (rc == 0 && has_test_case_filter(argc, argv) && selected_test_cases == 0) {
    std::fprintf(stderr, "no test case matches the --test-case filter: nothing ran\n");
    return 1;
  }
  return rc;
}

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

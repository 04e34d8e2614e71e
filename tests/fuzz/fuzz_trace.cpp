// Fuzz driver for the trace loader and executor: deterministically mutates the
// traces in a corpus directory (seeded PRNG) and feeds each mutant through
// load_trace_text and run_program, for a bounded number of iterations and time.
// A TraceError is the expected outcome of a bad input; any other exception, a
// crash, a hang (CTest timeout) or a sanitizer report is a finding. On a finding
// the input is written to fuzz-finding.trace and the exit code is 1.
//
// usage: fuzz_trace --corpus DIR [--iterations N] [--seconds S] [--seed K]
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "sim/trace/executor.h"
#include "sim/trace/trace.h"

#ifdef FFSIM_SANITIZE
// The same sanitizer defaults as the doctest binaries (tests/doctest_main.cpp).
extern "C" const char* __asan_default_options() { return "detect_leaks=1:abort_on_error=1:fast_unwind_on_malloc=0"; }
extern "C" const char* __ubsan_default_options() { return "print_stacktrace=1:halt_on_error=1"; }
extern "C" const char* __lsan_default_suppressions() { return "leak:OpenImageIO_v2_4::PNGInput::PngReadCallback\n"; }
#endif

namespace fs = std::filesystem;
using namespace ffsim;

namespace {

struct Rng {  // splitmix64: small, fast, the same sequence everywhere
  std::uint64_t s;
  std::uint64_t next() {
    std::uint64_t z = (s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  std::size_t below(std::size_t n) { return n ? static_cast<std::size_t>(next() % n) : 0; }
};

// Fragments that reach the interesting paths: syntax, limits, expressions, enums.
const char* const kDictionary[] = {
    "(", ")", "\"", "#", "|", "=", "\n", "\t", " ", "-", "^", "/0", "0x", "1e308", "1e-320", "-0", "..",
    "ffsim-trace 1\n", "ffsim-trace 2\n", "param p 1\n", "--", "sqrt(-1)", "atan2(", "clamp(1,2,0)", "pow(0,-1)",
    "glClear GL_COLOR_BUFFER_BIT|GL_STENCIL_BUFFER_BIT|GL_DEPTH_BUFFER_BIT\n", "glClearColor 1 0.5 0 1\n",
    "glScissor -5 -5 1000 1000\n", "glEnable GL_SCISSOR_TEST\n", "glColorMask 0 1 0 1\n", "glStencilMask 0xFFFFFFFF\n",
    "glPopMatrix\n", "glPushMatrix\n", "glMatrixMode GL_COLOR\n", "glLoadMatrixd", " 1 0 0 0", "glOrtho 0 1 0 1 1 1\n",
    "GL_", "GL_TRUE", "GL_BLEND", "0xFFFFFFFF", "4294967296", "framebuffer 128 128\n", "framebuffer 16384 16384\n",
    "profile ideal\n", "profile float32\n", "profile rgba12\n", "profile nonesuch\n", "include main.trace\n",
    "include setup.trace\n", "include ../x.trace\n", "include /dev/zero\n", "image q quad.png\n", "image q setup.trace\n",
    "table t 65536 x\n", "table t 300 sin(i)*1e38 x i n\n", "generate g hemisphere_bump width=128 height=128 radius=40\n",
    "generate g hemisphere_bump border=wrap\n", "dump color a.png\n", "dump depth d.exr\n", "dump stencil ../s.png\n",
    "hash depth\n", "hash stencil\n", "expect pixel 0 0 color 1 1 1 1 tol 1\n", "expect error GL_INVALID_VALUE\n",
    "expect hash alpha 0123456789abcdef\n", "(((((((((((((((((((((((((((((((((", ")))))))))))))))))", "1+1+1+1+1+1+1+1",
};

std::string mutate(Rng& r, const std::vector<std::string>& corpus) {
  std::string s = corpus[r.below(corpus.size())];
  const int rounds = 1 + static_cast<int>(r.below(4));
  for (int k = 0; k < rounds; ++k) {
    const std::size_t pos = r.below(s.size() + 1);
    switch (r.below(7)) {
      case 0:  // flip a byte
        if (!s.empty()) s[r.below(s.size())] = static_cast<char>(r.next());
        break;
      case 1:  // insert a dictionary fragment
        s.insert(pos, kDictionary[r.below(sizeof kDictionary / sizeof kDictionary[0])]);
        break;
      case 2: {  // delete a range
        const std::size_t n = r.below(16) + 1;
        if (pos < s.size()) s.erase(pos, n);
        break;
      }
      case 3: {  // duplicate a range
        if (s.empty()) break;
        const std::size_t a = r.below(s.size()), n = std::min<std::size_t>(r.below(64) + 1, s.size() - a);
        s.insert(pos, s.substr(a, n));
        break;
      }
      case 4: {  // splice in a piece of another corpus file
        const std::string& o = corpus[r.below(corpus.size())];
        if (o.empty()) break;
        const std::size_t a = r.below(o.size()), n = std::min<std::size_t>(r.below(200) + 1, o.size() - a);
        s.insert(pos, o.substr(a, n));
        break;
      }
      case 5:  // replace a digit by another number
        for (std::size_t i = pos; i < s.size(); ++i)
          if (s[i] >= '0' && s[i] <= '9') {
            static const char* const nums[] = {"0", "-1", "65535", "16385", "1e9", "0.5", "255", "3.4e38", "2147483648"};
            s.replace(i, 1, nums[r.below(sizeof nums / sizeof nums[0])]);
            break;
          }
        break;
      default:  // insert a random printable byte
        s.insert(pos, 1, static_cast<char>(0x20 + r.below(0x5f)));
        break;
    }
  }
  if (s.size() > 64 * 1024) s.resize(64 * 1024);
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  std::string corpus_dir;
  long long iterations = 20000;
  double seconds = 15;
  std::uint64_t seed = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) {
      std::cerr << "fuzz_trace: " << a << " needs a value\n";
      return 2;
    }
    const std::string v = argv[++i];
    if (a == "--corpus") corpus_dir = v;
    else if (a == "--iterations") iterations = std::atoll(v.c_str());
    else if (a == "--seconds") seconds = std::atof(v.c_str());
    else if (a == "--seed") seed = std::strtoull(v.c_str(), nullptr, 10);
    else {
      std::cerr << "fuzz_trace: unknown argument " << a << "\n";
      return 2;
    }
  }
  std::vector<std::string> corpus;
  for (const auto& e : fs::directory_iterator(corpus_dir)) {
    if (e.path().extension() != ".trace") continue;
    std::ifstream in(e.path(), std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    corpus.push_back(ss.str());
  }
  if (corpus.empty()) {
    std::cerr << "fuzz_trace: no .trace files in " << corpus_dir << "\n";
    return 2;
  }
  std::sort(corpus.begin(), corpus.end());  // directory order is not deterministic

  trace::LoadOptions lo;
  lo.max_pixels = 1 << 14;   // keep every framebuffer and image small
  lo.file_root = corpus_dir;  // includes and images only from the corpus
  trace::RunOptions ro;       // no out_dir: nothing is written
  ro.explain = true;
  ro.dump_each_pass = true;
  ro.probe = std::make_pair(0, 0);
  const std::string name = (fs::path(corpus_dir) / "fuzz.trace").string();

  Rng rng{seed};
  const auto t0 = std::chrono::steady_clock::now();
  long long done = 0, loaded = 0, passes = 0;
  for (; done < iterations; ++done) {
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > seconds) break;
    const std::string input = mutate(rng, corpus);
    try {
      const trace::Program p = trace::load_trace_text(input, name, lo);
      ++loaded;
      std::ostringstream out;
      const trace::RunResult r = trace::run_program(p, ro, out);
      passes += r.passes;
    } catch (const trace::TraceError&) {
      // expected for most mutants
    } catch (const std::exception& e) {
      std::ofstream("fuzz-finding.trace", std::ios::binary) << input;
      std::cerr << "fuzz_trace: iteration " << done << " (seed " << seed << "): unexpected exception: " << e.what()
                << "\ninput written to fuzz-finding.trace\n";
      return 1;
    }
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("fuzz_trace: %lld iterations in %.1f s (seed %llu): %lld loaded, %lld passes run, no findings\n", done,
              secs, static_cast<unsigned long long>(seed), loaded, passes);
  return 0;
}

// Fragment operations on listed pixels (run_fragment_plan_pixels), the terrain's
// path: nanoseconds per fragment of the paper's pass states on a W x H window
// (default 640 x 480), fragments listed as triangle groups list them (strips of
// triangles 8 pixels wide, each triangle's rows in turn, groups of 1024). The
// depths are the paper's: the buffer cleared to the far plane, every pass the
// same geometry, so the first pass stores each fragment's depth and the later
// ones pass LEQUAL on equal depths. Minimum over --repeat runs of 4 passes.
//
//   bench_fragment_ops [--size WxH] [--repeat N] [--out DIR]
//
// Prints a table and writes fragment_ops.csv into DIR (default docs/results/).
// Never fails on a number; the hash line lets two builds be compared for the
// same buffers (same --size and --repeat).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "pipeline/fragment/fragment_plan.h"
#include "sim/hash.h"

using namespace ffsim;

namespace {

struct Case {
  const char* name;
  const char* pass;  // where the paper uses it
  FragmentOpsState state;
};

std::vector<Case> cases() {
  FragmentOpsState base;
  base.depth = {true, gl::LEQUAL};
  std::vector<Case> c;
  FragmentOpsState s = base;
  s.color_mask = {false, false, false, false};
  c.push_back({"depth test only", "(reference)", s});
  s = base;
  s.color_mask = {false, false, false, true};
  c.push_back({"alpha written, no blend", "shadow sum (combiners)", s});
  s.blend = {true, gl::DST_ALPHA, gl::ONE, gl::FUNC_ADD, {}};
  c.push_back({"alpha, (DST_ALPHA, ONE)", "penumbra doubling", s});
  s = base;
  s.color_mask = {true, true, true, false};
  c.push_back({"RGB written, no blend", "bump map (DOT3)", s});
  s = base;
  s.blend = {true, gl::DST_ALPHA, gl::DST_ALPHA, gl::FUNC_ADD, {}};
  c.push_back({"RGBA, (DST_ALPHA, DST_ALPHA)", "final modulation", s});
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  int W = 640, H = 480, repeat = 30;
  std::string out_dir = std::string(FFSIM_SOURCE_DIR) + "/docs/results";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--size" && i + 1 < argc && std::sscanf(argv[i + 1], "%dx%d", &W, &H) == 2 && W >= 64 && H >= 60 &&
        W <= 8192 && H <= 8192) {
      ++i;
    } else if (a == "--repeat" && i + 1 < argc && (repeat = std::atoi(argv[i + 1])) >= 1 && repeat <= 1000) {
      ++i;
    } else if (a == "--out" && i + 1 < argc) {
      out_dir = argv[++i];
    } else {
      std::fprintf(stderr, "usage: bench_fragment_ops [--size WxH (64x60 .. 8192x8192)] [--repeat 1..1000] [--out DIR]\n");
      return 2;
    }
  }
  const auto npix = static_cast<std::size_t>(W) * static_cast<std::size_t>(H);
  // Strips of triangles over the middle of the window, as the terrain covers it.
  std::vector<std::uint32_t> pixel;
  const int band = std::max(2, H / 30), tw = 8;
  for (int y0 = H / 5; y0 + band <= H * 4 / 5; y0 += band)
    for (int x0 = W / 6; x0 + tw <= W * 5 / 6; x0 += tw)
      for (int y = y0; y < y0 + band; ++y)
        for (int x = x0; x < x0 + tw; ++x) pixel.push_back(static_cast<std::uint32_t>(y * W + x));
  const int n = static_cast<int>(pixel.size());
  std::mt19937 rng(1);
  std::vector<std::uint16_t> in(4 * static_cast<std::size_t>(n));
  for (auto& c : in) c = static_cast<std::uint16_t>(rng() % 256);
  std::vector<std::uint32_t> z(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) z[static_cast<std::size_t>(i)] = 1000 + pixel[static_cast<std::size_t>(i)] % 5000;

  FragmentTarget t;
  t.width = W;
  t.height = H;
  std::filesystem::create_directories(out_dir);
  std::ofstream csv(out_dir + "/fragment_ops.csv");
  csv << "state,paper_pass,width,height,fragments_per_pass,ns_per_fragment\n";
  std::printf("run_fragment_plan_pixels, %dx%d, %d fragments per pass, min of %d x 4 passes\n\n", W, H, n, repeat);
  std::printf("| state | paper's pass | ns per fragment |\n| --- | --- | --- |\n");
  Fnv1a64 hash;  // sim/hash.h
  for (const Case& c : cases()) {
    std::vector<std::uint16_t> codes(4 * npix);
    for (auto& v : codes) v = static_cast<std::uint16_t>(rng() % 256);
    std::vector<std::uint32_t> depth(npix, 0xFFFFFFu);  // cleared to the far plane
    FragmentBuffers b;
    b.codes = codes.data();
    b.depth = depth.data();
    const FragmentPlan plan = build_fragment_plan(fragment_plan_key(c.state, t));
    const FragmentConstants k = fragment_constants(c.state, t);
    double best = 1e30;
    for (int r = 0; r < repeat; ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      for (int pass = 0; pass < 4; ++pass)
        for (int g = 0; g < n; g += 1024)
          run_fragment_plan_pixels(plan, k, in.data() + 4 * static_cast<std::size_t>(g), z.data() + g, pixel.data() + g,
                                   std::min(1024, n - g), b);
      best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    const double ns = best * 1e9 / (4.0 * n);
    std::printf("| %s | %s | %.2f |\n", c.name, c.pass, ns);
    csv << '"' << c.name << "\",\"" << c.pass << "\"," << W << ',' << H << ',' << n << ',' << ns << '\n';
    hash.bytes(codes.data(), codes.size() * sizeof codes[0]);
    hash.bytes(depth.data(), depth.size() * sizeof depth[0]);
  }
  std::printf("\nbuffers hash %016llx (compare builds at the same --size and --repeat)\nwrote %s/fragment_ops.csv\n",
              static_cast<unsigned long long>(hash.state), out_dir.c_str());
  return 0;
}

// Golden hashes of every paper trace (traces/*.trace) under the geforce256 profile,
// both scenes, at small sizes. On a mismatch the run's dumps and final buffers are
// written to <temp>/ffsim-paper-golden/<trace>-scene<N>/ so they can be looked at.
//
// The hashes were produced by this build (branch `paper`, with the bindings and the
// combiners' draw path of main) and are trusted because the same traces were
// reviewed as images at the report's sizes (ffsim paper-report, out/report.md):
// the polygon's final colour (64^2 and magnified 4x) shows the grid of shaded bumps
// with black cast shadows toward -x/-y for the light from +x/+y, the hard variants'
// stencil views the same shadow shapes, the antialiased factor images dark in the
// shadows and grey (2d, not 1) on the lit ground, the unsquared variant's factor the
// bright lines along the sign changes of T1^r/T2^r that the pre-squared one lacks,
// and the terrain's colour a shaded perspective grid with shadowed slopes over a
// black background. These 16^2 runs are the same traces at a smaller size.
#include <doctest/doctest.h>

#include <filesystem>
#include <sstream>

#include "sim/image_io.h"
#include "sim/trace/executor.h"
#include "sim/trace/trace.h"

using namespace ffsim;
using namespace ffsim::trace;
namespace fs = std::filesystem;

namespace {
struct Golden {
  std::string trace;
  int scene;
  std::string color, alpha, stencil;
};

const std::vector<Golden> kGolden = {
    {"bump-only.trace", 0, "129b463d02692aa8", "3127c84fa1adf359", "e70255f0f036a037"},
    {"bump-only.trace", 1, "2c05bfede4920046", "48204d0f844a2925", "c76bc6bcb9b2506b"},
    {"kautz-geforce-aa-unsquared.trace", 0, "8c65088adcad1a48", "be8ecbb129f97eb5", "e70255f0f036a037"},
    {"kautz-geforce-aa-unsquared.trace", 1, "dd4931305fe0db16", "76ab13bda28294c6", "c76bc6bcb9b2506b"},
    {"kautz-geforce-aa.trace", 0, "c8c17b1325ceee23", "98f27d0666cb618b", "e70255f0f036a037"},
    {"kautz-geforce-aa.trace", 1, "055041419a8ac830", "772d5e064fa52b0c", "c76bc6bcb9b2506b"},
    {"kautz-geforce-hard.trace", 0, "a706b59c966b5386", "33b22d91ea53dd28", "acfb8e4a897f8e48"},
    {"kautz-geforce-hard.trace", 1, "8eb7f998e436f63c", "ef3e1d74d54d2969", "d29406814a2c12c7"},
    {"kautz-imaging-aa.trace", 0, "2061b2dbdd82d6a2", "a71578df9abb4afd", "e70255f0f036a037"},
    {"kautz-imaging-aa.trace", 1, "4ed3ec46ab639a4d", "aa158ae87d4986f9", "c76bc6bcb9b2506b"},
    {"kautz-imaging-hard.trace", 0, "5f6c16d8d175ac48", "e921effe559ccc68", "acfb8e4a897f8e48"},
    {"kautz-imaging-hard.trace", 1, "53d9e3a1b00075bb", "a95e2ab37d27103e", "d29406814a2c12c7"},
    {"kautz-reference.trace", 0, "409e0449a238e6e9", "4c3a412596941c59", "e70255f0f036a037"},
    {"kautz-reference.trace", 1, "7490504b28fddd3d", "204348f3f850eb71", "c76bc6bcb9b2506b"},
    // Max's horizon map (issue 9), 16 azimuths; reviewed as stencil views against
    // reference.png at 64^2 and by its disagreement in ffsim bench (docs/bench.md).
    // At this size the terrain has no shadow under the default light (empty stencil).
    {"max-horizon.trace", 0, "b091eb2129f6bfcf", "ec7ea40b87a11278", "62e22cee357ae03e"},
    {"max-horizon.trace", 1, "57241ce5af69412c", "fa95b5f644db8fe1", "c76bc6bcb9b2506b"}
};

std::string final_hash(const RunResult& r, const std::string& buffer) {
  for (const auto& [b, h] : r.final_hashes)
    if (b == buffer) return h;
  return "";
}
}  // namespace

TEST_CASE("paper golden: every paper trace's final buffers under geforce256") {
  const fs::path traces = fs::path(FFSIM_SOURCE_DIR) / "traces";
  // Every top-level trace in traces/ is in the table, for both scenes.
  long long listed = 0;
  for (const auto& e : fs::directory_iterator(traces))
    if (e.is_regular_file() && e.path().extension() == ".trace") {
      int scenes = 0;
      for (const auto& g : kGolden) scenes += g.trace == e.path().filename().string();
      CHECK_MESSAGE(scenes == 2, e.path().filename().string() << " needs golden hashes for scenes 0 and 1");
      ++listed;
    }
  CHECK(listed >= 7);
  for (const auto& g : kGolden) {
    LoadOptions lo;
    lo.profile = "geforce256";
    lo.sets = {{"scene", std::to_string(g.scene)}, {"res", "16"}, {"rays", "36"}, {"tw", "64"}, {"th", "36"}};
    const Program p = load_trace_file((traces / g.trace).string(), lo);
    RunOptions ro;
    ro.keep_images = true;
    std::ostringstream out;
    const RunResult r = run_program(p, ro, out);
    REQUIRE(r.ok);
    CHECK(r.gl_errors.empty());
    const std::string c = final_hash(r, "color"), a = final_hash(r, "alpha"), s = final_hash(r, "stencil");
    INFO(g.trace << " scene " << g.scene << ": color " << c << " alpha " << a << " stencil " << s);
    const bool same = c == g.color && a == g.alpha && s == g.stencil;
    CHECK(same);
    if (!same) {
      const fs::path dir = fs::temp_directory_path() / "ffsim-paper-golden" /
                           (g.trace.substr(0, g.trace.size() - 6) + "-scene" + std::to_string(g.scene));
      fs::create_directories(dir);
      for (const auto& [name, im] : r.images)
        write_image((dir / (name.find('.') == std::string::npos ? name + ".png" : name)).string(), im);
      MESSAGE("images written to " << dir.string());
    }
  }
}

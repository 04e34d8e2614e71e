// Issue 9, numerical stability of the paper's traces (sim level):
// - identical hashes at RunOptions.threads 1, 2, 3 and on a repeated run, for
//   every shadow variant, under a fixed and a float profile, with an ordinary and
//   a grazing light;
// - float framebuffers (ideal, float32) hold only finite values in [0, 1];
// - a light on the unit circle whose lx^2 + ly^2 rounds above 1 runs with lz = 0
//   (elevation exactly 0), while a light with |l| > 1 is refused with a clear error;
// - the error against `ideal` does not grow from 8 (geforce256) to 10 (rgba10) to
//   12 bits (rgba12), except where docs/numerics.md §12.5 explains it.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "sim/stress/traces.h"

using namespace ffsim::stress;

namespace {

const std::string kTraces = std::string(FFSIM_SOURCE_DIR) + "/traces";

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

Sets small(double lx, double ly) { return {{"res", "16"}, {"rays", "16"}, {"lx", num(lx)}, {"ly", num(ly)}}; }

}  // namespace

TEST_CASE("stress traces: identical results across thread counts 1, 2, 3 and repeated runs, finite float framebuffers") {
  // Elevation 1 degree at azimuth 0.5 rad: a grazing light the traces accept.
  const double ge = 1.0 * 3.14159265358979323846 / 180;
  const std::vector<Sets> lights = {small(0.7, 0.4), small(std::cos(ge) * std::cos(0.5), std::cos(ge) * std::sin(0.5))};
#ifdef FFSIM_SANITIZE
  const std::vector<std::string> stems = {"kautz-geforce-aa", "kautz-imaging-hard"};
  const std::vector<std::string> profiles = {"geforce256", "ideal"};
#else
  const std::vector<std::string> stems = {"kautz-geforce-aa", "kautz-imaging-aa", "kautz-geforce-hard", "kautz-imaging-hard"};
  const std::vector<std::string> profiles = {"geforce256", "float32", "ideal"};
#endif
  int runs = 0;
  for (const auto& stem : stems)
    for (const auto& prof : profiles)
      for (std::size_t li = 0; li < lights.size(); ++li) {
        if (li == 1 && prof == "float32") continue;
        CAPTURE(stem);
        CAPTURE(prof);
        CAPTURE(li);
        const TraceRun r1 = run_paper_trace(kTraces, stem, lights[li], prof, 1);
        CAPTURE(r1.error);
        REQUIRE(r1.ok);
        const std::string h = all_hashes(r1.r);
        CHECK_FALSE(r1.r.hashes.empty());
        for (int threads : {2, 3, 1}) {
          CAPTURE(threads);
          const TraceRun rt = run_paper_trace(kTraces, stem, lights[li], prof, threads);
          REQUIRE(rt.ok);
          CHECK(all_hashes(rt.r) == h);
        }
        std::string first;
        CHECK(bad_image_values(r1.r, &first) == 0);
        CAPTURE(first);
        ++runs;
      }
  MESSAGE(runs, " (trace, profile, light) combinations, each at threads 1, 2, 3 and repeated: identical hashes");
}

TEST_CASE("stress traces: a light on the horizon runs with lz = 0, a light outside the unit disc is refused") {
  // 0.6^2 + 0.8^2 rounds to 1 + 2^-52: scene.trace treats the radicand of
  // lz = sqrt(1 - lx^2 - ly^2) within 1e-12 below 0 as 0 (elevation exactly 0).
  const TraceRun r = run_paper_trace(kTraces, "kautz-geforce-aa", small(0.6, 0.8), "", 1);
  CAPTURE(r.error);
  CHECK(r.ok);
  // |l| = 0.9 sqrt 2 > 1: no such light; the load names the square root and the file.
  const TraceRun bad = run_paper_trace(kTraces, "kautz-geforce-aa", small(0.9, 0.9), "", 1);
  CHECK_FALSE(bad.ok);
  CAPTURE(bad.error);
  CHECK(bad.error.find("sqrt of a negative number") != std::string::npos);
  CHECK(bad.error.find("scene.trace") != std::string::npos);
}

TEST_CASE("stress traces: error against ideal from 8 to 10 to 12 bits") {
  // Polygon scene, 16^2 maps, a small sweep of lights (azimuths 30 and 200 degrees,
  // elevations 60, 30, 15 degrees). Metric: RMSE of alpha.png (the shadow test d
  // after its clamps) against the same trace under `ideal`, over covered pixels.
#ifdef FFSIM_SANITIZE
  const std::vector<double> elevations = {30};
  const std::vector<double> azimuths = {30};
#else
  const std::vector<double> elevations = {60, 30, 15};
  const std::vector<double> azimuths = {30, 200};
#endif
  const double pi = 3.14159265358979323846;
  std::string table;
  long long checked = 0, nonmonotonic = 0;
  for (const char* stem : {"kautz-geforce-aa", "kautz-imaging-aa"})
    for (double el : elevations)
      for (double az : azimuths) {
        const double r = std::cos(el * pi / 180);
        const Sets sets = small(r * std::cos(az * pi / 180), r * std::sin(az * pi / 180));
        const auto pts = error_sweep(kTraces, stem, sets, {"geforce256", "rgba10", "rgba12"});
        REQUIRE(pts.size() == 3);
        for (const auto& p : pts) {
          CAPTURE(p.error);
          REQUIRE(p.ok);
        }
        char line[400];
        std::snprintf(line, sizeof line,
                      "%s el %g az %g: RMSE vs ideal %.5f / %.5f / %.5f, max %.4f / %.4f / %.4f, verdicts != ideal %lld / "
                      "%lld / %lld, vs reference %lld / %lld / %lld (ideal %lld) of %lld\n",
                      stem, el, az, pts[0].rmse_vs_ideal, pts[1].rmse_vs_ideal, pts[2].rmse_vs_ideal, pts[0].max_abs_vs_ideal,
                      pts[1].max_abs_vs_ideal, pts[2].max_abs_vs_ideal, pts[0].differ_vs_ideal, pts[1].differ_vs_ideal,
                      pts[2].differ_vs_ideal, pts[0].disagree_vs_reference, pts[1].disagree_vs_reference,
                      pts[2].disagree_vs_reference, pts[0].ideal_disagree_vs_reference, pts[0].pixels);
        table += line;
        CAPTURE(line);
        if (std::string(stem) == "kautz-geforce-aa") {
          // Combiner path: every width step shrinks the texture, constant, register and
          // framebuffer grids together (numerics §12.2): the error must not grow.
          CHECK(pts[1].rmse_vs_ideal <= pts[0].rmse_vs_ideal);
          CHECK(pts[2].rmse_vs_ideal <= pts[1].rmse_vs_ideal);
          CHECK(pts[1].differ_vs_ideal <= pts[0].differ_vs_ideal);
          CHECK(pts[2].differ_vs_ideal <= pts[1].differ_vs_ideal);
          // The lit/shadow disagreement with the exact reference is NOT required to
          // fall: it is dominated by the ellipse approximation (ideal's own count), and
          // an 8-bit error can flip a verdict the ellipse got wrong (numerics §12.5).
        } else {
          // Imaging path, the explained exception (numerics §12.5): the three alpha
          // terms are stored in GL_ALPHA8 textures and squared through a 256-entry
          // table in every fixed profile; the profiles differ only in the conversion
          // of those 8-bit texels to the N-bit framebuffer (half an N-bit step each,
          // three terms, 1-Lipschitz blends and clamps) and of the N-bit alpha to the
          // 16-bit dump. So per pixel |alpha_N - alpha_8| <= 1.5/(2^N-1) + 0.5/65535,
          // and the RMSE may move either way by at most that much.
          for (int k = 1; k <= 2; ++k) {
            const double bound = 1.5 / ((1 << (8 + 2 * k)) - 1) + 0.5 / 65535 + 1e-9;
            double worst = 0;
            for (std::size_t i = 0; i < pts[0].alpha.size(); ++i)
              if (pts[0].covered[i]) worst = std::max(worst, std::fabs(pts[k].alpha[i] - pts[0].alpha[i]));
            CAPTURE(k);
            CHECK(worst <= bound);
            CHECK(std::fabs(pts[k].rmse_vs_ideal - pts[0].rmse_vs_ideal) <= bound);
            nonmonotonic += pts[k].rmse_vs_ideal > pts[k - 1].rmse_vs_ideal;
          }
        }
        ++checked;
      }
  MESSAGE(table, "imaging path: ", nonmonotonic, " non-monotonic steps (explained, numerics §12.5)");
  CHECK(checked > 0);
}

// The main job's report (ffsim paper-report, sim/paper.cpp) at the quick sizes:
// every variant of both scenes runs, report.md and report.json are written, and
// the classification counts are consistent; plus the mask/RMSE helpers.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "sim/paper.h"

using namespace ffsim;
namespace fs = std::filesystem;

TEST_CASE("paper report: compare_masks and rmse count only covered pixels") {
  const std::vector<bool> lit = {true, true, false, false, true};
  const std::vector<bool> ref = {true, false, true, false, false};
  const std::vector<bool> cov = {true, true, true, true, false};
  const paper::ShadowStats s = paper::compare_masks(lit, ref, cov);
  CHECK(s.pixels == 4);
  CHECK(s.false_lit == 1);
  CHECK(s.false_shadow == 1);
  CHECK(s.disagreement() == 0.5);
  CHECK(paper::rmse({0, 1, 0.5}, {0, 0, 0.5}, {true, true, false}) == doctest::Approx(std::sqrt(0.5)));
}

TEST_CASE("paper report: the quick report runs every variant of both scenes") {
  const fs::path out = fs::temp_directory_path() / (std::string("ffsim-test-paper-report-") + std::to_string(::getpid()));
  fs::remove_all(out);
  paper::ReportOptions o;
  o.traces_dir = (fs::path(FFSIM_SOURCE_DIR) / "traces").string();
  o.out_dir = out.string();
  o.quick = true;
  std::ostringstream log, err;
  const int code = paper::run_report(o, log, err);
  INFO(log.str() << err.str());
  CHECK(code == 0);
  std::ifstream j(out / "report.json");
  std::stringstream js;
  js << j.rdbuf();
  const std::string json = js.str();
  for (const char* v : {"bump-only", "kautz-imaging-hard", "kautz-imaging-aa", "kautz-geforce-aa", "kautz-geforce-aa-unsquared",
                        "kautz-geforce-hard", "kautz-geforce-aa-l2printed", "float64-ellipse-test"})
    CHECK_MESSAGE(json.find(std::string("\"variant\": \"") + v + "\"") != std::string::npos, v);
  CHECK(json.find("\"ok\": false") == std::string::npos);
  for (const char* scene : {"polygon", "terrain"}) {
    CHECK(fs::exists(out / scene / "kautz-imaging-hard" / "stencil-view.png"));
    CHECK(fs::exists(out / scene / "kautz-geforce-aa" / "factor.png"));
    CHECK(fs::exists(out / scene / "bump-only" / "color-view.png"));
  }
  CHECK(fs::exists(out / "report.md"));
  fs::remove_all(out);
}

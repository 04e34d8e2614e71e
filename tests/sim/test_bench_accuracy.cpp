// `ffsim bench` (issue 9, sim/bench/accuracy*.cpp): the Pareto front, the SVG
// writer, the light sweep, option parsing, and a tiny configuration whose numbers
// can be derived independently (reference against itself, the float64 ellipse test
// computed as ffsim paper-report does, CSV rows, well-formed plots).
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <unistd.h>

#include "bumpshadow/generators.h"
#include "bumpshadow/horizon.h"
#include "pipeline/number/unorm.h"
#include "sim/bench/accuracy_config.h"
#include "sim/bench/accuracy_output.h"
#include "sim/bench/accuracy_run.h"
#include "sim/bench/pareto.h"
#include "sim/bench/svg_plot.h"
#include "sim/paper.h"
#include "sim/paper_run.h"
#include "sim/trace/trace.h"

using namespace ffsim;
using namespace ffsim::bench;
namespace fs = std::filesystem;

namespace {

// A minimal XML well-formedness check: the declaration, then balanced elements
// with matching names; attribute values quoted; no raw '<' or '&' in text.
bool well_formed(const std::string& s, std::string& why) {
  std::vector<std::string> stack;
  std::size_t i = 0;
  if (s.rfind("<?xml", 0) != 0) return why = "no XML declaration", false;
  i = s.find("?>") + 2;
  bool root_seen = false;
  while (i < s.size()) {
    if (s[i] == '<') {
      const std::size_t end = s.find('>', i);
      if (end == std::string::npos) return why = "unterminated tag", false;
      std::string tag = s.substr(i + 1, end - i - 1);
      // Quotes balanced inside the tag.
      if (std::count(tag.begin(), tag.end(), '"') % 2) return why = "unbalanced quotes in <" + tag + ">", false;
      if (tag[0] == '/') {
        if (stack.empty() || stack.back() != tag.substr(1)) return why = "mismatched </" + tag.substr(1) + ">", false;
        stack.pop_back();
      } else {
        const bool self = tag.back() == '/';
        const std::string name = tag.substr(0, tag.find_first_of(" /"));
        if (stack.empty() && root_seen) return why = "two root elements", false;
        root_seen = true;
        if (!self) stack.push_back(name);
      }
      i = end + 1;
    } else {
      if (s[i] == '&') {
        const std::size_t semi = s.find(';', i);
        if (semi == std::string::npos || semi - i > 6) return why = "raw &", false;
      }
      if (s[i] == '>') return why = "raw > in text", false;
      ++i;
    }
  }
  if (!stack.empty()) return why = "unclosed <" + stack.back() + ">", false;
  return root_seen || (why = "no root", false);
}

}  // namespace

TEST_CASE("bench accuracy: pareto_front of a hand-made point set") {
  //            0          1          2          3          4          5          6
  const std::vector<std::pair<double, double>> p = {{1, 5}, {2, 3}, {2, 4}, {3, 3}, {4, 1}, {5, 2}, {4, 1}};
  // (2,4) is dominated by (2,3); (3,3) by (2,3); (5,2) by (4,1); the duplicate (4,1) is kept.
  CHECK(pareto_front(p) == std::vector<std::size_t>{0, 1, 4, 6});
  CHECK(pareto_front({}).empty());
  CHECK(pareto_front({{1, std::nan("")}, {2, 2}}) == std::vector<std::size_t>{1});
  CHECK(pareto_front({{3, 0}, {1, 9}, {2, 9}}) == std::vector<std::size_t>{1, 0});
}

TEST_CASE("bench accuracy: the SVG writer gives a well-formed document with escaped labels") {
  Plot p;
  p.title = "a <title> & \"quotes\"";
  p.x_label = "ms";
  p.y_label = "%";
  p.x_log = true;
  p.series.push_back({"s<1>", {{1, 2, "a&b"}, {10, 1, "c"}, {-1, 3, "dropped on the log axis"}, {std::nan(""), 1, "nan"}}, ""});
  p.series.push_back({"s2", {{100, 0, "zero"}}, "#123456"});
  p.lines.push_back({"front", {{1, 2}, {10, 1}}, "#d62728"});
  const std::string svg = render_svg(p);
  std::string why;
  CHECK_MESSAGE(well_formed(svg, why), why);
  CHECK(svg.find("a &lt;title&gt; &amp; &quot;quotes&quot;") != std::string::npos);
  CHECK(svg.find("<polyline") != std::string::npos);
  CHECK(svg.find("2 point(s) not shown") != std::string::npos);
  // An empty plot is well-formed too.
  CHECK(well_formed(render_svg(Plot{}), why));
  CHECK(xml_escape("<&>\"'") == "&lt;&amp;&gt;&quot;&apos;");
}

TEST_CASE("bench accuracy: the light sweep and its subsets") {
  const auto all = light_sweep();
  REQUIRE(all.size() == 48);
  CHECK(all[0].lx() == doctest::Approx(0.5));
  CHECK(all[13].azimuth_deg == 30);
  CHECK(all[13].elevation_deg == 30);
  CHECK(all[13].ly() == doctest::Approx(std::cos(M_PI / 6) * 0.5));
  const auto sub = light_subset(48);
  std::set<std::string> names;
  for (const auto& l : sub) names.insert(l.label());
  CHECK(names.size() == 48);  // 13 is prime to 48: the order visits every light
  CHECK(light_subset(3)[2].label() == "a60e15");
}

TEST_CASE("bench accuracy: options") {
  std::string e;
  auto c = parse_accuracy_args({"--quick"}, e);
  REQUIRE(c);
  CHECK(c->sizes == std::vector<int>{256});
  CHECK(c->lights.size() == 3);
  CHECK(c->name == "accuracy-quick");
  c = parse_accuracy_args({}, e);
  REQUIRE(c);
  CHECK(c->variants.size() == 10);
  CHECK(c->profiles.size() == 5);
  CHECK(c->lights.size() == 48);
  c = parse_accuracy_args({"--sizes", "256,512", "--lights", "all", "--filters", "nearest", "--variants", "reference", "--repeat", "2"}, e);
  REQUIRE(c);
  CHECK(c->sizes.size() == 2);
  CHECK(c->filters == std::vector<int>{0});
  for (const std::vector<std::string>& bad :
       {std::vector<std::string>{"--bogus"}, {"--sizes"}, {"--sizes", "x"}, {"--lights", "0"}, {"--filters", "cubic"},
        {"--variants", "nope"}, {"--sizes", "100"}, {"--repeat", "-1"}, {"--scenes", "moon"}}) {
    e.clear();
    CHECK_FALSE(parse_accuracy_args(bad, e));
    CHECK(!e.empty());
    CHECK(e.find('\n') == std::string::npos);
  }
}

TEST_CASE("bench accuracy: the horizon generator encodes Max's elevation in 8 bits, linear in angle") {
  trace::LoadOptions lo;
  const trace::Program p = trace::load_trace_text(
      "ffsim-trace 1\ngenerate H horizon field=bumps w=16 azimuths=8 index=3 cache=none\n", "t.trace", lo);
  REQUIRE(p.resources.size() == 1);
  const Image& im = *p.resources[0].image;
  REQUIRE(im.width == 16);
  const auto hm = bumpshadow::compute_horizon_map(bumpshadow::generate("bumps", {{"w", "16"}}), 8);
  int shaded = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const std::uint32_t want = unorm_from_double(std::min(1.0, hm.at(x, y, 3) / (M_PI / 2)), 8);
      CHECK(im.u8[im.index(x, y, 0)] == want);
      shaded += want > 0;
    }
  CHECK(shaded > 0);
}

TEST_CASE("bench accuracy: a tiny configuration runs and its numbers can be derived") {
  const fs::path out = fs::temp_directory_path() / (std::string("ffsim-test-bench-") + std::to_string(::getpid()));
  fs::remove_all(out);
  AccuracyConfig c;
  c.traces_dir = (fs::path(FFSIM_SOURCE_DIR) / "traces").string();
  c.out_dir = out.string();
  c.name = "tiny";
#ifdef FFSIM_SANITIZE
  // Under ASan a trace load (the terrain mesh is parsed with every draw.trace) takes
  // seconds on the shared machine: the sanitizer build runs the reference row only.
  const bool full = false;
#else
  const bool full = true;
#endif
  for (const auto& v : all_variants())
    if (v.name == "reference" ||
        (full && (v.name == "kautz-geforce-hard" || v.name == "kautz-geforce-aa" || v.name == "max-horizon-8" || v.name == "float64-ellipse")))
      c.variants.push_back(v);
  c.profiles = {"geforce256"};
  c.filters = {1};
  c.sizes = {32};
  c.scenes = {{0, "polygon"}};  // the terrain costs ~10x more under ASan; the quick bench runs it
  c.lights = light_subset(1);
  c.repeat = 1;
  c.map_res = 16;
  c.rays = 36;
  std::ostringstream progress;
  const AccuracyResult r = run_accuracy_config(c, progress);
  INFO(progress.str());
  CHECK(r.all_ok);
  // 3 hardware variants x (ideal + geforce256) x 1 filter + 2 CPU rows.
  REQUIRE(r.rows.size() == (full ? 3 * 2 + 2 : 1));
  for (const auto& row : r.rows) {
    INFO(row.scene << " " << row.variant.name << " " << row.profile << " " << row.acc.error);
    CHECK(row.acc.ok);
    CHECK(row.acc.lights == 1);
    CHECK(row.acc.seconds.size() == 1);
    CHECK(row.acc.sum_dis >= 0);
    CHECK(row.acc.max_dis <= 1);
    CHECK(row.acc.max_shaded <= 1);
    if (row.variant.kind == VariantKind::Reference) {
      CHECK(row.acc.sum_dis == 0);
      CHECK(row.acc.sum_shaded == 0);
      CHECK(row.acc.worst == 0);
    }
    if (row.profile == "geforce256") CHECK(row.acc.ideal_lights == 1);
    if (row.profile == "ideal") CHECK(row.acc.ideal_lights == 0);
  }
  // The float64 ellipse test's disagreement, computed the way ffsim paper-report does.
  for (const SceneSpec& sc : full ? c.scenes : std::vector<SceneSpec>{}) {
    double sum = 0;
    for (const Light& l : c.lights) {
      char lx[40], ly[40];
      std::snprintf(lx, sizeof lx, "%.17g", l.lx());
      std::snprintf(ly, sizeof ly, "%.17g", l.ly());
      std::vector<std::pair<std::string, std::string>> sets = {{"scene", std::to_string(sc.scene)}, {"res", "16"}, {"rays", "36"}};
      if (sc.scene == 0) sets.push_back({"zoom", "2"});
      else sets.push_back({"tw", "32"}), sets.push_back({"th", "32"});
      sets.push_back({"lx", lx});
      sets.push_back({"ly", ly});
      sets.push_back({"filter", "1"});
      const paper::Run ref = paper::run_trace(c.traces_dir + "/kautz-reference.trace", sets, "", 1, "ideal");
      REQUIRE(ref.ok);
      const auto cov = paper::threshold(paper::channel_values(*paper::image_of(ref, "coverage.png")), 0.5);
      const auto lit = paper::threshold(paper::channel_values(*paper::image_of(ref, "reference.png")), 0.5);
      const auto ell = paper::threshold(paper::channel_values(*paper::image_of(ref, "ellipse.png")), 0.5);
      sum += paper::compare_masks(ell, lit, cov).disagreement();
    }
    for (const auto& row : r.rows)
      if (row.scene == sc.name && row.variant.kind == VariantKind::Ellipse) CHECK(row.acc.sum_dis == doctest::Approx(sum).epsilon(1e-12));
  }
  // Files: CSV with a header and one line per row, Markdown, one well-formed plot per (scene, size).
  REQUIRE(write_accuracy_files(c, r, std::cerr));
  std::ifstream csv(out / "tiny.csv");
  std::string line;
  int lines = 0;
  std::getline(csv, line);
  CHECK(line.rfind("scene,size,variant,kind,profile,filter,", 0) == 0);
  const auto columns = std::count(line.begin(), line.end(), ',');
  while (std::getline(csv, line)) {
    ++lines;
    CHECK(std::count(line.begin(), line.end(), ',') == columns);
  }
  CHECK(lines == static_cast<int>(r.rows.size()));
  CHECK(fs::exists(out / "tiny.md"));
  for (const char* scene : {"polygon"}) {
    std::ifstream f(out / plot_file_name("tiny", scene, 32));
    std::stringstream ss;
    ss << f.rdbuf();
    std::string why;
    CHECK_MESSAGE(well_formed(ss.str(), why), why);
    CHECK(ss.str().find("Pareto front") != std::string::npos);
  }
  int front = 0;
  for (const auto& row : r.rows) front += row.pareto;
  CHECK(front >= 1);
  fs::remove_all(out);
}

TEST_CASE("bench accuracy: the 8/10/12-bit ladder flags a step that gets worse") {
  // Hand-made rows: variant "a" improves at every step (0.03 -> 0.02 -> 0.01 disagreement,
  // 0.3 -> 0.2 -> 0.1 RMSE), variant "b" gets worse from 10 to 12 bits in the RMSE.
  ffsim::bench::AccuracyResult r;
  auto add = [&](const std::string& v, const std::string& prof, double dis, double rmse) {
    ffsim::bench::AccuracyRow row;
    row.scene = "polygon";
    row.size = 256;
    row.variant.name = v;
    row.profile = prof;
    row.filter = 1;
    row.acc.lights = 1;
    row.acc.ideal_lights = 1;
    row.acc.sum_ideal_dis = dis;
    row.acc.sum_ideal_shaded = rmse;
    r.rows.push_back(row);
  };
  add("a", "geforce256", 0.03, 0.3);
  add("a", "rgba10", 0.02, 0.2);
  add("a", "rgba12", 0.01, 0.1);
  add("b", "geforce256", 0.03, 0.3);
  add("b", "rgba10", 0.02, 0.2);
  add("b", "rgba12", 0.02, 0.25);
  add("c", "geforce256", 0.03, 0.3);  // no rgba10/rgba12: not in the table
  const std::string md = ffsim::bench::precision_ladder(r);
  CAPTURE(md);
  CHECK(md.find("1 of 2 (scene, size, variant, filter) rows do not get worse") != std::string::npos);
  CHECK(md.find("| polygon 256 | a | linear | 3.000 / 2.000 / 1.000 % | 0.3000 / 0.2000 / 0.1000 | not worse |") != std::string::npos);
  CHECK(md.find("| polygon 256 | b | linear | 3.000 / 2.000 / 2.000 % | 0.3000 / 0.2000 / 0.2500 | **worse at a step** |") !=
        std::string::npos);
  CHECK(md.find("| polygon 256 | c |") == std::string::npos);
  CHECK(ffsim::bench::precision_ladder(ffsim::bench::AccuracyResult{}).empty());
}

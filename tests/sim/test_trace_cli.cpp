// The trace subcommands of the ffsim program (replay, diff, compare, info), driven
// through cli::run as main() does. Expected numbers are hand-derived in comments.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "cli_test_util.h"
#include "sim/cli/cli.h"
#include "sim/image_io.h"
#include "sim/trace/error.h"

using namespace ffsim;
namespace fs = std::filesystem;
using ffsim::trace::cat;

namespace {
using test::Run;
using test::run;
fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / cat("ffsim-cli-", std::to_string(::getpid()), "-", name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}
const std::string kExamples = std::string(FFSIM_SOURCE_DIR) + "/traces/examples/";
bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }
Image grey(std::vector<std::uint8_t> v) {
  Image im = Image::make(static_cast<int>(v.size()), 1, 1, SampleType::U8);
  im.u8 = std::move(v);
  return im;
}
}  // namespace

TEST_CASE("cli replay: runs a trace, writes its dumps and prints hashes") {
  const fs::path d = temp_dir("replay");
  const Run r = run({"replay", kExamples + "masks.trace", "--out", d.string()});
  CHECK(r.code == 0);
  CHECK(r.err.empty());
  CHECK(r.out.find(kExamples + "masks.trace: profile geforce256, 32x32, 3 passes, 22 steps, ") == 0);
  CHECK(contains(r.out, cat("\nhash alpha ")));
  CHECK(contains(r.out, cat("  ", kExamples, "masks.trace:31:1\n")));
  CHECK(contains(r.out, cat("wrote ", (d / "masks-alpha.png").string(), "\n")));
  CHECK(fs::exists(d / "masks-alpha.png"));
  CHECK(fs::exists(d / "masks-stencil.png"));
  fs::remove_all(d);
}

TEST_CASE("cli replay: --json, --threads and --dump-each-pass") {
  const fs::path d = temp_dir("json");
  const Run a = run({"replay", kExamples + "clear.trace", "--out", d.string(), "--json", "--threads", "1"});
  const Run b = run({"replay", kExamples + "clear.trace", "--out", d.string(), "--json", "--threads", "2", "--dump-each-pass"});
  CHECK(a.code == 0);
  CHECK(b.code == 0);
  CHECK(a.out.find(cat("{\"trace\": \"", kExamples, "clear.trace\", \"ok\": true, \"error\": null, \"profile\": \"geforce256\", "
                       "\"width\": 64, \"height\": 32, \"threads\": 1, \"passes\": 1, \"steps\": 7, \"seconds\": ")) == 0);
  // The color hash is the one clear.trace expects (derived in tests/sim/test_trace_run.cpp).
  CHECK(contains(a.out, "\"hashes\": [{\"buffer\": \"color\", \"hash\": \"75f697c3e645af00\""));
  // The final hashes are the same with 1 and 2 threads.
  const auto finals = [](const std::string& s) {
    const auto f = s.find("\"final\"");
    return s.substr(f, s.find("\"written\"") - f);
  };
  CHECK(finals(a.out).size() > 100);
  CHECK(finals(a.out) == finals(b.out));
  CHECK(fs::exists(d / "passes" / "001-glClear-color.png"));
  CHECK(fs::exists(d / "passes" / "001-glClear-alpha.png"));
  fs::remove_all(d);
}

TEST_CASE("cli replay: trace errors print position, line and caret, exit code 1") {
  const fs::path d = temp_dir("errors");
  const std::string t = (d / "t.trace").string();
  {
    std::ofstream(t) << "ffsim-trace 1\nglClearColor lz 0 0 1\n";
  }
  const Run r = run({"replay", t, "--out", (d / "out").string()});
  CHECK(r.code == 1);
  CHECK(r.out.empty());
  CHECK(r.err == cat(t, ":2:14: unknown parameter `lz`\n  glClearColor lz 0 0 1\n               ^\n"));
  CHECK(!fs::exists(d / "out"));
  const Run j = run({"replay", t, "--json", "--out", (d / "out").string()});
  CHECK(j.out == cat("{\"trace\": \"", t, "\", \"ok\": false, \"error\": \"", t, ":2:14: unknown parameter `lz`\"}\n"));
  const Run s = run({"replay", kExamples + "clear.trace", "--set", "zz=1", "--out", (d / "out").string()});
  CHECK(s.code == 1);
  CHECK(s.err == "--set:1:1: the trace has no parameter `zz`\n  zz=1\n  ^\n");
  const Run m = run({"replay", (d / "missing.trace").string()});
  CHECK(m.code == 1);
  CHECK(m.err == cat("ffsim replay: cannot read `", (d / "missing.trace").string(), "`: no such file\n"));
  fs::remove_all(d);
}

TEST_CASE("cli replay: GL errors, --strict, failed expects") {
  const fs::path d = temp_dir("strict");
  const std::string t = (d / "t.trace").string();
  {
    std::ofstream(t) << "ffsim-trace 1\nframebuffer 4 4\nglClear GL_COLOR_BUFFER_BIT\ndump color c.png\nglPopMatrix\n"
                        "expect pixel 0 0 alpha 1\n";
  }
  const Run a = run({"replay", t, "--out", (d / "a").string()});
  CHECK(a.code == 1);  // the expect fails: alpha is 0 after clearing to (0,0,0,0)
  CHECK(a.err == cat(t, ":5:1: glPopMatrix: GL_STACK_UNDERFLOW: GL_MODELVIEW stack has only one matrix\n", t,
                     ":6:1: expect pixel 0 0 alpha: got 0, expected 1 (tol 0)\n"));
  CHECK(fs::exists(d / "a" / "c.png"));  // dumps are still written when an expect fails
  const Run b = run({"replay", t, "--out", (d / "b").string(), "--strict"});
  CHECK(b.code == 1);
  CHECK(b.err == cat(t, ":5:1: glPopMatrix: GL_STACK_UNDERFLOW: GL_MODELVIEW stack has only one matrix\n",
                     "ffsim replay: stopped at the first GL error (--strict); nothing written\n"));
  CHECK(!fs::exists(d / "b" / "c.png"));
  fs::remove_all(d);
}

TEST_CASE("cli replay: --explain and --probe, usage errors") {
  const fs::path d = temp_dir("probe");
  const Run a = run({"replay", kExamples + "clear.trace", "--out", d.string(), "--explain", "--probe", "3,4"});
  CHECK(a.code == 0);
  CHECK(contains(a.out, cat("pass 1: glClear at ", kExamples, "clear.trace:7:1\n  framebuffer: clear color in (0, 0) 64x32\n")));
  CHECK(contains(a.out, "  probe (3, 4) clear: color codes (0, 0, 0, 0) = (0, 0, 0, 0), stencil 0, depth 0 -> color codes "
                        "(255, 128, 0, 255) = (1, 0.501961, 0, 1), stencil 0, depth 0\n"));
  CHECK(run({"replay"}).code == 2);
  CHECK(run({"replay", "a.trace", "--threads", "0"}).err == "ffsim replay: --threads expects a number from 1 to 256 (see `ffsim replay --help`)\n");
  CHECK(run({"replay", "a.trace", "--probe", "3"}).code == 2);
  CHECK(run({"replay", "a.trace", "--bogus"}).err == "ffsim replay: unknown argument `--bogus` (see `ffsim replay --help`)\n");
  CHECK(run({"replay", kExamples + "clear.trace", "--probe", "64,0"}).err ==
        "ffsim replay: --probe 64,0 is outside the 64x32 framebuffer (see `ffsim replay --help`)\n");
  CHECK(run({"replay", "--help"}).code == 0);
  fs::remove_all(d);
}

TEST_CASE("cli diff: identical, different, heat map, directories, errors") {
  const fs::path d = temp_dir("diff");
  write_image((d / "a.png").string(), grey({0, 100, 50}));
  write_image((d / "b.png").string(), grey({0, 103, 0}));
  write_image((d / "c.png").string(), grey({0, 100, 50}));
  const Run same = run({"diff", (d / "a.png").string(), (d / "c.png").string()});
  CHECK(same.code == 0);
  CHECK(same.out == "a.png: identical\n1 image compared, 0 different\n");
  const Run diff = run({"diff", (d / "a.png").string(), (d / "b.png").string(), "--out", (d / "hm").string()});
  CHECK(diff.code == 1);
  // Pixels 1 and 2 differ by 3 and 50 codes; RMSE = sqrt((3^2 + 50^2) / 3) / 255 = 0.113410,
  // PSNR = 20 log10(1 / RMSE) = 18.91 dB; pixel 2 is lit (50 > 0) in A, in shadow in B.
  CHECK(diff.out == cat("a.png: 2 of 3 pixels differ; max |d| in 8-bit LSB: V 50.00; RMSE 0.113410; PSNR 18.91 dB; "
                        "lit/shadow disagreements 1\nwrote ", (d / "hm" / "diff-a.png").string(), "\n1 image compared, 1 different\n"));
  const Image hm = read_image((d / "hm" / "diff-a.png").string());
  CHECK(hm.channels == 3);
  CHECK(hm.u8[0] == 0);                 // equal pixel: black
  CHECK(hm.u8[hm.index(2, 0, 0)] == 255);  // the largest difference: white
  CHECK(hm.u8[hm.index(2, 0, 2)] == 255);
  CHECK(hm.u8[hm.index(1, 0, 0)] > 0);     // any difference is visible
  const Run json = run({"diff", (d / "a.png").string(), (d / "b.png").string(), "--json"});
  CHECK(contains(json.out, "\"differing_pixels\": 2, \"total_pixels\": 3"));
  CHECK(contains(json.out, "\"lit_shadow_disagreements\": 1"));
  // Directories: files matched by relative path.
  fs::create_directories(d / "A");
  fs::create_directories(d / "B");
  fs::copy_file(d / "a.png", d / "A" / "x.png");
  fs::copy_file(d / "c.png", d / "B" / "x.png");
  fs::copy_file(d / "a.png", d / "A" / "only.png");
  const Run dirs = run({"diff", (d / "A").string(), (d / "B").string()});
  CHECK(dirs.code == 1);
  CHECK(dirs.out == "x.png: identical\nonly.png: only in A\n1 image compared, 1 different\n");
  const Run missing = run({"diff", (d / "a.png").string(), (d / "nonesuch.png").string()});
  CHECK(missing.code == 2);
  CHECK(contains(missing.err, "nonesuch.png"));
  CHECK(run({"diff", (d / "a.png").string()}).code == 2);
  CHECK(run({"diff", (d / "A").string(), (d / "a.png").string()}).code == 2);
  fs::remove_all(d);
}

TEST_CASE("cli compare: one trace under two profiles") {
  // clear.trace clears to (1, 0.5, 0, 1). geforce256 stores green as 128/255, ideal
  // as 0.5: a difference of 1/510 = 0.5 8-bit LSB in every pixel; RMSE over the four
  // channels = (1/510) / 2 = 0.000980, PSNR = 20 log10(1020) = 60.17 dB.
  const Run r = run({"compare", kExamples + "clear.trace", "--profile-b", "ideal"});
  CHECK(r.code == 1);
  const std::string line = "2048 of 2048 pixels differ; max |d| in 8-bit LSB: R 0.00 G 0.50 B 0.00 A 0.00; RMSE 0.000980; PSNR 60.17 dB\n";
  CHECK(r.out == cat("A: ", kExamples, "clear.trace (profile geforce256)\nB: ", kExamples, "clear.trace (profile ideal)\n",
                     "clear-color.png: ", line, "final-alpha: identical\nfinal-color: ", line, "3 images compared, 2 different\n"));
  const Run same = run({"compare", kExamples + "clear.trace", kExamples + "clear.trace"});
  CHECK(same.code == 0);
  const Run json = run({"compare", kExamples + "clear.trace", "--profile-b", "rgba12", "--json"});
  CHECK(json.code == 1);
  CHECK(json.out.find(cat("{\"a\": {\"trace\": \"", kExamples, "clear.trace\", \"profile\": \"geforce256\"}, ")) == 0);
  CHECK(run({"compare"}).code == 2);
  CHECK(run({"compare", kExamples + "clear.trace", "--set", "zz=1"}).code == 2);
}

TEST_CASE("cli info: parameters, resources, passes, outputs") {
  const Run r = run({"info", kExamples + "light.trace", "--set", "lx=0.5"});
  CHECK(r.code == 0);
  CHECK(r.out == cat("trace ", kExamples, "light.trace (ffsim-trace 1)\n",
                     "framebuffer 16x16, profile geforce256\n"
                     "parameters:\n"
                     "  lx = 0.5 (default 0.3)  light direction, x\n"
                     "  ly = 0.4  light direction, y\n"
                     "  penumbra = 2  scale of d (section 4.2: at least 2)\n"
                     "resources: none\n"
                     "passes: 1\n"
                     "  1 glClear  ", kExamples, "light.trace:18:1\n"
                     "outputs:\n"
                     "  expect pixel 5 5 color lx ly sqrt(1-lx^2-ly^2) 0.5 tol 0.5/255  ", kExamples, "light.trace:19:1\n"
                     "  hash color  ", kExamples, "light.trace:20:1\n"));
  const Run t = run({"info", kExamples + "table.trace"});
  CHECK(contains(t.out, "  lookup: table 0.5*(4*x-1)^2, 256x1, 1 channel, float  "));
  CHECK(contains(t.out, "  bump: generate hemisphere_bump, 32x32, 1 channel, float  "));
  const Run c = run({"info", "--commands"});
  CHECK(c.code == 0);
  CHECK(contains(c.out, "glClear mask    (pass)\n"));
  CHECK(contains(c.out, "glClearColor red green blue alpha\n"));
  CHECK(contains(c.out, "generate NAME hemisphere_bump width=64 height=64 radius=16 border=clamp|wrap    "));
  CHECK(run({"info"}).code == 2);
  CHECK(run({"info", "--help"}).code == 0);
}

// Loading traces (sim/trace/trace.h): every error class, with the exact
// file:line:column and message the user sees, and what a correct trace loads to.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "sim/trace/trace.h"

using namespace ffsim;
using namespace ffsim::trace;
namespace fs = std::filesystem;

namespace {
const std::string V = "ffsim-trace 1\n";

std::string load_error(const std::string& text, const LoadOptions& opt = {}) {
  try {
    load_trace_text(text, "t.trace", opt);
  } catch (const TraceError& e) {
    return e.what();
  }
  return "no error";
}

// A fresh directory under the system temp directory for file tests.
fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / (std::string("ffsim-test-") + std::to_string(::getpid()) + "-" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}
void write_file(const fs::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}
}  // namespace

TEST_CASE("trace load: a trace with every set-up command") {
  LoadOptions opt;
  const Program p = load_trace_text(V +
                                        "param lx 0.3 light x\n"
                                        "param two 2*lx \"a quoted description\"\n"
                                        "framebuffer 32 16\n"
                                        "profile rgba10\n"
                                        "table t 5 x*2 i\n"
                                        "generate h hemisphere_bump width=8 height=4 radius=2\n"
                                        "glClearColor lx 0 0 1\n"
                                        "glClear GL_COLOR_BUFFER_BIT|GL_STENCIL_BUFFER_BIT\n"
                                        "dump color out/c.png\n"
                                        "hash alpha\n"
                                        "expect hash color 0123456789abcdef\n"
                                        "expect pixel 1 2 color 0.3 0 0 1 tol 1/1023\n"
                                        "expect error GL_NO_ERROR\n",
                                    "t.trace", opt);
  CHECK(p.width == 32);
  CHECK(p.height == 16);
  CHECK(p.profile.name == "rgba10");
  REQUIRE(p.params.size() == 2);
  CHECK(p.params[0].description == "light x");
  CHECK(p.params[1].value == 0.6);
  CHECK(p.params[1].description == "a quoted description");
  REQUIRE(p.resources.size() == 2);
  const Image& t = *p.resources[0].image;
  CHECK(t.width == 5);
  CHECK(t.channels == 2);
  CHECK(t.f32[t.index(4, 0, 0)] == 2.0f);  // x = 4/4 = 1, times 2
  CHECK(t.f32[t.index(3, 0, 1)] == 3.0f);  // i = 3
  CHECK(p.resources[1].image->width == 8);
  REQUIRE(p.steps.size() == 7);
  CHECK(p.steps[0].args[0].f == static_cast<double>(0.3f));  // glClearColor takes GLclampf
  CHECK(p.steps[1].args[0].i == 0x4400);                     // COLOR 0x4000 | STENCIL 0x0400
  CHECK(p.steps[1].is_pass());
  CHECK(p.steps[2].file == "out/c.png");
  CHECK(p.steps[4].hash == 0x0123456789abcdefull);
  CHECK(p.steps[5].tol == 1.0 / 1023);
  CHECK(p.pass_count() == 1);
}

TEST_CASE("trace load: --set overrides a parameter with an expression") {
  LoadOptions opt;
  opt.sets = {{"lx", "0.5*ly"}};
  const Program p = load_trace_text(V + "param ly 0.8\nparam lx 0.3\n", "t.trace", opt);
  CHECK(p.params[1].value == 0.4);
  CHECK(p.params[1].default_value == 0.3);
  CHECK(p.params[1].overridden);
  opt.sets = {{"lz", "1"}};
  CHECK(load_error(V + "param lx 0.3\n", opt) == "--set:1:1: the trace has no parameter `lz`");
  opt.sets = {{"lx", "1/0"}};
  CHECK(load_error(V + "param lx 0.3\n", opt) == "--set:1:5: division by zero");
  CHECK(parse_set_argument("a=1").second == "1");
  CHECK_THROWS_AS(parse_set_argument("=1"), TraceError);
}

TEST_CASE("trace load: version line errors") {
  CHECK(load_error("") == "t.trace:1:1: empty trace: expected the version line `ffsim-trace 1`");
  CHECK(load_error("# only a comment\n\n") == "t.trace:1:1: empty trace: expected the version line `ffsim-trace 1`");
  CHECK(load_error("glClear GL_COLOR_BUFFER_BIT\n") == "t.trace:1:1: expected the version line `ffsim-trace 1` first");
  CHECK(load_error("ffsim-trace 2\n") == "t.trace:1:13: unsupported trace version `2`; this ffsim reads version 1");
  CHECK(load_error("ffsim-trace 1 x\n") == "t.trace:1:15: the version line is `ffsim-trace 1`");
  CHECK(load_error(V + "ffsim-trace 1\n") == "t.trace:2:1: the version line may appear only once, first in the file");
}

TEST_CASE("trace load: syntax errors") {
  CHECK(load_error(V + "image a \"x.png\n") == "t.trace:2:9: unterminated string");
  CHECK(load_error(V + "glClearColor (1 0 0 1\n") == "t.trace:2:14: unclosed parenthesis");
  CHECK(load_error(V + "glClear \x01\n") == "t.trace:2:9: invalid character 0x01");
  CHECK(load_error(V + "image a \"x\"y\n") == "t.trace:2:12: expected a space after the closing quote");
  CHECK(load_error(V + "image a x\"y\"\n") == "t.trace:2:10: a quote may only start a token");
  CHECK(load_error(V + "\"glClear\" 1\n") == "t.trace:2:1: a command name cannot be quoted");
  CHECK(load_error(V + "glClearColor 1) 0 0 1\n") == "t.trace:2:15: unexpected `)`");
  // Comments and CRLF line ends are fine.
  CHECK(load_error(V + "glClear GL_COLOR_BUFFER_BIT # clear\r\n") == "no error");
}

TEST_CASE("trace load: unknown commands and argument counts") {
  CHECK(load_error(V + "glFrobnicate 1\n") == "t.trace:2:1: unknown command `glFrobnicate`");
  CHECK(load_error(V + "  glClearColor 1 0 0\n") == "t.trace:2:3: glClearColor takes 4 arguments (red green blue alpha), got 3");
  CHECK(load_error(V + "glClear GL_COLOR_BUFFER_BIT 7\n") == "t.trace:2:29: glClear takes 1 argument (mask), got 2");
  CHECK(load_error(V + "glLoadIdentity 1\n") == "t.trace:2:16: glLoadIdentity takes 0 arguments, got 1");
  CHECK(load_error(V + "glLoadMatrixd 1 2 3\n") == "t.trace:2:1: glLoadMatrixd takes 16 arguments (m[16]), got 3");
  CHECK(load_error(V + "param\n") == "t.trace:2:6: `param` needs a name and a default: param NAME DEFAULT [description]");
  CHECK(load_error(V + "framebuffer 8\n") == "t.trace:2:14: `framebuffer` needs more arguments: framebuffer WIDTH HEIGHT");
  CHECK(load_error(V + "framebuffer 8 8 8\n") == "t.trace:2:17: too many arguments: framebuffer WIDTH HEIGHT");
}

TEST_CASE("trace load: argument types") {
  CHECK(load_error(V + "glColorMask 1 0 2 1\n") == "t.trace:2:17: expected 0, 1, GL_TRUE or GL_FALSE for `blue` of glColorMask, got `2`");
  CHECK(load_error(V + "glScissor 0 0 2.5 1\n") == "t.trace:2:15: `width` of glScissor must be an integer, got 2.5");
  CHECK(load_error(V + "glStencilMask -1\n") == "t.trace:2:15: `mask` of glStencilMask must be in [0, 4294967295], got -1");
  CHECK(load_error(V + "glClearColor 1e300 0 0 1\n") == "t.trace:2:14: `red` of glClearColor is outside the binary32 range (1e+300)");
  CHECK(load_error(V + "glMatrixMode GL_FROB\n") == "t.trace:2:14: unknown GL enum `GL_FROB`");
  CHECK(load_error(V + "glMatrixMode GL_BLEND\n") ==
        "t.trace:2:14: `GL_BLEND` is not allowed for `mode` of glMatrixMode (expected GL_MODELVIEW, GL_PROJECTION, GL_TEXTURE or GL_COLOR)");
  CHECK(load_error(V + "glClear GL_COLOR_BUFFER_BIT||GL_DEPTH_BUFFER_BIT\n") == "t.trace:2:29: empty part in the bitfield `mask` of glClear");
  CHECK(load_error(V + "glClear GL_COLOR_BUFFER_BIT|GL_BLEND\n") ==
        "t.trace:2:29: `GL_BLEND` is not allowed in `mask` of glClear (expected GL_COLOR_BUFFER_BIT, GL_DEPTH_BUFFER_BIT, "
        "GL_STENCIL_BUFFER_BIT or GL_ACCUM_BUFFER_BIT)");
  CHECK(load_error(V + "glClear 0.5\n") == "t.trace:2:9: `mask` of glClear must be an integer in [0, 4294967295], got 0.5");
  // Numbers pass the allowed set unchecked, so a trace can provoke GL errors.
  CHECK(load_error(V + "glMatrixMode 0x1234\nglClear 0x8000\n") == "no error");
  CHECK(load_error(V + "glEnable SCISSOR_TEST\n") == "no error");  // the GL_ prefix is optional
}

TEST_CASE("trace load: parameters") {
  CHECK(load_error(V + "glClearColor lx 0 0 1\n") == "t.trace:2:14: unknown parameter `lx`");
  CHECK(load_error(V + "param lx 1\nparam lx 2\n") == "t.trace:3:7: parameter `lx` is already declared at t.trace:2:7");
  CHECK(load_error(V + "param 3d 1\n") == "t.trace:2:7: bad parameter name `3d` (letters, digits and _, not starting with a digit)");
  CHECK(load_error(V + "param a b\n") == "t.trace:2:9: unknown parameter `b`");
}

TEST_CASE("trace load: failed expressions") {
  CHECK(load_error(V + "param a 1\nglClearColor 1/(a-1) 0 0 1\n") == "t.trace:3:15: division by zero");
  CHECK(load_error(V + "glClearColor sqrt(-2) 0 0 1\n") == "t.trace:2:14: sqrt of a negative number (-2)");
  CHECK(load_error(V + "table t 4 1/(x-1)\n") == "t.trace:2:12: division by zero (at i = 3)");
  CHECK(load_error(V + "table t 4 1e38*(i+1)*10\n") == "t.trace:2:11: value 1e+39 at i = 0 is outside the binary32 range");
}

TEST_CASE("trace load: set-up order and limits") {
  CHECK(load_error(V + "glClear GL_COLOR_BUFFER_BIT\nframebuffer 8 8\n") ==
        "t.trace:3:1: `framebuffer` must come before the first GL command or output");
  CHECK(load_error(V + "framebuffer 8 8\nframebuffer 8 8\n") == "t.trace:3:1: `framebuffer` is already set at t.trace:2:1");
  CHECK(load_error(V + "hash color\nprofile ideal\n") == "t.trace:3:1: `profile` must come before the first GL command or output");
  CHECK(load_error(V + "framebuffer 0 8\n") == "t.trace:2:13: the width must be in [1, 16384], got 0");
  CHECK(load_error(V + "framebuffer 16384 16384\n") ==
        "t.trace:2:1: framebuffer size 16384x16384 is out of range (1..16384 per side, at most 67108864 pixels)");
  LoadOptions small;
  small.max_pixels = 100;
  CHECK(load_error(V + "framebuffer 11 10\n", small) ==
        "t.trace:2:1: framebuffer size 11x10 is out of range (1..16384 per side, at most 100 pixels)");
  CHECK(load_error(V + "table t 101 x\n", small) == "t.trace:2:9: the table width must be in [1, 100], got 101");
  CHECK(load_error(V + "generate h hemisphere_bump width=20 height=20\n", small) ==
        "t.trace:2:34: image size 20x20 exceeds the limit of 100 pixels");
  CHECK(load_error(V + "profile nonesuch\n").find("t.trace:2:9: ") == 0);
  LoadOptions size;
  size.size = std::make_pair(0, 5);
  CHECK(load_error(V, size) == "--size:1:1: framebuffer size 0x5 is out of range (1..16384 per side, at most 67108864 pixels)");
}

TEST_CASE("trace load: client images, generators and tables") {
  CHECK(load_error(V + "image a /no/such/file.png\n") == "t.trace:2:9: /no/such/file.png: no such file");
  CHECK(load_error(V + "table a 2 x\ntable a 2 x\n") == "t.trace:3:7: image `a` is already defined at t.trace:2:7");
  CHECK(load_error(V + "table a 2 x 1 2 3 4\n") == "t.trace:2:19: too many arguments: table NAME WIDTH EXPR [EXPR EXPR EXPR]");
  CHECK(load_error(V + "table a 2\n") == "t.trace:2:10: `table` needs a name, a width and 1 to 4 expressions: table NAME WIDTH EXPR...");
  CHECK(load_error(V + "generate h nonesuch\n") == "t.trace:2:12: unknown generator `nonesuch` (this build has bump, bumps, craters, fractal, hemisphere_bump, horizon, ridges or shadowmap)");
  CHECK(load_error(V + "generate h hemisphere_bump radius\n") == "t.trace:2:28: expected key=value, got `radius`");
  CHECK(load_error(V + "generate h hemisphere_bump colour=3\n") == "t.trace:2:28: unknown key `colour`");
  CHECK(load_error(V + "generate h hemisphere_bump border=mirror\n") == "t.trace:2:35: `border` must be clamp or wrap, got `mirror`");
  CHECK(load_error(V + "generate h hemisphere_bump width=2.5\n") == "t.trace:2:34: `width` must be an integer, got 2.5");
  CHECK(load_error(V + "generate h hemisphere_bump width=2 height=2 radius=1e100\n") ==
        "t.trace:2:12: hemisphere_bump: height 1e+100 at (0, 0) is outside the binary32 range");
  CHECK(load_error(V + "generate h hemisphere_bump width=2 height=2 radius=1e200\n") ==
        "t.trace:2:12: hemisphere_bump: non-finite height at x=0 y=0");
  CHECK(load_error(V + "generate h hemisphere_bump radius=1 radius=2\n") == "t.trace:2:37: key `radius` is given twice");
}

TEST_CASE("trace load: outputs") {
  CHECK(load_error(V + "dump colour a.png\n") == "t.trace:2:6: expected a buffer: color, alpha, stencil or depth; got `colour`");
  CHECK(load_error(V + "dump color ../a.png\n") == "t.trace:2:12: dump file `../a.png` must be a relative path inside the output directory (no `..`, no names starting with `.`)");
  CHECK(load_error(V + "dump color /tmp/a.png\n") == "t.trace:2:12: dump file `/tmp/a.png` must be a relative path inside the output directory (no `..`, no names starting with `.`)");
  CHECK(load_error(V + "dump color sub/.a.png\n") == "t.trace:2:12: dump file `sub/.a.png` must be a relative path inside the output directory (no `..`, no names starting with `.`)");
  CHECK(load_error(V + "dump color a.jpg\n") == "t.trace:2:12: dump file `a.jpg` needs the extension .png, .exr, .tif or .tiff");
  CHECK(load_error(V + "dump color a.png\ndump alpha a.png\n") == "t.trace:3:12: `a.png` is already written by the dump at t.trace:2:1");
  CHECK(load_error(V + "dump color passes/a.png\n") == "t.trace:2:12: the directory passes/ is reserved for --dump-each-pass");
  CHECK(load_error(V + "expect hash color 12\n") == "t.trace:2:19: expected a hash of 16 hex digits, got `12`");
  CHECK(load_error(V + "framebuffer 8 8\nexpect pixel 8 0 alpha 0\n") == "t.trace:3:14: x must be in [0, 7], got 8");
  CHECK(load_error(V + "expect pixel 0 0 color 1 1 1\n") == "t.trace:2:29: expected 4 values for color, got 3");
  CHECK(load_error(V + "expect pixel 0 0 alpha 1 1\n") == "t.trace:2:26: too many values: alpha has 1");
  CHECK(load_error(V + "expect pixel 0 0 alpha 1 tol\n") == "t.trace:2:29: `tol` needs a value");
  CHECK(load_error(V + "expect pixel 0 0 alpha 1 tol -1\n") == "t.trace:2:30: the tolerance must not be negative, got -1");
  CHECK(load_error(V + "expect frobs\n") == "t.trace:2:8: expected hash, pixel, image, error or enabled after `expect`, got `frobs`");
  CHECK(load_error(V + "expect error GL_FROB\n") == "t.trace:2:14: unknown GL enum `GL_FROB`");
  CHECK(load_error(V + "expect enabled GL_SCISSOR_TEST 2\n") == "t.trace:2:32: expected 0, 1, GL_TRUE or GL_FALSE for the state, got `2`");
  CHECK(load_error(V + "expect\n") == "t.trace:2:7: `expect` needs what to check: hash, pixel, image, error or enabled");
}

TEST_CASE("trace load: files, includes and cycles") {
  const fs::path d = temp_dir("includes");
  write_file(d / "a.trace", V + "include sub/b.trace\n");
  fs::create_directories(d / "sub");
  write_file(d / "sub/b.trace", V + "param x 1\ninclude ../a.trace\n");
  const std::string a = (d / "a.trace").string(), b = (d / "sub/b.trace").string();
  try {
    load_trace_file(a, {});
    FAIL("expected an include cycle");
  } catch (const TraceError& e) {
    CHECK(std::string(e.what()) == b + ":3:9: include cycle: " + a + " -> " + b + " -> " + (d / "sub/../a.trace").string());
    CHECK(e.excerpt() == "  include ../a.trace\n          ^\n");
  }
  write_file(d / "c.trace", V + "include nonesuch.trace\n");
  try {
    load_trace_file((d / "c.trace").string(), {});
    FAIL("expected a missing file");
  } catch (const TraceError& e) {
    CHECK(std::string(e.what()) == (d / "c.trace").string() + ":2:9: cannot read `" + (d / "nonesuch.trace").string() + "`: no such file");
  }
  try {
    load_trace_file((d / "missing.trace").string(), {});
    FAIL("expected a missing file");
  } catch (const TraceError& e) {
    CHECK(std::string(e.what()) == cat("cannot read `", (d / "missing.trace").string(), "`: no such file"));
  }
  // A chain deeper than kMaxIncludeDepth.
  for (int k = 0; k < 20; ++k) write_file(d / cat("n", std::to_string(k), ".trace"), cat(V, "include n", std::to_string(k + 1), ".trace\n"));
  try {
    load_trace_file((d / "n0.trace").string(), {});
    FAIL("expected the include depth limit");
  } catch (const TraceError& e) {
    CHECK(std::string(e.what()) == (d / "n16.trace").string() + ":2:1: includes nested more than 16 deep");
  }
  // Files outside the allowed root are refused (the fuzz driver uses this).
  LoadOptions rooted;
  rooted.file_root = (d / "sub").string();
  write_file(d / "sub/c.trace", V + "include ../c.trace\n");
  try {
    load_trace_file((d / "sub/c.trace").string(), rooted);
    FAIL("expected a refusal");
  } catch (const TraceError& e) {
    CHECK(std::string(e.what()) == (d / "sub/c.trace").string() + ":2:9: `" + (d / "sub/../c.trace").string() +
                                       std::string("` is outside the allowed directory ") + (d / "sub").string());
  }
  // A directory is not a trace.
  write_file(d / "dir.trace", V + "include sub\n");
  try {
    load_trace_file((d / "dir.trace").string(), {});
    FAIL("expected an error");
  } catch (const TraceError& e) {
    CHECK(std::string(e.what()) == (d / "dir.trace").string() + ":2:9: cannot read `" + (d / "sub").string() + "`: not a regular file");
  }
  fs::remove_all(d);
}

TEST_CASE("trace load: a profile without a stencil buffer rejects stencil outputs") {
  const fs::path d = temp_dir("profile");
  write_file(d / "nostencil.profile", "base = geforce256\nstencil_bits = 0\n");
  write_file(d / "t.trace", V + "profile nostencil.profile\nhash stencil\n");
  try {
    load_trace_file((d / "t.trace").string(), {});
    FAIL("expected an error");
  } catch (const TraceError& e) {
    // A profile read from a file is named by its path.
    CHECK(std::string(e.what()) ==
          cat((d / "t.trace").string(), ":3:6: the framebuffer has no stencil buffer (profile ", (d / "nostencil.profile").string(), ")"));
  }
  fs::remove_all(d);
}

TEST_CASE("trace load: excerpt shows the line and a caret") {
  try {
    load_trace_text(V + "glClearColor\t1 lz 0 1\n", "t.trace", {});
    FAIL("expected an error");
  } catch (const TraceError& e) {
    CHECK(std::string(e.what()) == "t.trace:2:16: unknown parameter `lz`");
    CHECK(e.excerpt() == "  glClearColor\t1 lz 0 1\n              \t  ^\n");
  }
}

TEST_CASE("trace load: image reads a file relative to the trace") {
  // traces/examples/data/quad.png was written by traces/examples/make-quad.trace:
  // white, red lower-left quarter and blue upper-right quarter with alpha code 128.
  const Program p = load_trace_file(std::string(FFSIM_SOURCE_DIR) + "/traces/examples/image.trace", {});
  REQUIRE(p.resources.size() == 1);
  const Image& q = *p.resources[0].image;
  CHECK(q.width == 4);
  CHECK(q.channels == 4);
  CHECK(q.type == SampleType::U8);
  // Rows bottom to top: (0, 0) is the lower-left pixel.
  CHECK(q.u8[q.index(0, 0, 0)] == 255);
  CHECK(q.u8[q.index(0, 0, 2)] == 0);
  CHECK(q.u8[q.index(0, 0, 3)] == 128);
  CHECK(q.u8[q.index(3, 3, 2)] == 255);
  CHECK(q.u8[q.index(3, 3, 0)] == 0);
  CHECK(q.u8[q.index(0, 3, 0)] == 255);
  CHECK(q.u8[q.index(0, 3, 3)] == 255);
}

TEST_CASE("trace load: the bytes read in all, includes expanded, are capped") {
  // A 3 MiB file (one comment line) included 22 times: 21 x 3 MiB = 63 MiB plus
  // the main file stay under 64 MiB, the 22nd include (line 23) goes over.
  const fs::path d = temp_dir("bytes");
  write_file(d / "big.trace", cat(V, "#", std::string(3u << 20, 'x'), "\n"));
  std::string main = V;
  for (int k = 0; k < 22; ++k) main += "include big.trace\n";
  write_file(d / "main.trace", main);
  try {
    load_trace_file((d / "main.trace").string(), {});
    FAIL("expected the size limit");
  } catch (const TraceError& e) {
    CHECK(std::string(e.what()) == cat((d / "main.trace").string(), ":23:9: the trace reads more than 67108864 bytes (includes expanded)"));
  }
  fs::remove_all(d);
}

TEST_CASE("trace load: an enum argument may be an expression over parameters and GL_ names") {
  const std::string t = V + "param filter 1\nglTexParameteri GL_TEXTURE_2D GL_TEXTURE_MIN_FILTER (GL_NEAREST+filter)\n";
  Program p = load_trace_text(t, "t.trace", {});
  REQUIRE(p.steps.size() == 1);
  CHECK(p.steps[0].args[2].i == 0x2601);  // GL_LINEAR
  LoadOptions opt;
  opt.sets = {{"filter", "0"}};
  p = load_trace_text(t, "t.trace", opt);
  CHECK(p.steps[0].args[2].i == 0x2600);  // GL_NEAREST
  // Parameters are looked up first; unknown GL_ names and fractions are errors at the argument.
  CHECK(load_error(V + "glTexParameteri GL_TEXTURE_2D GL_TEXTURE_MIN_FILTER (GL_NOPE+1)\n").find("GL_NOPE") != std::string::npos);
  CHECK(load_error(V + "glTexParameteri GL_TEXTURE_2D GL_TEXTURE_MIN_FILTER (GL_NEAREST+0.5)\n") ==
        "t.trace:2:53: `param` of glTexParameteri must be an integer, got 9728.5");
  // GL_ names are not known outside enum positions.
  CHECK(load_error(V + "glClearColor (GL_NEAREST) 0 0 0\n").find("GL_NEAREST") != std::string::npos);
}

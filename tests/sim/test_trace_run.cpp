// Running traces (sim/trace/executor.h) and the binder (sim/trace/binder.h): GL
// state after each bound call, GL errors with their trace line, --strict, outputs,
// every example trace, round trips (twice, 1 and 2 threads).
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <unistd.h>

#include "sim/hash.h"
#include "sim/profile_io.h"
#include "sim/trace/executor.h"
#include "sim/trace/explain.h"
#include "sim/trace/trace.h"

using namespace ffsim;
using namespace ffsim::trace;
namespace fs = std::filesystem;

namespace {
const std::string V = "ffsim-trace 1\n";
const fs::path kExamples = fs::path(FFSIM_SOURCE_DIR) / "traces" / "examples";

struct Ran {
  Program prog;
  RunResult r;
  std::string out;
};
Ran run_text(const std::string& text, RunOptions ro = {}) {
  Ran x;
  x.prog = load_trace_text(text, "t.trace", {});
  std::ostringstream out;
  x.r = run_program(x.prog, ro, out);
  x.out = out.str();
  return x;
}
fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / (std::string("ffsim-test-") + std::to_string(::getpid()) + "-" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}
std::vector<fs::path> example_traces() {
  std::vector<fs::path> v;
  for (const auto& e : fs::recursive_directory_iterator(kExamples))
    if (e.is_regular_file() && e.path().extension() == ".trace") v.push_back(e.path());
  std::sort(v.begin(), v.end());
  return v;
}
std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
}  // namespace

TEST_CASE("trace run: every bound core command reaches the Context") {
  const Program p = load_trace_text(V +
                                        "framebuffer 8 4\n"
                                        "glClearColor 0.25 0.5 0.75 1\n"
                                        "glClearStencil 3\n"
                                        "glClearDepth 0.5\n"
                                        "glColorMask 1 GL_FALSE 1 0\n"
                                        "glStencilMask 0x0F\n"
                                        "glDepthMask 0\n"
                                        "glScissor 1 2 3 4\n"
                                        "glEnable GL_SCISSOR_TEST\n"
                                        "glMatrixMode GL_COLOR\n"
                                        "glLoadMatrixd 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16\n"
                                        "glPushMatrix\n"
                                        "glMultMatrixf 2 0 0 0 0 2 0 0 0 0 2 0 0 0 0 2\n"
                                        "glPopMatrix\n"
                                        "glMatrixMode GL_PROJECTION\n"
                                        "glOrtho 0 8 0 4 -1 1\n"
                                        "glMatrixMode GL_MODELVIEW\n"
                                        "glTranslated 1 2 3\n"
                                        "glScalef 2 2 2\n"
                                        "glRotated 90 0 0 1\n"
                                        "glLoadIdentity\n"
                                        "glTranslatef 0.1 0 0\n"
                                        "glFrustum -1 1 -1 1 1 10\n"
                                        "glLoadMatrixf 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n"
                                        "glMultMatrixd 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n"
                                        "glRotatef 0 0 0 1\n"
                                        "glScaled 1 1 1\n"
                                        "glDisable GL_SCISSOR_TEST\n",
                                    "t.trace", {});
  Context ctx(p.profile, p.width, p.height);
  std::ostringstream out;
  const RunResult r = run_program_on(ctx, p, {}, out);
  CHECK(r.ok);
  CHECK(r.gl_errors.empty());
  CHECK(ctx.clear_state().color == std::array<double, 4>{0.25, 0.5, 0.75, 1});
  CHECK(ctx.clear_state().stencil == 3);
  CHECK(ctx.clear_state().depth == 0.5);
  CHECK(ctx.write_masks().color == std::array<bool, 4>{true, false, true, false});
  CHECK(ctx.write_masks().stencil == 0x0F);
  CHECK(!ctx.write_masks().depth);
  CHECK(ctx.scissor_state().box.x == 1);
  CHECK(ctx.scissor_state().box.height == 4);
  CHECK(!ctx.scissor_state().enabled);
  // glLoadMatrixd is column-major: element (row 3, column 0) is the 4th value.
  CHECK(ctx.color_matrix().top()[0][3] == 4);
  CHECK(ctx.color_matrix().top()[3][0] == 13);
  CHECK(ctx.matrix_mode() == gl::MODELVIEW);
  // glTranslatef rounds 0.1 to binary32 like the C call, then the frustum multiplies.
  CHECK(ctx.modelview().top()[0][0] == 1);
}

TEST_CASE("trace run: the paper's color matrix M from lx and ly") {
  // Kautz et al. section 4.1.3, transposed for glLoadMatrixd (column-major):
  // alpha' = lx/2 R + ly/2 G - B/2 + (1/2 - (lx+ly)/4) A.
  const Program p = load_trace_file((kExamples / "light.trace").string(), {});
  Context ctx(p.profile, p.width, p.height);
  std::ostringstream out;
  CHECK(run_program_on(ctx, p, {}, out).ok);
  const auto& m = ctx.color_matrix().top();  // glm: m[column][row]
  CHECK(m[0][3] == 0.5 * 0.3);
  CHECK(m[1][3] == 0.5 * 0.4);
  CHECK(m[2][3] == -0.5);
  CHECK(m[3][3] == -0.25 * (0.3 + 0.4) + 0.5);
  CHECK(m[0][0] == 0);
  CHECK(m[3][2] == 0);
}

TEST_CASE("trace run: matrices.trace leaves the stacks as a hand computation says") {
  const Program p = load_trace_file((kExamples / "matrices.trace").string(), {});
  Context ctx(p.profile, p.width, p.height);
  std::ostringstream out;
  const RunResult r = run_program_on(ctx, p, {}, out);
  CHECK(r.ok);
  CHECK(r.gl_errors.empty());
  // glPushMatrix / glPopMatrix undo translate-rotate-scale; glMultMatrixd leaves a
  // translation by 0.5 in x (column 3, row 0).
  CHECK(ctx.modelview().top()[3][0] == 0.5);
  CHECK(ctx.modelview().top()[0][0] == 1);
  CHECK(ctx.modelview().top()[0][1] == 0);
  // glOrtho(0, 16, 0, 16, -1, 1): x scale 2/16, x offset -1.
  CHECK(ctx.projection().top()[0][0] == 0.125);
  CHECK(ctx.projection().top()[3][0] == -1);
  CHECK(ctx.texture_matrix(0).top() == glm::dmat4(1.0));
  CHECK(!ctx.write_masks().depth);
}

TEST_CASE("trace run: GL errors carry the trace line and --strict stops at the first") {
  const std::string t = V + "framebuffer 4 4\nglScissor 0 0 -1 1\nglClear GL_COLOR_BUFFER_BIT\n";
  const Ran a = run_text(t);
  CHECK(a.r.ok);
  REQUIRE(a.r.gl_errors.size() == 1);
  CHECK(a.r.gl_errors[0] == "t.trace:3:1: glScissor: GL_INVALID_VALUE: width and height must not be negative (got -1, 1)");
  CHECK(a.r.passes == 1);
  RunOptions strict;
  strict.strict = true;
  const Ran b = run_text(t, strict);
  CHECK(!b.r.ok);
  CHECK(b.r.strict_stop);
  CHECK(b.r.fatal == "t.trace:3:1: glScissor: GL_INVALID_VALUE: width and height must not be negative (got -1, 1) (--strict)");
  CHECK(b.r.passes == 0);  // glClear never ran
  CHECK(b.r.steps == 1);
  // An error checked by `expect error` is neither reported nor fatal.
  const Ran c = run_text(t + "expect error GL_NO_ERROR\n", strict);
  CHECK(!c.r.ok);
  const Ran d = run_text(V + "glScissor 0 0 -1 1\nexpect error GL_INVALID_VALUE\nglPopMatrix\nexpect error GL_STACK_UNDERFLOW\n", strict);
  CHECK(d.r.ok);
  CHECK(d.r.gl_errors.empty());
  CHECK(d.r.expect_failures.empty());
}

TEST_CASE("trace run: expect failures are reported and do not stop the run") {
  const Ran a = run_text(V +
                         "framebuffer 4 4\n"
                         "glClearColor 1 0.5 0 1\n"
                         "glClear GL_COLOR_BUFFER_BIT\n"
                         "expect pixel 0 0 color 1 0.5 0 1\n"
                         "expect pixel 0 0 color 1 0.5 0 1 tol 1/255\n"
                         "expect pixel 1 1 alpha 0\n"
                         "expect pixel 1 1 stencil 1\n"
                         "expect pixel 1 1 depth 1\n"
                         "expect hash color 0000000000000000\n"
                         "expect error GL_INVALID_ENUM\n"
                         "hash color\n");
  CHECK(a.r.ok);
  CHECK(a.r.exit_code() == 1);
  REQUIRE(a.r.expect_failures.size() == 6);
  // 0.5 -> code 128 (round half up), 128/255 = 0.50196...
  CHECK(a.r.expect_failures[0] ==
        "t.trace:5:1: expect pixel 0 0 color: got (1, 0.5019607843137255, 0, 1), expected (1, 0.5, 0, 1) (tol 0)");
  CHECK(a.r.expect_failures[1] == "t.trace:7:1: expect pixel 1 1 alpha: got 1, expected 0 (tol 0)");
  CHECK(a.r.expect_failures[2] == "t.trace:8:1: expect pixel 1 1 stencil: got 0, expected 1 (tol 0)");
  CHECK(a.r.expect_failures[3] == "t.trace:9:1: expect pixel 1 1 depth: got 0, expected 1 (tol 0)");
  CHECK(a.r.expect_failures[4].find("t.trace:10:1: expect hash color: got ") == 0);
  CHECK(a.r.expect_failures[5] == "t.trace:11:1: expect error GL_INVALID_ENUM: glGetError returned GL_NO_ERROR");
  CHECK(a.r.gl_errors.empty());
  REQUIRE(a.r.hashes.size() == 1);
  // The last expect error: glGetError returned GL_NO_ERROR.
  const Ran e = run_text(V + "glEnable GL_SCISSOR_TEST\nexpect enabled GL_SCISSOR_TEST 1\nexpect enabled GL_SCISSOR_TEST 0\n");
  REQUIRE(e.r.expect_failures.size() == 1);
  CHECK(e.r.expect_failures[0] == "t.trace:4:1: expect enabled GL_SCISSOR_TEST: glIsEnabled returned GL_TRUE");
  const Ran b = run_text(V + "expect error GL_INVALID_ENUM\n");
  REQUIRE(b.r.expect_failures.size() == 1);
  CHECK(b.r.expect_failures[0] == "t.trace:2:1: expect error GL_INVALID_ENUM: glGetError returned GL_NO_ERROR");
}

TEST_CASE("trace run: a hash equals the hash of the same framebuffer built directly") {
  // clear.trace clears a 64x32 geforce256 framebuffer to (1, 0.5, 0, 1): codes
  // (255, 128, 0, 255) by docs/numerics.md 1.2. Build that framebuffer without the
  // trace machinery and compare hashes.
  const Program p = load_trace_file((kExamples / "clear.trace").string(), {});
  std::ostringstream out;
  const RunResult r = run_program(p, {}, out);
  REQUIRE(r.hashes.size() == 1);
  Framebuffer fb(FramebufferFormat::from_profile(p.profile, 64, 32));
  for (std::size_t i = 0; i < fb.codes().size(); i += 4) {
    fb.codes()[i] = 255;
    fb.codes()[i + 1] = 128;
    fb.codes()[i + 2] = 0;
    fb.codes()[i + 3] = 255;
  }
  CHECK(r.hashes[0].hex == hash_hex(buffer_hash(fb, BufferKind::Color)));
}

TEST_CASE("trace run: every example trace replays without errors or failed expects") {
  const auto files = example_traces();
  CHECK(files.size() >= 8);
  for (const auto& f : files) {
    CAPTURE(f.string());
    const Program p = load_trace_file(f.string(), {});
    std::ostringstream out;
    const RunResult r = run_program(p, {}, out);
    CHECK(r.ok);
    CHECK(r.gl_errors.empty());
    CHECK(r.expect_failures.empty());
  }
}

TEST_CASE("trace run: every trace line in docs/trace-format.md is in an example trace") {
  // docs/trace-format.md shows examples in ```trace blocks; each of their lines must
  // come from a file under traces/examples, which the test above replays.
  std::set<std::string> lines;
  for (const auto& f : example_traces()) {
    std::istringstream in(read_file(f));
    for (std::string l; std::getline(in, l);) lines.insert(l);
  }
  std::istringstream doc(read_file(fs::path(FFSIM_SOURCE_DIR) / "docs" / "trace-format.md"));
  bool in_block = false;
  int checked = 0;
  for (std::string l; std::getline(doc, l);) {
    if (l == "```trace") { in_block = true; continue; }
    if (l == "```") { in_block = false; continue; }
    if (!in_block || l.empty() || l == "...") continue;
    CAPTURE(l);
    CHECK(lines.count(l) == 1);
    ++checked;
  }
  CHECK(checked > 40);
}

TEST_CASE("trace run: replaying twice and with 1 or 2 threads gives identical hashes") {
  for (const auto& f : example_traces()) {
    CAPTURE(f.string());
    const Program p = load_trace_file(f.string(), {});
    std::vector<std::vector<std::pair<std::string, std::string>>> finals;
    std::vector<std::vector<std::string>> hashes;
    for (int threads : {1, 1, 2}) {
      RunOptions ro;
      ro.threads = threads;
      std::ostringstream out;
      const RunResult r = run_program(p, ro, out);
      finals.push_back(r.final_hashes);
      std::vector<std::string> h;
      for (const auto& x : r.hashes) h.push_back(x.hex);
      hashes.push_back(h);
    }
    CHECK(finals[0] == finals[1]);
    CHECK(finals[0] == finals[2]);
    CHECK(hashes[0] == hashes[1]);
    CHECK(hashes[0] == hashes[2]);
    CHECK(finals[0].size() == 4);
  }
}

TEST_CASE("trace run: dumps are written only when the run succeeds") {
  const fs::path d = temp_dir("dumps");
  RunOptions ro;
  ro.out_dir = (d / "ok").string();
  ro.dump_each_pass = true;
  const Ran a = run_text(V + "framebuffer 4 4\nglClear GL_COLOR_BUFFER_BIT\ndump color sub/c.png\ndump alpha a.exr\ndump stencil s.png\ndump depth z.tif\n", ro);
  CHECK(a.r.ok);
  for (const char* f : {"sub/c.png", "a.exr", "s.png", "z.tif", "passes/001-glClear-color.png",
                        "passes/001-glClear-alpha.png", "passes/001-glClear-stencil.png"})
    CHECK(fs::exists(d / "ok" / f));
  CHECK(a.r.written.size() == 7);
  // No temporaries are left.
  for (const auto& e : fs::recursive_directory_iterator(d / "ok")) CHECK(e.path().filename().string()[0] != '.');
  // A fatal GL error after a dump: nothing is left behind.
  ro.out_dir = (d / "fail").string();
  ro.strict = true;
  const Ran b = run_text(V + "framebuffer 4 4\nglClear GL_COLOR_BUFFER_BIT\ndump color c.png\nglPopMatrix\nglClear GL_COLOR_BUFFER_BIT\n", ro);
  CHECK(!b.r.ok);
  CHECK(b.r.written.empty());
  std::size_t files = 0;
  if (fs::exists(d / "fail"))
    for (const auto& e : fs::recursive_directory_iterator(d / "fail")) files += e.is_regular_file() ? 1 : 0;
  CHECK(files == 0);
  fs::remove_all(d);
}

TEST_CASE("trace run: --explain and --probe print per pass") {
  RunOptions ro;
  ro.explain = true;
  ro.probe = std::make_pair(2, 1);
  const Ran a = run_text(V + "framebuffer 4 4\nglClearColor 1 0 0 1\nglScissor 2 0 2 2\nglEnable GL_SCISSOR_TEST\nglColorMask 1 1 1 0\n"
                             "glClear GL_COLOR_BUFFER_BIT\nglScissor 0 0 1 1\nglClear GL_COLOR_BUFFER_BIT\n", ro);
  CHECK(a.out ==
        "pass 1: glClear at t.trace:7:1\n"
        "  framebuffer: clear color in (2, 0) 2x2\n"
        "  framebuffer: writes: color RGB, stencil mask 0xFF, depth on; scissor (2, 0) 2x2\n"
        "  probe (2, 1) clear: color codes (0, 0, 0, 0) = (0, 0, 0, 0), stencil 0, depth 0 -> "
        "color codes (255, 0, 0, 0) = (1, 0, 0, 0), stencil 0, depth 0\n"
        "pass 2: glClear at t.trace:9:1\n"
        "  framebuffer: clear color in (0, 0) 1x1\n"
        "  framebuffer: writes: color RGB, stencil mask 0xFF, depth on; scissor (0, 0) 1x1\n");
  // Probe only: passes that do not touch the pixel print nothing.
  RunOptions po;
  po.probe = std::make_pair(3, 3);
  CHECK(run_text(V + "framebuffer 4 4\nglScissor 0 0 1 1\nglEnable GL_SCISSOR_TEST\nglClear GL_COLOR_BUFFER_BIT\n", po).out.empty());
}

TEST_CASE("trace run: write_fragments records the probed pixel") {
  Context ctx(load_profile("geforce256"), 4, 4);
  ctx.probe().set_target(1, 0);
  FragmentSpan span;
  span.y = 0;
  span.x0 = 0;
  span.count = 2;
  span.codes = {10, 20, 30, 40, 50, 60, 70, 80};
  ctx.write_fragments(span);
  REQUIRE(ctx.probe().records().size() == 1);
  CHECK(ctx.probe().records()[0].stage == "write_fragments");
  CHECK(ctx.probe().records()[0].text ==
        "fragment codes (50, 60, 70, 80) = (0.196078, 0.235294, 0.27451, 0.313725)\n"
        "    before: color codes (0, 0, 0, 0) = (0, 0, 0, 0), stencil 0, depth 0\n"
        "    after:  color codes (50, 60, 70, 80) = (0.196078, 0.235294, 0.27451, 0.313725), stencil 0, depth 0");
}

TEST_CASE("trace binder: the table builds and bindings are checked") {
  const CommandTable& t = gl_commands();
  for (const char* n : {"glClearColor", "glClearStencil", "glClearDepth", "glClear", "glColorMask", "glStencilMask",
                        "glDepthMask", "glScissor", "glEnable", "glDisable", "glMatrixMode", "glLoadIdentity",
                        "glLoadMatrixd", "glLoadMatrixf", "glMultMatrixd", "glMultMatrixf", "glPushMatrix", "glPopMatrix",
                        "glTranslated", "glTranslatef", "glScaled", "glScalef", "glRotated", "glRotatef", "glOrtho", "glFrustum"})
    CHECK(t.find(n) != nullptr);
  CHECK(t.find("glClear")->is_pass);
  CHECK(!t.find("glClearColor")->is_pass);
  CHECK(t.find("glClearColor")->signature() == "glClearColor red green blue alpha");
  CHECK(t.find("glLoadMatrixd")->signature() == "glLoadMatrixd m[16]");
  CommandTable bad;
  CHECK_THROWS_WITH_AS(bad.bind("glClearColor", &Context::clearColor, {Float("r")}),
                       "glClearColor: 1 argument specs for a method with 4 parameters", BindError);
  CHECK_THROWS_WITH_AS(bad.bind("glColorMask", &Context::colorMask, {Float("r"), Bool("g"), Bool("b"), Bool("a")}),
                       "glColorMask: argument 1 (r) has a spec kind the method parameter cannot take", BindError);
  bad.bind("glLoadIdentity", &Context::loadIdentity, {});
  CHECK_THROWS_WITH_AS(bad.bind("glLoadIdentity", &Context::loadIdentity, {}), "glLoadIdentity is bound twice", BindError);
  CHECK_THROWS_AS(bad.add("glX", {Numbers("v", 0), Float("after")}, [](Context&, const Args&) {}), BindError);
}

TEST_CASE("trace binder: lambda commands with client images and variable-length numbers") {
  // A custom table, as an area file would extend gl_commands(): an image argument
  // and a rest-of-line Numbers argument reach the lambda unchanged.
  CommandTable t;
  register_core_commands(t);
  int width_seen = 0;
  std::vector<double> numbers_seen;
  GLenum enum_seen = 0;
  t.add("glTestImage", {Enum("target", {gl::TEXTURE_2D}), ClientImage("pixels"), Numbers("extra", 0)},
        [&](Context&, const Args& a) {
          enum_seen = a.enum_at(0);
          width_seen = a.image_at(1).width;
          numbers_seen = a.numbers_at(2);
        })
      .pass();
  LoadOptions lo;
  lo.commands = &t;
  const Program p = load_trace_text(V + "table ramp 7 x\nglTestImage GL_TEXTURE_2D ramp 1 2 (1+2)\n", "t.trace", lo);
  std::ostringstream out;
  const RunResult r = run_program(p, {}, out);
  CHECK(r.passes == 1);
  CHECK(enum_seen == gl::TEXTURE_2D);
  CHECK(width_seen == 7);
  CHECK(numbers_seen == std::vector<double>{1, 2, 3});
  try {
    load_trace_text(V + "glTestImage GL_TEXTURE_2D nope 1\n", "t.trace", lo);
    FAIL("expected an error");
  } catch (const TraceError& e) {
    CHECK(std::string(e.what()) == "t.trace:2:27: unknown image `nope` (define it with image, generate or table)");
  }
  try {
    load_trace_text(V + "table ramp 7 x\nglTestImage GL_TEXTURE_2D ramp\n", "t.trace", lo);
    FAIL("expected an error");
  } catch (const TraceError& e) {
    CHECK(std::string(e.what()) == "t.trace:3:1: glTestImage takes at least 3 arguments (target pixels extra...), got 2");
  }
}

TEST_CASE("trace explain: the registry has the framebuffer explainer") {
  REQUIRE(!explainers().all().empty());
  CHECK(explainers().all()[0].area == "framebuffer");
}

TEST_CASE("trace run: quiet runs of vertex calls replay as step by step, and a bad texture unit is reported at its line") {
  // StepHot::quiet_run: consecutive packed vertex-data calls that cannot record
  // a GL error are called one after the other without the per-step
  // bookkeeping. The same program with every quiet_run zeroed runs step by
  // step: the buffers, step counts and errors must be the same.
  const std::string t = V +
                        "profile geforce256\n"
                        "framebuffer 16 16\n"
                        "glMatrixMode GL_PROJECTION\n"
                        "glOrtho 0 16 0 16 -1 1\n"
                        "glMatrixMode GL_MODELVIEW\n"
                        "glVertex2d 1 1\n"                       // 7: outside glBegin: no effect, no error
                        "glBegin GL_TRIANGLE_STRIP\n"            // 8
                        "glColor4d 1 0.5 0.25 1\n"
                        "glSecondaryColor3d 0.1 0.2 0.3\n"
                        "glNormal3d 0 0 1\n"
                        "glTexCoord2d 0 0\n"
                        "glMultiTexCoord2d GL_TEXTURE1 0 1\n"
                        "glVertex2d 0 0\n"
                        "glColor3f 0.5 1 0\n"
                        "glMultiTexCoord2d GL_TEXTURE3 1 1\n"    // 16: not a unit of geforce256
                        "glVertex3d 16 0 0\n"
                        "glMultiTexCoord4d GL_TEXTURE0 0 1 0 1\n"
                        "glVertex4d 0 16 0 1\n"
                        "glVertex2d 16 16\n"
                        "glEnd\n"                                // 21
                        "hash color\n";
  Program quiet = load_trace_text(t, "t.trace", {});
  Program steps = quiet;
  std::size_t longest = 0;
  for (StepHot& h : steps.hot) {
    longest = std::max<std::size_t>(longest, h.quiet_run);
    h.quiet_run = 0;
  }
  CHECK(longest == 7);  // glVertex2d 1 1 (line 7) is followed by glBegin; lines 9-15 are the longest run
  // Steps: lines 4-6 are steps 0-2, line 7 step 3, and so on (line = step + 4).
  REQUIRE(quiet.hot.size() == 19);
  CHECK(quiet.hot[3].quiet_run == 1);   // line 7, alone
  CHECK(quiet.hot[4].quiet_run == 0);   // glBegin (may record an error)
  CHECK(quiet.hot[5].quiet_run == 7);   // lines 9-15
  CHECK(quiet.hot[12].quiet_run == 0);  // line 16: GL_TEXTURE3
  CHECK(quiet.hot[13].quiet_run == 4);  // lines 17-20
  CHECK(quiet.hot[17].quiet_run == 0);  // glEnd (a pass)
  CHECK(quiet.hot[18].quiet_run == 0);  // hash
  std::ostringstream out;
  const RunResult a = run_program(quiet, {}, out), b = run_program(steps, {}, out);
  CHECK(a.ok);
  CHECK(a.steps == b.steps);
  CHECK(a.steps == 19);
  CHECK(a.passes == 1);
  REQUIRE(a.gl_errors.size() == 1);
  CHECK(a.gl_errors == b.gl_errors);
  CHECK(a.gl_errors[0].rfind("t.trace:16:1: glMultiTexCoord: GL_INVALID_ENUM", 0) == 0);
  REQUIRE(a.hashes.size() == 1);
  CHECK(a.hashes[0].hex == b.hashes[0].hex);
  CHECK(a.final_hashes == b.final_hashes);
  // --strict stops at the bad unit either way, after the same steps.
  RunOptions strict;
  strict.strict = true;
  const RunResult c = run_program(quiet, strict, out), d = run_program(steps, strict, out);
  CHECK(!c.ok);
  CHECK(c.steps == d.steps);
  CHECK(c.fatal == d.fatal);
  // On a Context with fewer texture units than the program's profile, a unit
  // valid for the program may not be: every step is taken one by one.
  Program four = load_trace_text(t, "t.trace", {});
  four.profile = *find_builtin_profile("rgba12");  // 4 units: GL_TEXTURE3 too is quiet
  four.hot = hot_steps(four);
  CHECK(four.hot[5].quiet_run == 12);  // lines 9-20
  Context two(*find_builtin_profile("geforce256"), 16, 16);
  const RunResult e = run_program_on(two, four, {}, out);
  REQUIRE(e.gl_errors.size() == 1);
  CHECK(e.gl_errors[0] == a.gl_errors[0]);
  CHECK(e.final_hashes == a.final_hashes);
}

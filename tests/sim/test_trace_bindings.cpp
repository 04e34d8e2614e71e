// The GL commands of the pipeline areas (sim/trace/commands_pixels.cpp,
// commands_draw.cpp, commands_fragment.cpp, commands_combiners.cpp): every bound
// command runs in a minimal valid form, load errors (enums, counts, client image
// formats, vector sizes) name their exact position, run-time overreads stop the
// replay at the call, GL errors carry the trace line, client memory written by
// glReadPixels is used by later calls and by `dump image`, and the explainers.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>

#include "pipeline/combiners/register_combiners.h"
#include "sim/profile_io.h"
#include "sim/trace/executor.h"
#include "sim/trace/trace.h"

using namespace ffsim;
using namespace ffsim::trace;
namespace fs = std::filesystem;

namespace {
const std::string V = "ffsim-trace 1\n";
const fs::path kExamples = fs::path(FFSIM_SOURCE_DIR) / "traces" / "examples";

// Client images every minimal form may use: quad is the 4x4 8-bit RGBA
// data/quad.png, src and invert 2x1 float RGBA tables.
const std::string kImages =
    "framebuffer 4 4\n"
    "image quad data/quad.png\n"
    "table src 2 x 0 0 1\n"
    "table invert 2 1-x 1-x 1-x 1-x\n";

struct Ran {
  RunResult r;
  std::string out;
};
Ran run(const std::string& text, const std::string& name, RunOptions ro = {}) {
  const Program p = load_trace_text(text, name, {});
  std::ostringstream out;
  Ran x;
  x.r = run_program(p, ro, out);
  x.out = out.str();
  return x;
}
// The message of the load error of `text` (named t.trace), "" if it loads.
std::string load_error(const std::string& text) {
  try {
    load_trace_text(text, "t.trace", {});
  } catch (const TraceError& e) {
    return e.what();
  }
  return "";
}

struct Form {
  const char* command;
  const char* prelude;  // lines run before (may be "")
  const char* line;
};

// One minimal valid use of each command of the four areas.
const Form kForms[] = {
    // pixel path
    {"glPixelStorei", "", "glPixelStorei GL_UNPACK_ALIGNMENT 1"},
    {"glPixelStoref", "", "glPixelStoref GL_UNPACK_ROW_LENGTH 0"},
    {"glPixelTransferi", "", "glPixelTransferi GL_MAP_COLOR 0"},
    {"glPixelTransferf", "", "glPixelTransferf GL_RED_SCALE 0.5"},
    {"glPixelMapfv", "", "glPixelMapfv GL_PIXEL_MAP_R_TO_R 2 1 0"},
    {"glPixelZoom", "", "glPixelZoom 2 1"},
    {"glColorTable", "", "glColorTable GL_COLOR_TABLE GL_RGBA 2 GL_RGBA GL_FLOAT invert"},
    {"glColorTableParameterfv", "", "glColorTableParameterfv GL_COLOR_TABLE GL_COLOR_TABLE_SCALE 1 1 1 1"},
    {"glCopyColorTable", "", "glCopyColorTable GL_COLOR_TABLE GL_RGBA 0 0 4"},
    {"glConvolutionFilter1D", "", "glConvolutionFilter1D GL_CONVOLUTION_1D GL_RGBA 2 GL_RGBA GL_FLOAT src"},
    {"glConvolutionFilter2D", "", "glConvolutionFilter2D GL_CONVOLUTION_2D GL_RGBA 2 1 GL_RGBA GL_FLOAT src"},
    {"glSeparableFilter2D", "", "glSeparableFilter2D GL_SEPARABLE_2D GL_RGBA 2 2 GL_RGBA GL_FLOAT src invert"},
    {"glConvolutionParameteri", "", "glConvolutionParameteri GL_CONVOLUTION_2D GL_CONVOLUTION_BORDER_MODE GL_REDUCE"},
    {"glConvolutionParameterfv", "", "glConvolutionParameterfv GL_CONVOLUTION_2D GL_CONVOLUTION_FILTER_SCALE 1 1 1 1"},
    {"glTexImage1D", "", "glTexImage1D GL_TEXTURE_1D 0 GL_RGBA 2 0 GL_RGBA GL_FLOAT src"},
    {"glTexImage2D", "", "glTexImage2D GL_TEXTURE_2D 0 GL_RGBA 4 4 0 GL_RGBA GL_UNSIGNED_BYTE quad"},
    {"glTexSubImage1D", "glTexImage1D GL_TEXTURE_1D 0 GL_RGBA 2 0 GL_RGBA GL_FLOAT src\n",
     "glTexSubImage1D GL_TEXTURE_1D 0 0 2 GL_RGBA GL_FLOAT src"},
    {"glTexSubImage2D", "glTexImage2D GL_TEXTURE_2D 0 GL_RGBA 4 4 0 GL_RGBA GL_UNSIGNED_BYTE quad\n",
     "glTexSubImage2D GL_TEXTURE_2D 0 0 0 2 1 GL_RGBA GL_FLOAT src"},
    {"glCopyTexImage1D", "", "glCopyTexImage1D GL_TEXTURE_1D 0 GL_RGBA 0 0 4 0"},
    {"glCopyTexImage2D", "", "glCopyTexImage2D GL_TEXTURE_2D 0 GL_RGBA 0 0 4 4 0"},
    {"glCopyTexSubImage1D", "glCopyTexImage1D GL_TEXTURE_1D 0 GL_RGBA 0 0 4 0\n", "glCopyTexSubImage1D GL_TEXTURE_1D 0 0 0 0 2"},
    {"glCopyTexSubImage2D", "glCopyTexImage2D GL_TEXTURE_2D 0 GL_RGBA 0 0 4 4 0\n",
     "glCopyTexSubImage2D GL_TEXTURE_2D 0 0 0 0 0 2 2"},
    {"glDrawPixels", "", "glDrawPixels 4 4 GL_RGBA GL_UNSIGNED_BYTE quad"},
    {"glReadPixels", "", "glReadPixels 0 0 4 4 GL_RGBA GL_UNSIGNED_BYTE readback"},
    {"glCopyPixels", "", "glCopyPixels 0 0 2 1 GL_COLOR"},
    // geometry and texturing
    {"glBegin", "", "glBegin GL_QUADS"},
    {"glEnd", "glBegin GL_TRIANGLES\nglVertex2f 0 0\nglVertex2f 4 0\nglVertex2f 0 4\n", "glEnd"},
    {"glVertex2f", "glBegin GL_TRIANGLES\n", "glVertex2f 0 0"},
    {"glVertex2d", "glBegin GL_TRIANGLES\n", "glVertex2d 0 0"},
    {"glVertex3f", "glBegin GL_TRIANGLES\n", "glVertex3f 0 0 0"},
    {"glVertex3d", "glBegin GL_TRIANGLES\n", "glVertex3d 0 0 0"},
    {"glVertex4f", "glBegin GL_TRIANGLES\n", "glVertex4f 0 0 0 1"},
    {"glVertex4d", "glBegin GL_TRIANGLES\n", "glVertex4d 0 0 0 1"},
    {"glColor3f", "", "glColor3f 1 0.5 0"},
    {"glColor3d", "", "glColor3d 1 0.5 0"},
    {"glColor4f", "", "glColor4f 1 0.5 0 1"},
    {"glColor4d", "", "glColor4d 1 0.5 0 1"},
    {"glSecondaryColor3f", "", "glSecondaryColor3f 0 0 1"},
    {"glSecondaryColor3d", "", "glSecondaryColor3d 0 0 1"},
    {"glTexCoord2f", "", "glTexCoord2f 1 0"},
    {"glTexCoord2d", "", "glTexCoord2d 1 0"},
    {"glTexCoord4f", "", "glTexCoord4f 1 0 0 1"},
    {"glTexCoord4d", "", "glTexCoord4d 1 0 0 1"},
    {"glMultiTexCoord2f", "", "glMultiTexCoord2f GL_TEXTURE1 1 0"},
    {"glMultiTexCoord2d", "", "glMultiTexCoord2d GL_TEXTURE1 1 0"},
    {"glMultiTexCoord4f", "", "glMultiTexCoord4f GL_TEXTURE1 1 0 0 1"},
    {"glMultiTexCoord4d", "", "glMultiTexCoord4d GL_TEXTURE1 1 0 0 1"},
    {"glNormal3f", "", "glNormal3f 0 0 1"},
    {"glNormal3d", "", "glNormal3d 0 0 1"},
    {"glViewport", "", "glViewport 0 0 4 4"},
    {"glDepthRange", "", "glDepthRange 0 1"},
    {"glShadeModel", "", "glShadeModel GL_FLAT"},
    {"glRasterPos2f", "", "glRasterPos2f 0 0"},
    {"glRasterPos2d", "", "glRasterPos2d 0 0"},
    {"glRasterPos3f", "", "glRasterPos3f 0 0 0"},
    {"glRasterPos3d", "", "glRasterPos3d 0 0 0"},
    {"glRasterPos4f", "", "glRasterPos4f 0 0 0 1"},
    {"glRasterPos4d", "", "glRasterPos4d 0 0 0 1"},
    {"glBindTexture", "", "glBindTexture GL_TEXTURE_2D 1"},
    {"glDeleteTextures", "glBindTexture GL_TEXTURE_2D 2\nglBindTexture GL_TEXTURE_2D 0\n", "glDeleteTextures 1 2"},
    {"glTexParameteri", "", "glTexParameteri GL_TEXTURE_2D GL_TEXTURE_MIN_FILTER GL_NEAREST"},
    {"glTexParameterf", "", "glTexParameterf GL_TEXTURE_2D GL_TEXTURE_PRIORITY 1"},
    {"glTexParameterfv", "", "glTexParameterfv GL_TEXTURE_2D GL_TEXTURE_BORDER_COLOR 0 0 0 0"},
    {"glActiveTexture", "", "glActiveTexture GL_TEXTURE1"},
    {"glClientActiveTexture", "", "glClientActiveTexture GL_TEXTURE1"},
    {"glTexEnvi", "", "glTexEnvi GL_TEXTURE_ENV GL_TEXTURE_ENV_MODE GL_MODULATE"},
    {"glTexEnvf", "", "glTexEnvf GL_TEXTURE_ENV GL_RGB_SCALE 2"},
    {"glTexEnvfv", "", "glTexEnvfv GL_TEXTURE_ENV GL_TEXTURE_ENV_COLOR 0 0 0 1"},
    // per-fragment operations
    {"glAlphaFunc", "", "glAlphaFunc GL_GREATER 0.5"},
    {"glStencilFunc", "", "glStencilFunc GL_ALWAYS 0 0xFF"},
    {"glStencilOp", "", "glStencilOp GL_KEEP GL_KEEP GL_INCR_WRAP_EXT"},
    {"glDepthFunc", "", "glDepthFunc GL_LEQUAL"},
    {"glBlendFunc", "", "glBlendFunc GL_ONE GL_ONE"},
    {"glBlendEquation", "", "glBlendEquation GL_FUNC_SUBTRACT_EXT"},
    {"glBlendColor", "", "glBlendColor 0 0 0 0.5"},
    {"glLogicOp", "", "glLogicOp GL_XOR"},
    // register combiners
    {"glCombinerParameterfvNV", "", "glCombinerParameterfvNV GL_CONSTANT_COLOR0_NV 0 0.5 1 1"},
    {"glCombinerParameterfNV", "", "glCombinerParameterfNV GL_NUM_GENERAL_COMBINERS_NV 2"},
    {"glCombinerParameterivNV", "", "glCombinerParameterivNV GL_COLOR_SUM_CLAMP_NV 1"},
    {"glCombinerParameteriNV", "", "glCombinerParameteriNV GL_COLOR_SUM_CLAMP_NV GL_TRUE"},
    {"glCombinerInputNV", "", "glCombinerInputNV GL_COMBINER1_NV GL_ALPHA GL_VARIABLE_D_NV GL_TEXTURE0_ARB GL_EXPAND_NORMAL_NV GL_BLUE"},
    {"glCombinerOutputNV", "",
     "glCombinerOutputNV GL_COMBINER0_NV GL_RGB GL_SPARE0_NV GL_SPARE1_NV GL_DISCARD_NV GL_SCALE_BY_TWO_NV GL_NONE 1 0 0"},
    {"glFinalCombinerInputNV", "", "glFinalCombinerInputNV GL_VARIABLE_G_NV GL_PRIMARY_COLOR_NV GL_UNSIGNED_INVERT_NV GL_ALPHA"},
    {"glCombinerStageParameterfvNV", "", "glCombinerStageParameterfvNV GL_COMBINER0_NV GL_CONSTANT_COLOR1_NV 1 0 0 1"},
};

// The commands of the four areas: every bound command that the core file does not bind.
std::set<std::string> area_commands() {
  CommandTable core;
  register_core_commands(core);
  std::set<std::string> s;
  for (const auto& [name, d] : gl_commands().all())
    if (!core.find(name)) s.insert(name);
  return s;
}
// An alias (glActiveTextureARB) stands for the command without its suffix.
std::string base_name(const std::string& n) {
  for (const char* suffix : {"ARB", "EXT"}) {
    const std::string s(suffix);
    if (n.size() > s.size() && n.compare(n.size() - s.size(), s.size(), s) == 0) return n.substr(0, n.size() - s.size());
  }
  return n;
}
std::map<std::string, const Form*> forms_by_command() {
  std::map<std::string, const Form*> m;
  for (const auto& f : kForms) m[f.command] = &f;
  return m;
}
}  // namespace

TEST_CASE("trace bindings: every command of the four areas runs in a minimal form without a GL error") {
  const auto forms = forms_by_command();
  const auto cmds = area_commands();
  CHECK(cmds.size() >= 90);
  const std::string name = (kExamples / "t.trace").string();  // data/quad.png resolves beside the examples
  for (const auto& c : cmds) {
    CAPTURE(c);
    const auto it = forms.find(base_name(c));
    REQUIRE(it != forms.end());
    std::string line = it->second->line;
    line.replace(0, it->second->command ? std::string(it->second->command).size() : 0, c);
    const Ran x = run(V + kImages + it->second->prelude + line + "\nexpect error GL_NO_ERROR\n", name);
    CHECK(x.r.ok);
    CHECK(x.r.gl_errors.empty());
    CHECK(x.r.expect_failures.empty());
    CHECK(x.r.steps > 0);
  }
  // And no form names a command that is not bound.
  for (const auto& f : kForms) CHECK(cmds.count(f.command) == 1);
}

TEST_CASE("trace bindings: every command of the four areas appears in docs/trace-format.md") {
  std::ifstream in(fs::path(FFSIM_SOURCE_DIR) / "docs" / "trace-format.md");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string doc = ss.str();
  for (const auto& c : area_commands()) {
    CAPTURE(c);
    const std::string b = base_name(c);
    // f/d pairs are documented as glVertex2f/d.
    const bool fd = (b.back() == 'f' || b.back() == 'd') && doc.find(b.substr(0, b.size() - 1) + "f/d") != std::string::npos;
    CHECK((doc.find(std::string("| ") + b + " |") != std::string::npos || fd));
  }
}

TEST_CASE("trace bindings: enum, count and vector-size errors name their exact position") {
  CHECK(load_error(V + "glStencilOp GL_KEEP GL_KEEP GL_FROB\n") == "t.trace:2:29: unknown GL enum `GL_FROB`");
  CHECK(load_error(V + "glShadeModel GL_BLEND\n") ==
        "t.trace:2:14: `GL_BLEND` is not allowed for `mode` of glShadeModel (expected GL_FLAT or GL_SMOOTH)");
  CHECK(load_error(V + "glCombinerInputNV GL_COMBINER0_NV GL_RGB GL_VARIABLE_E_NV GL_ZERO GL_UNSIGNED_IDENTITY_NV GL_RGB\n") ==
        "t.trace:2:42: `GL_VARIABLE_E_NV` is not allowed for `variable` of glCombinerInputNV (expected GL_VARIABLE_A_NV, "
        "GL_VARIABLE_B_NV, GL_VARIABLE_C_NV or GL_VARIABLE_D_NV)");
  CHECK(load_error(V + "table src 2 x 0 0 1\nglTexImage2D GL_TEXTURE_2D 0 GL_RGBA 2 1 0 GL_RGBA GL_FLOAT\n") ==
        "t.trace:3:1: glTexImage2D takes 9 arguments (target level internalformat width height border format type "
        "pixels), got 8");
  CHECK(load_error(V + "glBlendColor 0 0 0 0 1\n") ==
        "t.trace:2:22: glBlendColor takes 4 arguments (red green blue alpha), got 5");
  CHECK(load_error(V + "glEnd 1\n") == "t.trace:2:7: glEnd takes 0 arguments, got 1");
  CHECK(load_error(V + "glTexEnvfv GL_TEXTURE_ENV GL_TEXTURE_ENV_COLOR 0 0 1\n") ==
        "t.trace:2:48: glTexEnvfv GL_TEXTURE_ENV_COLOR takes 4 values, got 3");
  CHECK(load_error(V + "glTexParameterfv GL_TEXTURE_2D GL_TEXTURE_PRIORITY 1 1\n") ==
        "t.trace:2:52: glTexParameterfv GL_TEXTURE_PRIORITY takes 1 value, got 2");
  CHECK(load_error(V + "glCombinerParameterfvNV GL_CONSTANT_COLOR1_NV 1\n") ==
        "t.trace:2:47: glCombinerParameterfvNV GL_CONSTANT_COLOR1_NV takes 4 values, got 1");
  CHECK(load_error(V + "glCombinerParameterivNV GL_NUM_GENERAL_COMBINERS_NV 1.5\n") ==
        "t.trace:2:53: the params of glCombinerParameterivNV must be integers in [-2147483648, 2147483647], got 1.5");
  CHECK(load_error(V + "glPixelMapfv GL_PIXEL_MAP_R_TO_R 4 0 0.5 1\n") ==
        "t.trace:2:36: glPixelMapfv has mapsize 4 but 3 values");
  CHECK(load_error(V + "glDeleteTextures 2 1\n") == "t.trace:2:20: glDeleteTextures has n = 2 but 1 names");
  CHECK(load_error(V + "glCopyPixels 0 0 1 1 GL_RGBA\n") ==
        "t.trace:2:22: `GL_RGBA` is not allowed for `type` of glCopyPixels (expected GL_COLOR, GL_STENCIL or GL_DEPTH)");
}

TEST_CASE("trace bindings: a client image that does not match format and type is a load error at the image") {
  const std::string t = V + "table src 2 x 0 0 1\ntable lum 3 x\n";
  // 4 float channels read as RGB (3 channels).
  CHECK(load_error(t + "glTexImage2D GL_TEXTURE_2D 0 GL_RGBA 2 1 0 GL_RGB GL_FLOAT src\n") ==
        "t.trace:4:60: image `src` has float samples and 4 channels; glTexImage2D with GL_RGB GL_FLOAT reads float "
        "samples and 3 channels");
  // Float samples read as bytes.
  CHECK(load_error(t + "glDrawPixels 2 1 GL_RGBA GL_UNSIGNED_BYTE src\n") ==
        "t.trace:4:43: image `src` has float samples and 4 channels; glDrawPixels with GL_RGBA GL_UNSIGNED_BYTE reads "
        "8-bit samples and 4 channels");
  CHECK(load_error(t + "glColorTable GL_COLOR_TABLE GL_RGBA 3 GL_LUMINANCE_ALPHA GL_FLOAT lum\n") ==
        "t.trace:4:67: image `lum` has float samples and 1 channel; glColorTable with GL_LUMINANCE_ALPHA GL_FLOAT "
        "reads float samples and 2 channels");
  // The second image of glSeparableFilter2D is checked too.
  CHECK(load_error(t + "glSeparableFilter2D GL_SEPARABLE_2D GL_RGBA 2 3 GL_RGBA GL_FLOAT src lum\n") ==
        "t.trace:4:70: image `lum` has float samples and 1 channel; glSeparableFilter2D with GL_RGBA GL_FLOAT reads "
        "float samples and 4 channels");
  // Types and formats no client image holds.
  CHECK(load_error(t + "glTexImage1D GL_TEXTURE_1D 0 GL_RGBA 2 0 GL_RGBA GL_INT src\n") ==
        "t.trace:4:50: GL_INT has no client image form (client images hold 8-bit, 16-bit or float samples: "
        "UNSIGNED_BYTE, BYTE, UNSIGNED_SHORT, SHORT or FLOAT)");
  CHECK(load_error(t + "glDrawPixels 2 1 0x1234 GL_FLOAT src\n") ==
        "t.trace:4:18: 0x1234 is not a pixel format of client images (glDrawPixels takes RED, GREEN, BLUE, ALPHA, "
        "RGB, RGBA, BGR, BGRA, LUMINANCE, LUMINANCE_ALPHA, COLOR_INDEX, STENCIL_INDEX or DEPTH_COMPONENT data)");
  CHECK(load_error(t + "glReadPixels 0 0 2 1 GL_RGBA GL_UNSIGNED_INT rb\n") ==
        "t.trace:4:30: GL_UNSIGNED_INT has no client image form (client images hold 8-bit, 16-bit or float samples: "
        "UNSIGNED_BYTE, BYTE, UNSIGNED_SHORT, SHORT or FLOAT)");
  CHECK(load_error(t + "glDrawPixels 2 1 GL_RGBA GL_FLOAT nothing\n") ==
        "t.trace:4:35: unknown image `nothing` (define it with image, generate or table)");
}

TEST_CASE("trace bindings: glReadPixels client memory keeps one shape and is not a file image") {
  const std::string t = V + "table src 2 x 0 0 1\nglReadPixels 0 0 2 2 GL_RGBA GL_FLOAT rb\n";
  CHECK(load_error(t + "glReadPixels 0 0 2 2 GL_RGBA GL_FLOAT rb\n").empty());
  CHECK(load_error(t + "glReadPixels 0 0 3 2 GL_RGBA GL_FLOAT rb\n") ==
        "t.trace:4:39: client image `rb` is 2x2 float with 4 channels (declared at t.trace:3:39); glReadPixels here "
        "writes 3x2 float with 4 channels");
  CHECK(load_error(t + "glReadPixels 0 0 2 1 GL_RGBA GL_FLOAT src\n") ==
        "t.trace:4:39: image `src` (table at t.trace:2:7) is not client memory glReadPixels may write; name a new image");
  CHECK(load_error(t + "table rb 2 x\n") == "t.trace:4:7: image `rb` is already defined at t.trace:3:39");
  CHECK(load_error(t + "dump image nothing a.png\n") ==
        "t.trace:4:12: unknown image `nothing` (define it with image, generate, table or glReadPixels)");
  CHECK(load_error(t + "dump image rb\n") == "t.trace:4:14: `dump` needs more arguments: dump image NAME FILE");
}

TEST_CASE("trace bindings: glReadPixels fills client memory that glDrawPixels and dump image read at run time") {
  // Clear to red, read it back, clear to blue, draw the read-back: red again.
  const std::string t = V +
                        "framebuffer 4 4\n"
                        "glClearColor 1 0 0 1\n"
                        "glClear GL_COLOR_BUFFER_BIT\n"
                        "glReadPixels 0 0 4 4 GL_RGBA GL_UNSIGNED_BYTE rb\n"
                        "dump image rb rb.png\n"
                        "glClearColor 0 0 1 1\n"
                        "glClear GL_COLOR_BUFFER_BIT\n"
                        "expect pixel 1 1 color 0 0 1 1\n"
                        "glDrawPixels 4 4 GL_RGBA GL_UNSIGNED_BYTE rb\n"
                        "expect pixel 1 1 color 1 0 0 1\n";
  RunOptions ro;
  ro.keep_images = true;
  const Ran x = run(t, "t.trace", ro);
  CHECK(x.r.ok);
  CHECK(x.r.gl_errors.empty());
  CHECK(x.r.expect_failures.empty());
  REQUIRE(x.r.images.count("rb.png") == 1);
  const Image& im = x.r.images.at("rb.png");
  CHECK(im.width == 4);
  CHECK(im.channels == 4);
  CHECK(im.type == SampleType::U8);
  CHECK(im.u8[im.index(3, 3, 0)] == 255);
  CHECK(im.u8[im.index(3, 3, 2)] == 0);
  // expect image checks client memory as it is when the line runs.
  const Ran e = run(V + "framebuffer 2 1\nglClearColor 0 0.2 1 0.2\nglClear GL_COLOR_BUFFER_BIT\n"
                        "glReadPixels 0 0 2 1 GL_LUMINANCE_ALPHA GL_UNSIGNED_BYTE la\n"
                        "expect image la 1 0 1 51/255\n"   // L = R + G + B = 1.2 clamped to 1 (GL121 §4.3.2), A = 51
                        "glClearColor 0 0 0 0\nglClear GL_COLOR_BUFFER_BIT\nexpect image la 1 0 0 0\n",
                    "t.trace");
  REQUIRE(e.r.expect_failures.size() == 1);
  CHECK(e.r.expect_failures[0] == "t.trace:9:1: expect image la 1 0: got (1, 0.2), expected (0, 0) (tol 0)");
  CHECK(load_error(V + "table t 2 x\nexpect image t 2 0 1\n") == "t.trace:3:16: x must be in [0, 1], got 2");
  CHECK(load_error(V + "table t 2 x\nexpect image t 1 0 1 1\n") == "t.trace:3:22: too many values: image `t` has 1 channel");
}

TEST_CASE("trace bindings: an image too small for the unpack modes stops the replay at the call") {
  // 3 float luminance samples = 12 bytes; SKIP_PIXELS 1 makes glTexImage1D read 16.
  const Ran x = run(V + "table lum 3 x\nglPixelStorei GL_UNPACK_SKIP_PIXELS 1\nglTexImage1D GL_TEXTURE_1D 0 GL_LUMINANCE 3 0 GL_LUMINANCE GL_FLOAT lum\n",
                    "t.trace");
  CHECK_FALSE(x.r.ok);
  CHECK(x.r.fatal ==
        "t.trace:4:69: glTexImage1D reads 16 bytes of image `lum` under the current unpack modes, but it holds 12 (3x1 "
        "with tightly packed rows; GL_UNPACK_ALIGNMENT 1 reads such rows)");
  // 4x4 RGBA bytes: rows of 16 bytes, which alignment 4 reads exactly.
  const Ran ok = run(V + kImages + "glTexImage2D GL_TEXTURE_2D 0 GL_RGBA 4 4 0 GL_RGBA GL_UNSIGNED_BYTE quad\n",
                     (kExamples / "t.trace").string());
  CHECK(ok.r.ok);
  // glReadPixels of 3 RGB bytes per row under PACK_ALIGNMENT 4 addresses 4 + 3 bytes
  // for two rows, more than the 6 of the 1x2 image.
  const Ran rd = run(V + "framebuffer 4 4\nglReadPixels 0 0 1 2 GL_RGB GL_UNSIGNED_BYTE rb\n", "t.trace");
  CHECK_FALSE(rd.r.ok);
  CHECK(rd.r.fatal ==
        "t.trace:3:46: glReadPixels writes 7 bytes into image `rb` under the current pack modes, but it holds 6 "
        "(tightly packed rows; GL_PACK_ALIGNMENT 1 writes such rows)");
  const Ran rd1 = run(V + "framebuffer 4 4\nglPixelStorei GL_PACK_ALIGNMENT 1\nglReadPixels 0 0 1 2 GL_RGB GL_UNSIGNED_BYTE rb\n", "t.trace");
  CHECK(rd1.r.ok);
}

TEST_CASE("trace bindings: GL errors of bound calls are reported with their trace line") {
  const Ran x = run(V +
                        "table src 2 x 0 0 1\n"
                        "glTexImage2D GL_TEXTURE_3D 0 GL_RGBA 2 1 0 GL_RGBA GL_FLOAT src\n"
                        "glCombinerInputNV GL_COMBINER7_NV GL_RGB GL_VARIABLE_A_NV GL_ZERO GL_UNSIGNED_IDENTITY_NV GL_RGB\n"
                        "glActiveTexture GL_TEXTURE3\n"
                        "glViewport 0 0 -1 4\n",
                    "t.trace");
  CHECK(x.r.ok);
  REQUIRE(x.r.gl_errors.size() == 4);
  CHECK(x.r.gl_errors[0] == "t.trace:3:1: glTexImage2D: GL_INVALID_ENUM: target must be GL_TEXTURE_2D (got GL_TEXTURE_3D)");
  CHECK(x.r.gl_errors[1] == "t.trace:4:1: glCombinerInputNV: GL_INVALID_ENUM: GL_COMBINER7_NV is not COMBINER0_NV .. COMBINER1_NV");
  CHECK(x.r.gl_errors[2].rfind("t.trace:5:1: glActiveTexture: GL_INVALID_ENUM: ", 0) == 0);
  CHECK(x.r.gl_errors[3] == "t.trace:6:1: glViewport: GL_INVALID_VALUE: negative width or height");
}

TEST_CASE("trace bindings: the combiner example's two stages give the hand-derived colour") {
  // traces/examples/combiners.trace derives (102, 255, 0, 255) for primary (1, 1, 0, 1).
  const Program p = load_trace_file((kExamples / "combiners.trace").string(), {});
  Context ctx(p.profile, p.width, p.height);
  std::ostringstream out;
  const RunResult r = run_program_on(ctx, p, {}, out);
  REQUIRE(r.ok);
  CHECK(r.gl_errors.empty());
  const combiners::CombinerPlan& plan = ctx.combiner_plan();
  CHECK(plan.primary_needed);
  const std::array<std::uint16_t, 4> primary{255, 255, 0, 255};
  combiners::CombinerInputsFixed in;
  in.count = 1;
  in.primary = primary.data();
  std::array<std::uint16_t, 4> got{};
  combiners::shade_span(plan, in, {0, 0, 0, 0}, got.data());
  CHECK(got == std::array<std::uint16_t, 4>{102, 255, 0, 255});
}

TEST_CASE("trace bindings: --explain prints each area's plan for the passes it concerns") {
  RunOptions ro;
  ro.explain = true;
  const Ran c = run(V + "framebuffer 2 2\n"
                        "glCombinerInputNV GL_COMBINER0_NV GL_RGB GL_VARIABLE_A_NV GL_PRIMARY_COLOR_NV GL_UNSIGNED_IDENTITY_NV GL_RGB\n"
                        "glEnable GL_REGISTER_COMBINERS_NV\n"
                        "glBegin GL_TRIANGLES\nglVertex2f -1 -1\nglVertex2f 1 -1\nglVertex2f -1 1\nglEnd\n"
                        "glDisable GL_REGISTER_COMBINERS_NV\n"
                        "glBegin GL_TRIANGLES\nglVertex2f -1 -1\nglVertex2f 1 -1\nglVertex2f -1 1\nglEnd\n"
                        "glClear GL_COLOR_BUFFER_BIT\n"
                        "table src 1 1 1 1 1\nglDrawPixels 1 1 GL_RGBA GL_FLOAT src\n",
                    "t.trace", ro);
  CHECK(c.r.ok);
  const std::string& o = c.out;
  const auto pass2 = o.find("pass 2:"), pass3 = o.find("pass 3:"), pass4 = o.find("pass 4:");
  REQUIRE(pass2 != std::string::npos);
  REQUIRE(pass3 != std::string::npos);
  REQUIRE(pass4 != std::string::npos);
  const std::string p1 = o.substr(0, pass2), p2 = o.substr(pass2, pass3 - pass2), p3 = o.substr(pass3, pass4 - pass3),
                    p4 = o.substr(pass4);
  CHECK(p1.find("  combiners: stage 0 rgb:") != std::string::npos);  // enabled
  CHECK(p1.find("  shading: texture unit 0: off") != std::string::npos);
  CHECK(p1.find("  fragment: per-fragment operations") != std::string::npos);
  CHECK(p1.find("  pixel transfer:") == std::string::npos);           // not a pixel rectangle
  CHECK(p2.find("  combiners:") == std::string::npos);                // disabled
  CHECK(p3.find("  fragment:") == std::string::npos);                 // glClear: only the writes
  CHECK(p3.find("  framebuffer: clear color") != std::string::npos);
  CHECK(p4.find("  pixel transfer: raster position (0, 0), zoom 1 x 1") != std::string::npos);
  CHECK(p4.find("  pixel transfer: identity") != std::string::npos);
  const Ran st = run(V + "framebuffer 2 2\nglCopyPixels 0 0 1 1 GL_STENCIL\n", "t.trace", ro);
  CHECK(st.out.find("  pixel transfer: stencil indices: no colour transfer") != std::string::npos);
  // Texture uploads are not passes; --explain reports their transfer plan after the call.
  const Ran up = run(V + "framebuffer 2 2\ntable src 2 x 0 0 1\nglPixelTransferf GL_RED_SCALE 0.5\n"
                         "glTexImage2D GL_TEXTURE_2D 0 GL_RGBA 2 1 0 GL_RGBA GL_FLOAT src\n",
                     "t.trace", ro);
  CHECK(up.r.passes == 0);
  CHECK(up.out.rfind("call: glTexImage2D at t.trace:5:1 (not a pass)\n  pixel transfer: ", 0) == 0);
  CHECK(up.out.find("identity") == std::string::npos);  // the scale is a stage of the plan
  CHECK(up.out.find("  framebuffer:") == std::string::npos);
  CHECK(up.out.find("  fragment:") == std::string::npos);
}

TEST_CASE("trace bindings: expect enabled follows glEnable and glDisable of every area's capabilities") {
  const char* caps[] = {"GL_COLOR_TABLE", "GL_POST_CONVOLUTION_COLOR_TABLE", "GL_POST_COLOR_MATRIX_COLOR_TABLE",
                        "GL_CONVOLUTION_1D", "GL_CONVOLUTION_2D", "GL_SEPARABLE_2D", "GL_TEXTURE_1D", "GL_TEXTURE_2D",
                        "GL_ALPHA_TEST", "GL_STENCIL_TEST", "GL_DEPTH_TEST", "GL_BLEND", "GL_COLOR_LOGIC_OP",
                        "GL_REGISTER_COMBINERS_NV", "GL_PER_STAGE_CONSTANTS_NV"};
  for (const char* cap : caps) {
    CAPTURE(cap);
    const std::string c(cap);
    const Ran x = run(V + "expect enabled " + c + " 0\nglEnable " + c + "\nexpect enabled " + c + " 1\nglDisable " + c +
                          "\nexpect enabled " + c + " 0\n",
                      "t.trace");
    CHECK(x.r.ok);
    CHECK(x.r.gl_errors.empty());
    CHECK(x.r.expect_failures.empty());
  }
  // Texture enables belong to the active unit.
  const Ran u = run(V + "glActiveTexture GL_TEXTURE1\nglEnable GL_TEXTURE_2D\nexpect enabled GL_TEXTURE_2D 1\n"
                        "glActiveTexture GL_TEXTURE0\nexpect enabled GL_TEXTURE_2D 0\n",
                    "t.trace");
  CHECK(u.r.expect_failures.empty());
  CHECK(u.r.gl_errors.empty());
}

TEST_CASE("trace bindings: a scalar call from its packed arguments gets what the Args path gives") {
  // The replay calls bound methods whose parameters are all scalars straight from
  // the packed arguments (CommandDef::packed_call, docs/performance.md 16): the
  // conversions must be convert's, for every argument kind and parameter type.
  std::mt19937_64 g(7);
  const ArgKind kinds[] = {ArgKind::Enum, ArgKind::Int, ArgKind::Float, ArgKind::Float32, ArgKind::Bool, ArgKind::Bitfield};
  const double specials[] = {0.0, -0.0, 1e300, -1e-310, INFINITY, -INFINITY, NAN, 0.5, -3.75};
  auto same = [](auto a, auto b) {
    if constexpr (std::is_floating_point_v<decltype(a)>) return std::memcmp(&a, &b, sizeof a) == 0;
    else return a == b;
  };
  for (int it = 0; it < 20000; ++it) {
    ArgValue v;
    v.kind = kinds[g() % std::size(kinds)];
    v.i = static_cast<std::int64_t>(g() % 3 == 0 ? g() : g() % 2001) - (g() % 2 ? 1000 : 0);
    v.f = g() % 3 == 0 ? specials[g() % std::size(specials)] : std::ldexp(static_cast<double>(g() % 100000) - 50000, static_cast<int>(g() % 40) - 20);
    const std::vector<ArgValue> vs{v};
    const Args args(vs);
    const PackedArg p{v.kind, v.i, v.f};
    CAPTURE(it);
    CHECK(same(detail::convert<bool>(args, 0), detail::convert_packed<bool>(p)));
    CHECK(same(detail::convert<int>(args, 0), detail::convert_packed<int>(p)));
    CHECK(same(detail::convert<GLenum>(args, 0), detail::convert_packed<GLenum>(p)));
    CHECK(same(detail::convert<float>(args, 0), detail::convert_packed<float>(p)));
    CHECK(same(detail::convert<double>(args, 0), detail::convert_packed<double>(p)));
  }
  // Set on the scalar bindings only, and the call reaches the method with them.
  const CommandTable& t = gl_commands();
  REQUIRE(t.find("glViewport"));
  REQUIRE(t.find("glTexImage2D"));
  CHECK(bool(t.find("glViewport")->packed_call));
  CHECK(bool(t.find("glVertex3d")->packed_call));
  CHECK(!t.find("glTexImage2D")->packed_call);  // an image argument
  Context a(Profile{}, 8, 8), b(Profile{}, 8, 8);
  const CommandDef& vp = *t.find("glViewport");
  std::vector<ArgValue> args(4);
  std::vector<PackedArg> packed;
  const std::int64_t box[4] = {1, -2, 5, 7};
  for (std::size_t k = 0; k < 4; ++k) {
    args[k].kind = ArgKind::Int;
    args[k].i = box[k];
    packed.push_back({ArgKind::Int, box[k], 0.0});
  }
  vp.call(a, Args(args));
  vp.packed_call(b, packed.data(), vp.method);
  CHECK(a.viewport_box() == std::array<int, 4>{1, -2, 5, 7});
  CHECK(b.viewport_box() == a.viewport_box());
}

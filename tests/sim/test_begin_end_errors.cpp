// GL121 §2.6.3: between glBegin and glEnd only vertex attribute commands are
// allowed; any other command raises INVALID_OPERATION and has no other effect.
#include <doctest/doctest.h>

#include <functional>
#include <string>
#include <vector>

#include "draw_test_util.h"

using namespace ffsim;
using namespace ffsim::test;

TEST_CASE("begin/end: state commands of every area raise INVALID_OPERATION and change nothing") {
  const float cc[4] = {0.5f, 0.5f, 0.5f, 0.5f};
  const std::uint8_t px[4] = {1, 2, 3, 4};
  struct Call {
    const char* name;
    std::function<void(Context&)> run;
    std::function<bool(Context&)> unchanged;  // checked after glEnd
  };
  const std::vector<Call> calls = {
      {"glClearColor", [](Context& c) { c.clearColor(1, 1, 1, 1); }, [](Context& c) { return c.clear_state().color[0] == 0; }},
      {"glColorMask", [](Context& c) { c.colorMask(false, false, false, false); }, [](Context& c) { return c.write_masks().color[0]; }},
      {"glClear", [](Context& c) { c.clear(gl::COLOR_BUFFER_BIT); }, [](Context&) { return true; }},
      {"glEnable", [](Context& c) { c.enable(gl::BLEND); }, [](Context& c) { return !c.isEnabled(gl::BLEND); }},
      {"glMatrixMode", [](Context& c) { c.matrixMode(gl::COLOR); }, [](Context& c) { return c.matrix_mode() == gl::MODELVIEW; }},
      {"glBlendEquation", [](Context& c) { c.blendEquation(gl::FUNC_SUBTRACT); }, [](Context&) { return true; }},
      {"glAlphaFunc", [](Context& c) { c.alphaFunc(gl::EQUAL, 0); }, [](Context&) { return true; }},
      {"glCombinerParameterfvNV", [&](Context& c) { c.combinerParameterfv(gl::CONSTANT_COLOR0_NV, cc); },
       [](Context&) { return true; }},
      {"glPixelZoom", [](Context& c) { c.pixelZoom(2, 2); }, [](Context&) { return true; }},
      {"glDrawPixels", [&](Context& c) { c.drawPixels(1, 1, gl::RGBA, gl::UNSIGNED_BYTE, px); },
       [](Context& c) { return code_at(c, 0, 0, 0) == 0; }},
  };
  for (const Call& call : calls) {
    Context ctx(profile_named("geforce256"), 4, 4);
    std::vector<std::string> seen;
    ctx.set_error_callback([&](const GLErrorEvent& e) { seen.push_back(e.str()); });
    ctx.begin(gl::TRIANGLES);
    call.run(ctx);
    ctx.end();
    INFO(call.name);
    REQUIRE(seen.size() == 1);
    CHECK(seen[0] == std::string(call.name) + ": GL_INVALID_OPERATION: not allowed between glBegin and glEnd");
    CHECK(ctx.getError() == gl::INVALID_OPERATION);
    CHECK(call.unchanged(ctx));
  }
}

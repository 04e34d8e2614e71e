// Trace commands for the pixel path (GL121 §3.6, §3.8.1-3.8.2, §4.3, imaging
// subset): pixel store, transfer, maps and zoom; colour tables and convolution
// filters; texture images; DrawPixels, ReadPixels, CopyPixels. Calls taking pixels
// take a client image (sim/trace/command_util.h); glReadPixels writes one.
#include "sim/trace/binder.h"
#include "sim/trace/command_util.h"

namespace ffsim::trace {

namespace {
int i32(const Args& a, std::size_t k) { return static_cast<int>(a.int_at(k)); }
}  // namespace

void register_pixels_commands(CommandTable& t) {
  // §3.6.1 pixel storage modes (SWAP_BYTES and LSB_FIRST take 0/1), §3.6.3 transfer modes.
  t.bind("glPixelStorei", &Context::pixelStorei, {Enum("pname"), Int("param")});
  t.bind("glPixelStoref", &Context::pixelStoref, {Enum("pname"), Float32("param")});
  t.bind("glPixelTransferi", &Context::pixelTransferi, {Enum("pname"), Int("param")});
  t.bind("glPixelTransferf", &Context::pixelTransferf, {Enum("pname"), Float32("param")});
  // glPixelMapfv map mapsize values...: exactly mapsize values (GLfloat).
  t.bind("glPixelMapfv", &Context::pixelMapfv, {Enum("map"), Int("mapsize"), Numbers("values", 0, true)})
      .checked([](const std::vector<ArgValue>& a) -> std::optional<ArgProblem> {
        if (static_cast<std::int64_t>(a[2].list.size()) == a[1].i) return std::nullopt;
        return ArgProblem{2, cat("glPixelMapfv has mapsize ", std::to_string(a[1].i), " but ",
                                 std::to_string(a[2].list.size()), " values")};
      });
  t.bind("glPixelZoom", &Context::pixelZoom, {Float32("xfactor"), Float32("yfactor")});

  // Imaging subset: colour tables (§3.6.3 "Color Table Specification").
  t.add("glColorTable", {Enum("target"), Enum("internalformat"), Int("width"), Enum("format"), Enum("type"), ClientImage("table")},
        [](Context& c, const Args& a) {
          c.colorTable(a.enum_at(0), a.enum_at(1), i32(a, 2), a.enum_at(3), a.enum_at(4),
                       unpack_source(c, a, 5, i32(a, 2), 1, a.enum_at(3), a.enum_at(4), "glColorTable"));
        })
      .checked([](const std::vector<ArgValue>& a) { return check_client_image(a, 3, 4, 5, "glColorTable"); });
  t.bind("glColorTableParameterfv", &Context::colorTableParameterfv, {Enum("target"), Enum("pname"), Numbers("params", 4, true)});
  t.bind("glCopyColorTable", &Context::copyColorTable, {Enum("target"), Enum("internalformat"), Int("x"), Int("y"), Int("width")});

  // Convolution filters.
  t.add("glConvolutionFilter1D", {Enum("target"), Enum("internalformat"), Int("width"), Enum("format"), Enum("type"), ClientImage("image")},
        [](Context& c, const Args& a) {
          c.convolutionFilter1D(a.enum_at(0), a.enum_at(1), i32(a, 2), a.enum_at(3), a.enum_at(4),
                                unpack_source(c, a, 5, i32(a, 2), 1, a.enum_at(3), a.enum_at(4), "glConvolutionFilter1D"));
        })
      .checked([](const std::vector<ArgValue>& a) { return check_client_image(a, 3, 4, 5, "glConvolutionFilter1D"); });
  t.add("glConvolutionFilter2D",
        {Enum("target"), Enum("internalformat"), Int("width"), Int("height"), Enum("format"), Enum("type"), ClientImage("image")},
        [](Context& c, const Args& a) {
          c.convolutionFilter2D(a.enum_at(0), a.enum_at(1), i32(a, 2), i32(a, 3), a.enum_at(4), a.enum_at(5),
                                unpack_source(c, a, 6, i32(a, 2), i32(a, 3), a.enum_at(4), a.enum_at(5), "glConvolutionFilter2D"));
        })
      .checked([](const std::vector<ArgValue>& a) { return check_client_image(a, 4, 5, 6, "glConvolutionFilter2D"); });
  t.add("glSeparableFilter2D",
        {Enum("target"), Enum("internalformat"), Int("width"), Int("height"), Enum("format"), Enum("type"), ClientImage("row"),
         ClientImage("column")},
        [](Context& c, const Args& a) {
          const void* row = unpack_source(c, a, 6, i32(a, 2), 1, a.enum_at(4), a.enum_at(5), "glSeparableFilter2D");
          const void* column = unpack_source(c, a, 7, i32(a, 3), 1, a.enum_at(4), a.enum_at(5), "glSeparableFilter2D");
          c.separableFilter2D(a.enum_at(0), a.enum_at(1), i32(a, 2), i32(a, 3), a.enum_at(4), a.enum_at(5), row, column);
        })
      .checked([](const std::vector<ArgValue>& a) {
        auto p = check_client_image(a, 4, 5, 6, "glSeparableFilter2D");
        return p ? p : check_client_image(a, 4, 5, 7, "glSeparableFilter2D");
      });
  // CONVOLUTION_BORDER_MODE takes a token (REDUCE, CONSTANT_BORDER, REPLICATE_BORDER).
  t.bind("glConvolutionParameteri", &Context::convolutionParameteri, {Enum("target"), Enum("pname"), Enum("param")});
  t.bind("glConvolutionParameterfv", &Context::convolutionParameterfv, {Enum("target"), Enum("pname"), Numbers("params", 4, true)});

  // §3.8.1 texture images (internalformat may be 1..4 or a token).
  t.add("glTexImage1D",
        {Enum("target"), Int("level"), Enum("internalformat"), Int("width"), Int("border"), Enum("format"), Enum("type"),
         ClientImage("pixels")},
        [](Context& c, const Args& a) {
          c.texImage1D(a.enum_at(0), i32(a, 1), a.enum_at(2), i32(a, 3), i32(a, 4), a.enum_at(5), a.enum_at(6),
                       unpack_source(c, a, 7, i32(a, 3), 1, a.enum_at(5), a.enum_at(6), "glTexImage1D"));
        })
      .checked([](const std::vector<ArgValue>& a) { return check_client_image(a, 5, 6, 7, "glTexImage1D"); })
      .explain_after();
  t.add("glTexImage2D",
        {Enum("target"), Int("level"), Enum("internalformat"), Int("width"), Int("height"), Int("border"), Enum("format"),
         Enum("type"), ClientImage("pixels")},
        [](Context& c, const Args& a) {
          c.texImage2D(a.enum_at(0), i32(a, 1), a.enum_at(2), i32(a, 3), i32(a, 4), i32(a, 5), a.enum_at(6), a.enum_at(7),
                       unpack_source(c, a, 8, i32(a, 3), i32(a, 4), a.enum_at(6), a.enum_at(7), "glTexImage2D"));
        })
      .checked([](const std::vector<ArgValue>& a) { return check_client_image(a, 6, 7, 8, "glTexImage2D"); })
      .explain_after();
  t.add("glTexSubImage1D",
        {Enum("target"), Int("level"), Int("xoffset"), Int("width"), Enum("format"), Enum("type"), ClientImage("pixels")},
        [](Context& c, const Args& a) {
          c.texSubImage1D(a.enum_at(0), i32(a, 1), i32(a, 2), i32(a, 3), a.enum_at(4), a.enum_at(5),
                          unpack_source(c, a, 6, i32(a, 3), 1, a.enum_at(4), a.enum_at(5), "glTexSubImage1D"));
        })
      .checked([](const std::vector<ArgValue>& a) { return check_client_image(a, 4, 5, 6, "glTexSubImage1D"); })
      .explain_after();
  t.add("glTexSubImage2D",
        {Enum("target"), Int("level"), Int("xoffset"), Int("yoffset"), Int("width"), Int("height"), Enum("format"),
         Enum("type"), ClientImage("pixels")},
        [](Context& c, const Args& a) {
          c.texSubImage2D(a.enum_at(0), i32(a, 1), i32(a, 2), i32(a, 3), i32(a, 4), i32(a, 5), a.enum_at(6), a.enum_at(7),
                          unpack_source(c, a, 8, i32(a, 4), i32(a, 5), a.enum_at(6), a.enum_at(7), "glTexSubImage2D"));
        })
      .checked([](const std::vector<ArgValue>& a) { return check_client_image(a, 6, 7, 8, "glTexSubImage2D"); })
      .explain_after();
  // §3.8.2 copies from the colour buffer into textures (not passes: the framebuffer is only read).
  t.bind("glCopyTexImage1D", &Context::copyTexImage1D,
         {Enum("target"), Int("level"), Enum("internalformat"), Int("x"), Int("y"), Int("width"), Int("border")})
      .explain_after();
  t.bind("glCopyTexImage2D", &Context::copyTexImage2D,
         {Enum("target"), Int("level"), Enum("internalformat"), Int("x"), Int("y"), Int("width"), Int("height"), Int("border")})
      .explain_after();
  t.bind("glCopyTexSubImage1D", &Context::copyTexSubImage1D,
         {Enum("target"), Int("level"), Int("xoffset"), Int("x"), Int("y"), Int("width")})
      .explain_after();
  t.bind("glCopyTexSubImage2D", &Context::copyTexSubImage2D,
         {Enum("target"), Int("level"), Int("xoffset"), Int("yoffset"), Int("x"), Int("y"), Int("width"), Int("height")})
      .explain_after();

  // §3.6.4, §4.3.2, §4.3.3 pixel rectangles.
  t.add("glDrawPixels", {Int("width"), Int("height"), Enum("format"), Enum("type"), ClientImage("pixels")},
        [](Context& c, const Args& a) {
          c.drawPixels(i32(a, 0), i32(a, 1), a.enum_at(2), a.enum_at(3),
                       unpack_source(c, a, 4, i32(a, 0), i32(a, 1), a.enum_at(2), a.enum_at(3), "glDrawPixels"));
        })
      .checked([](const std::vector<ArgValue>& a) { return check_client_image(a, 2, 3, 4, "glDrawPixels"); })
      .pass();
  // glReadPixels x y width height format type NAME: NAME is client memory of
  // width x height groups (declared here, zero until read), usable afterwards as an
  // image argument and by `dump image NAME FILE`.
  t.add("glReadPixels",
        {Int("x"), Int("y"), Int("width", -2147483648ll, kMaxFramebufferSide), Int("height", -2147483648ll, kMaxFramebufferSide),
         Enum("format"), Enum("type"), ClientImageOut("pixels")},
        [](Context& c, const Args& a) {
          Image& im = a.out_image_at(6);
          const std::size_t need = c.pixel_client_bytes(true, i32(a, 2), i32(a, 3), a.enum_at(4), a.enum_at(5));
          const std::size_t have = image_bytes(im);
          if (need > have)
            throw TraceError(a.where_at(6), cat("glReadPixels writes ", std::to_string(need), " bytes into image `", a[6].text,
                                                "` under the current pack modes, but it holds ", std::to_string(have),
                                                " (tightly packed rows; GL_PACK_ALIGNMENT 1 writes such rows)"));
          void* data = im.type == SampleType::U8    ? static_cast<void*>(im.u8.data())
                       : im.type == SampleType::U16 ? static_cast<void*>(im.u16.data())
                                                    : static_cast<void*>(im.f32.data());
          c.readPixels(i32(a, 0), i32(a, 1), i32(a, 2), i32(a, 3), a.enum_at(4), a.enum_at(5), data);
        })
      .checked([](const std::vector<ArgValue>& a) -> std::optional<ArgProblem> {
        const GLenum f = static_cast<GLenum>(a[4].i), ty = static_cast<GLenum>(a[5].i);
        if (client_format_channels(f) == 0)
          return ArgProblem{4, cat(gl::enum_name(f), " is not a pixel format of client images (glReadPixels takes RED, GREEN,"
                                                     " BLUE, ALPHA, RGB, RGBA, BGR, BGRA, LUMINANCE, LUMINANCE_ALPHA,"
                                                     " COLOR_INDEX, STENCIL_INDEX or DEPTH_COMPONENT)")};
        if (!client_sample_type(ty))
          return ArgProblem{5, cat(gl::enum_name(ty), " has no client image form (client images hold 8-bit, 16-bit or float"
                                                      " samples: UNSIGNED_BYTE, BYTE, UNSIGNED_SHORT, SHORT or FLOAT)")};
        return std::nullopt;
      })
      .writes_image([](const std::vector<ArgValue>& a) {
        return client_image_for(static_cast<int>(a[2].i), static_cast<int>(a[3].i), static_cast<GLenum>(a[4].i),
                                static_cast<GLenum>(a[5].i));
      });
  t.bind("glCopyPixels", &Context::copyPixels, {Int("x"), Int("y"), Int("width"), Int("height"), Enum("type", {gl::COLOR, gl::STENCIL, gl::DEPTH})})
      .pass();
}

}  // namespace ffsim::trace

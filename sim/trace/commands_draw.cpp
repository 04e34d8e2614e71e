// Trace commands for geometry, rasterization and texturing (GL121 §2.6-§2.12,
// §3.8, ARB_multitexture, EXT_secondary_color, ARB/EXT_texture_env_combine and
// _dot3): immediate mode (primitives are drawn at glEnd, the pass), viewport,
// depth range, shade model, raster position, texture objects and parameters,
// texture units and environments. The f forms round their arguments to binary32
// as the C call would, the d forms do not.
#include "sim/trace/binder.h"
#include "sim/trace/command_util.h"

namespace ffsim::trace {

void register_draw_commands(CommandTable& t) {
  // §2.6 begin/end: the primitive is assembled and drawn at glEnd.
  t.bind("glBegin", &Context::begin, {Enum("mode")}).vertex_data_call();
  t.bind("glEnd", &Context::end, {}).pass().vertex_data_call();

  // §2.7 vertex and current values.
  t.bind("glVertex2f", &Context::vertex2, {Float32("x"), Float32("y")}).vertex_data_call().quiet().vertex();
  t.bind("glVertex2d", &Context::vertex2, {Float("x"), Float("y")}).vertex_data_call().quiet().vertex();
  t.bind("glVertex3f", &Context::vertex3, {Float32("x"), Float32("y"), Float32("z")}).vertex_data_call().quiet().vertex();
  t.bind("glVertex3d", &Context::vertex3, {Float("x"), Float("y"), Float("z")}).vertex_data_call().quiet().vertex();
  t.bind("glVertex4f", &Context::vertex4, {Float32("x"), Float32("y"), Float32("z"), Float32("w")}).vertex_data_call().quiet().vertex();
  t.bind("glVertex4d", &Context::vertex4, {Float("x"), Float("y"), Float("z"), Float("w")}).vertex_data_call().quiet().vertex();
  t.bind("glColor3f", &Context::color3, {Float32("red"), Float32("green"), Float32("blue")}).vertex_data_call().quiet().sets(kAttribColor);
  t.bind("glColor3d", &Context::color3, {Float("red"), Float("green"), Float("blue")}).vertex_data_call().quiet().sets(kAttribColor);
  t.bind("glColor4f", &Context::color4, {Float32("red"), Float32("green"), Float32("blue"), Float32("alpha")}).vertex_data_call().quiet().sets(kAttribColor);
  t.bind("glColor4d", &Context::color4, {Float("red"), Float("green"), Float("blue"), Float("alpha")}).vertex_data_call().quiet().sets(kAttribColor);
  t.bind("glSecondaryColor3f", &Context::secondaryColor3, {Float32("red"), Float32("green"), Float32("blue")}).vertex_data_call().quiet().sets(kAttribSecondary);
  t.bind("glSecondaryColor3d", &Context::secondaryColor3, {Float("red"), Float("green"), Float("blue")}).vertex_data_call().quiet().sets(kAttribSecondary);
  t.alias("glSecondaryColor3fEXT", "glSecondaryColor3f");
  t.alias("glSecondaryColor3dEXT", "glSecondaryColor3d");
  t.bind("glTexCoord2f", &Context::texCoord2, {Float32("s"), Float32("t")}).vertex_data_call().quiet().sets(kAttribTexCoord0);
  t.bind("glTexCoord2d", &Context::texCoord2, {Float("s"), Float("t")}).vertex_data_call().quiet().sets(kAttribTexCoord0);
  t.bind("glTexCoord4f", &Context::texCoord4, {Float32("s"), Float32("t"), Float32("r"), Float32("q")}).vertex_data_call().quiet().sets(kAttribTexCoord0);
  t.bind("glTexCoord4d", &Context::texCoord4, {Float("s"), Float("t"), Float("r"), Float("q")}).vertex_data_call().quiet().sets(kAttribTexCoord0);
  t.bind("glMultiTexCoord2f", &Context::multiTexCoord2, {Enum("texture"), Float32("s"), Float32("t")}).vertex_data_call().quiet_with_unit().sets_unit_coordinates();
  t.bind("glMultiTexCoord2d", &Context::multiTexCoord2, {Enum("texture"), Float("s"), Float("t")}).vertex_data_call().quiet_with_unit().sets_unit_coordinates();
  t.bind("glMultiTexCoord4f", &Context::multiTexCoord4, {Enum("texture"), Float32("s"), Float32("t"), Float32("r"), Float32("q")}).vertex_data_call().quiet_with_unit().sets_unit_coordinates();
  t.bind("glMultiTexCoord4d", &Context::multiTexCoord4, {Enum("texture"), Float("s"), Float("t"), Float("r"), Float("q")}).vertex_data_call().quiet_with_unit().sets_unit_coordinates();
  for (const char* n : {"glMultiTexCoord2f", "glMultiTexCoord2d", "glMultiTexCoord4f", "glMultiTexCoord4d"})
    t.alias(std::string(n) + "ARB", n);
  t.bind("glNormal3f", &Context::normal3, {Float32("nx"), Float32("ny"), Float32("nz")}).vertex_data_call().quiet().sets(kAttribNormal);
  t.bind("glNormal3d", &Context::normal3, {Float("nx"), Float("ny"), Float("nz")}).vertex_data_call().quiet().sets(kAttribNormal);

  // §2.10.1 viewport and depth range (GLclampd), §2.13.7 shading.
  t.bind("glViewport", &Context::viewport, {Int("x"), Int("y"), Int("width"), Int("height")});
  t.bind("glDepthRange", &Context::depthRange, {Float("near"), Float("far")});
  t.bind("glShadeModel", &Context::shadeModel, {Enum("mode", {gl::FLAT, gl::SMOOTH})});

  // §2.12 raster position.
  t.bind("glRasterPos2f", &Context::rasterPos2, {Float32("x"), Float32("y")});
  t.bind("glRasterPos2d", &Context::rasterPos2, {Float("x"), Float("y")});
  t.bind("glRasterPos3f", &Context::rasterPos3, {Float32("x"), Float32("y"), Float32("z")});
  t.bind("glRasterPos3d", &Context::rasterPos3, {Float("x"), Float("y"), Float("z")});
  t.bind("glRasterPos4f", &Context::rasterPos4, {Float32("x"), Float32("y"), Float32("z"), Float32("w")});
  t.bind("glRasterPos4d", &Context::rasterPos4, {Float("x"), Float("y"), Float("z"), Float("w")});

  // §3.8.12 texture objects: a trace names textures by number (glBindTexture
  // creates them); glGenTextures is not bound (a trace cannot use the names it returns).
  t.bind("glBindTexture", &Context::bindTexture, {Enum("target"), Int("texture", 0, 0xFFFFFFFFll)});
  t.add("glDeleteTextures", {Int("n"), Numbers("textures", 0)},
        [](Context& c, const Args& a) {
          std::vector<std::uint32_t> names;
          for (double v : a.numbers_at(1)) names.push_back(static_cast<std::uint32_t>(v));
          c.deleteTextures(static_cast<int>(a.int_at(0)), names.data());
        })
      .checked([](const std::vector<ArgValue>& a) -> std::optional<ArgProblem> {
        if (a[0].i >= 0 && static_cast<std::size_t>(a[0].i) != a[1].list.size())
          return ArgProblem{1, cat("glDeleteTextures has n = ", std::to_string(a[0].i), " but ",
                                   std::to_string(a[1].list.size()), " names")};
        return check_integers(a, 1, 0, 4294967295.0, "texture names of glDeleteTextures");
      });

  // §3.8.4 texture parameters: the i form takes a token (GL_LINEAR) or an integer;
  // glTexParameterfv GL_TEXTURE_BORDER_COLOR takes 4 values, other pnames 1.
  t.bind("glTexParameteri", &Context::texParameteri, {Enum("target"), Enum("pname"), Enum("param")});
  t.bind("glTexParameterf", &Context::texParameterf, {Enum("target"), Enum("pname"), Float32("param")});
  t.add("glTexParameterfv", {Enum("target"), Enum("pname"), Numbers("params", 0, true)},
        [](Context& c, const Args& a) {
          const auto v = padded4(a.numbers_at(2));
          c.texParameterfv(a.enum_at(0), a.enum_at(1), v.data());
        })
      .checked([](const std::vector<ArgValue>& a) {
        return check_vector_count(a, 1, 2, {gl::TEXTURE_BORDER_COLOR}, "glTexParameterfv");
      });

  // ARB_multitexture units.
  t.bind("glActiveTexture", &Context::activeTexture, {Enum("texture")});
  t.bind("glClientActiveTexture", &Context::clientActiveTexture, {Enum("texture")});
  t.alias("glActiveTextureARB", "glActiveTexture");
  t.alias("glClientActiveTextureARB", "glClientActiveTexture");

  // §3.8.9 texture environments (and the combine / dot3 extensions): the i form takes
  // a token (GL_MODULATE, GL_DOT3_RGB) or an integer; glTexEnvfv GL_TEXTURE_ENV_COLOR
  // takes 4 values, other pnames 1.
  t.bind("glTexEnvi", &Context::texEnvi, {Enum("target"), Enum("pname"), Enum("param")});
  t.bind("glTexEnvf", &Context::texEnvf, {Enum("target"), Enum("pname"), Float32("param")});
  t.add("glTexEnvfv", {Enum("target"), Enum("pname"), Numbers("params", 0, true)},
        [](Context& c, const Args& a) {
          const auto v = padded4(a.numbers_at(2));
          c.texEnvfv(a.enum_at(0), a.enum_at(1), v.data());
        })
      .checked([](const std::vector<ArgValue>& a) {
        return check_vector_count(a, 1, 2, {gl::TEXTURE_ENV_COLOR}, "glTexEnvfv");
      });
}

}  // namespace ffsim::trace

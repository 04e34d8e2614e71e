// Trace commands for NV_register_combiners and NV_register_combiners2 (the
// specifications' entry points with their NV suffix). Enable REGISTER_COMBINERS_NV
// and PER_STAGE_CONSTANTS_NV with glEnable. The query calls
// (glGetCombiner*ParameterfvNV/ivNV) are not bound: a trace checks results with
// `expect` on the framebuffer.
#include <array>
#include <cstdint>

#include "sim/trace/binder.h"
#include "sim/trace/command_util.h"

namespace ffsim::trace {

void register_combiners_commands(CommandTable& t) {
  const std::vector<GLenum> portions = {gl::RGB, gl::ALPHA};
  const std::vector<GLenum> variables = {gl::VARIABLE_A_NV, gl::VARIABLE_B_NV, gl::VARIABLE_C_NV, gl::VARIABLE_D_NV};
  const std::vector<GLenum> final_variables = {gl::VARIABLE_A_NV, gl::VARIABLE_B_NV, gl::VARIABLE_C_NV, gl::VARIABLE_D_NV,
                                               gl::VARIABLE_E_NV, gl::VARIABLE_F_NV, gl::VARIABLE_G_NV};
  const std::vector<GLenum> mappings = {gl::UNSIGNED_IDENTITY_NV, gl::UNSIGNED_INVERT_NV, gl::EXPAND_NORMAL_NV,
                                        gl::EXPAND_NEGATE_NV,     gl::HALF_BIAS_NORMAL_NV, gl::HALF_BIAS_NEGATE_NV,
                                        gl::SIGNED_IDENTITY_NV,   gl::SIGNED_NEGATE_NV};
  const std::vector<GLenum> usages = {gl::RGB, gl::ALPHA, gl::BLUE};
  const std::vector<GLenum> scales = {gl::NONE, gl::SCALE_BY_TWO_NV, gl::SCALE_BY_FOUR_NV, gl::SCALE_BY_ONE_HALF_NV};
  const std::vector<GLenum> biases = {gl::NONE, gl::BIAS_BY_NEGATIVE_ONE_HALF_NV};
  const std::vector<GLenum> colors = {gl::CONSTANT_COLOR0_NV, gl::CONSTANT_COLOR1_NV};

  // glCombinerParameter*: CONSTANT_COLOR0_NV / CONSTANT_COLOR1_NV take 4 values,
  // NUM_GENERAL_COMBINERS_NV and COLOR_SUM_CLAMP_NV one.
  t.add("glCombinerParameterfvNV", {Enum("pname"), Numbers("params", 0, true)},
        [](Context& c, const Args& a) {
          const auto d = padded4(a.numbers_at(1));
          const std::array<float, 4> v{static_cast<float>(d[0]), static_cast<float>(d[1]), static_cast<float>(d[2]),
                                       static_cast<float>(d[3])};
          c.combinerParameterfv(a.enum_at(0), v.data());
        })
      .checked([colors](const std::vector<ArgValue>& a) { return check_vector_count(a, 0, 1, colors, "glCombinerParameterfvNV"); });
  t.bind("glCombinerParameterfNV", &Context::combinerParameterf, {Enum("pname"), Float32("param")});
  t.add("glCombinerParameterivNV", {Enum("pname"), Numbers("params", 0)},
        [](Context& c, const Args& a) {
          const auto d = padded4(a.numbers_at(1));
          const std::array<std::int32_t, 4> v{static_cast<std::int32_t>(d[0]), static_cast<std::int32_t>(d[1]),
                                              static_cast<std::int32_t>(d[2]), static_cast<std::int32_t>(d[3])};
          c.combinerParameteriv(a.enum_at(0), v.data());
        })
      .checked([colors](const std::vector<ArgValue>& a) {
        auto p = check_vector_count(a, 0, 1, colors, "glCombinerParameterivNV");
        return p ? p : check_integers(a, 1, -2147483648.0, 2147483647.0, "the params of glCombinerParameterivNV");
      });
  // The i form takes a number or a token (GL_TRUE for COLOR_SUM_CLAMP_NV).
  t.bind("glCombinerParameteriNV", &Context::combinerParameteri, {Enum("pname"), Enum("param")});

  t.bind("glCombinerInputNV", &Context::combinerInput,
         {Enum("stage"), Enum("portion", portions), Enum("variable", variables), Enum("input"), Enum("mapping", mappings),
          Enum("componentUsage", usages)});
  t.bind("glCombinerOutputNV", &Context::combinerOutput,
         {Enum("stage"), Enum("portion", portions), Enum("abOutput"), Enum("cdOutput"), Enum("sumOutput"),
          Enum("scale", scales), Enum("bias", biases), Bool("abDotProduct"), Bool("cdDotProduct"), Bool("muxSum")});
  t.bind("glFinalCombinerInputNV", &Context::finalCombinerInput,
         {Enum("variable", final_variables), Enum("input"), Enum("mapping", mappings), Enum("componentUsage", usages)});
  // NV_register_combiners2: per-stage constants (4 values).
  t.add("glCombinerStageParameterfvNV", {Enum("stage"), Enum("pname"), Numbers("params", 4, true)},
        [](Context& c, const Args& a) {
          const auto& d = a.numbers_at(2);
          const std::array<float, 4> v{static_cast<float>(d[0]), static_cast<float>(d[1]), static_cast<float>(d[2]),
                                       static_cast<float>(d[3])};
          c.combinerStageParameterfv(a.enum_at(0), a.enum_at(1), v.data());
        });
}

}  // namespace ffsim::trace

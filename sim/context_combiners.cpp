// NV_register_combiners and NV_register_combiners2 entry points. Errors as RC's
// Errors section and §3.8.12 list them; tokens a parameter does not accept are
// INVALID_ENUM (GL121 §2.5). A call that raises an error changes no state.
#include <cmath>

#include "pipeline/combiners/describe.h"
#include "pipeline/gl/enum_names.h"
#include "sim/context.h"

namespace ffsim {

using namespace combiners;

namespace {

// Colours are clamped to [0,1] when specified (RC §3.8.12.1, RC2 v1.1); NaN -> 0.
double clamp_color(double x) { return !(x > 0) ? 0.0 : (x > 1 ? 1.0 : x); }

// GL121 Table 2.6, signed int: (2c + 1) / (2^32 - 1).
double int_to_color(std::int32_t c) { return (2.0 * c + 1.0) / 4294967295.0; }

}  // namespace

// ---- CombinerParameter*NV ---------------------------------------------------

namespace {
struct ParamValues {
  double v[4];
  int count;
};
}  // namespace

static bool set_combiner_parameter(Context& ctx, CombinerState& s, const char* fn, GLenum pname, const ParamValues& p,
                                   bool vector_call) {
  switch (pname) {
    case gl::CONSTANT_COLOR0_NV:
    case gl::CONSTANT_COLOR1_NV: {
      if (!vector_call)
        return ctx.error(gl::INVALID_ENUM, fn, gl::enum_name(pname) + " needs four values (use the v form)");
      auto& dst = pname == gl::CONSTANT_COLOR0_NV ? s.constant_color0 : s.constant_color1;
      for (std::size_t i = 0; i < 4; ++i) dst[i] = clamp_color(p.v[i]);
      return true;
    }
    case gl::NUM_GENERAL_COMBINERS_NV: {
      const double n = std::round(p.v[0]);  // a float count rounds to nearest, half away from zero
      const int max = ctx.profile().general_combiners;
      // RC §3.8.12.1: less than one or greater than MAX_GENERAL_COMBINERS_NV is an
      // error (the Errors section's "greater or equal" contradicts the body; choice #27).
      if (!(n >= 1 && n <= max))
        return ctx.error(gl::INVALID_VALUE, fn,
                         "NUM_GENERAL_COMBINERS_NV must be in 1.." + std::to_string(max) + " (MAX_GENERAL_COMBINERS_NV)");
      s.num_general_combiners = static_cast<int>(n);
      return true;
    }
    case gl::COLOR_SUM_CLAMP_NV: s.color_sum_clamp = p.v[0] != 0; return true;
    default:
      return ctx.error(gl::INVALID_ENUM, fn, gl::enum_name(pname) + " is not a combiner parameter");
  }
}

void Context::combinerParameterfv(GLenum pname, const float* params) {
  if (reject_in_begin("glCombinerParameterfvNV")) return;
  const int n = pname == gl::CONSTANT_COLOR0_NV || pname == gl::CONSTANT_COLOR1_NV ? 4 : 1;
  ParamValues p{{0, 0, 0, 0}, n};
  for (int i = 0; i < n; ++i) p.v[i] = params[i];
  CombinerState s = combiners_;
  if (set_combiner_parameter(*this, s, "glCombinerParameterfvNV", pname, p, true)) {
    combiners_ = s;
    combiner_plan_.reset();
  }
}

void Context::combinerParameterf(GLenum pname, float param) {
  if (reject_in_begin("glCombinerParameterfNV")) return;
  CombinerState s = combiners_;
  if (set_combiner_parameter(*this, s, "glCombinerParameterfNV", pname, ParamValues{{param, 0, 0, 0}, 1}, false)) {
    combiners_ = s;
    combiner_plan_.reset();
  }
}

void Context::combinerParameteriv(GLenum pname, const std::int32_t* params) {
  if (reject_in_begin("glCombinerParameterivNV")) return;
  const bool color = pname == gl::CONSTANT_COLOR0_NV || pname == gl::CONSTANT_COLOR1_NV;
  ParamValues p{{0, 0, 0, 0}, color ? 4 : 1};
  for (int i = 0; i < p.count; ++i) p.v[i] = color ? int_to_color(params[i]) : static_cast<double>(params[i]);
  CombinerState s = combiners_;
  if (set_combiner_parameter(*this, s, "glCombinerParameterivNV", pname, p, true)) {
    combiners_ = s;
    combiner_plan_.reset();
  }
}

void Context::combinerParameteri(GLenum pname, std::int32_t param) {
  if (reject_in_begin("glCombinerParameteriNV")) return;
  CombinerState s = combiners_;
  if (set_combiner_parameter(*this, s, "glCombinerParameteriNV", pname,
                             ParamValues{{static_cast<double>(param), 0, 0, 0}, 1}, false)) {
    combiners_ = s;
    combiner_plan_.reset();
  }
}

// ---- CombinerInputNV / CombinerOutputNV / FinalCombinerInputNV --------------

void Context::combinerInput(GLenum stage, GLenum portion, GLenum variable, GLenum input, GLenum mapping,
                            GLenum componentUsage) {
  if (reject_in_begin("glCombinerInputNV")) return;
  const char* fn = "glCombinerInputNV";
  const int st = stage_index(stage, profile_.general_combiners);
  if (st < 0) {
    error(gl::INVALID_ENUM, fn, gl::enum_name(stage) + " is not COMBINER0_NV .. COMBINER" +
                                    std::to_string(profile_.general_combiners - 1) + "_NV");
    return;
  }
  const Check c = check_combiner_input(portion, variable, input, mapping, componentUsage, profile_.texture_units);
  if (!c) {
    error(c.error, fn, c.message);
    return;
  }
  PortionState& p = portion == gl::RGB ? combiners_.stages[static_cast<std::size_t>(st)].rgb
                                       : combiners_.stages[static_cast<std::size_t>(st)].alpha;
  p.var[static_cast<std::size_t>(variable_index(variable, 4))] = VariableState{input, mapping, componentUsage};
  combiner_plan_.reset();
}

void Context::combinerOutput(GLenum stage, GLenum portion, GLenum abOutput, GLenum cdOutput, GLenum sumOutput,
                             GLenum scale, GLenum bias, bool abDotProduct, bool cdDotProduct, bool muxSum) {
  if (reject_in_begin("glCombinerOutputNV")) return;
  const char* fn = "glCombinerOutputNV";
  const int st = stage_index(stage, profile_.general_combiners);
  if (st < 0) {
    error(gl::INVALID_ENUM, fn, gl::enum_name(stage) + " is not COMBINER0_NV .. COMBINER" +
                                    std::to_string(profile_.general_combiners - 1) + "_NV");
    return;
  }
  const Check c = check_combiner_output(portion, abOutput, cdOutput, sumOutput, scale, bias, abDotProduct,
                                        cdDotProduct, profile_.texture_units);
  if (!c) {
    error(c.error, fn, c.message);
    return;
  }
  PortionState& p = portion == gl::RGB ? combiners_.stages[static_cast<std::size_t>(st)].rgb
                                       : combiners_.stages[static_cast<std::size_t>(st)].alpha;
  p.ab_output = abOutput;
  p.cd_output = cdOutput;
  p.sum_output = sumOutput;
  p.scale = scale;
  p.bias = bias;
  p.ab_dot_product = abDotProduct;
  p.cd_dot_product = cdDotProduct;
  p.mux_sum = muxSum;
  combiner_plan_.reset();
}

void Context::finalCombinerInput(GLenum variable, GLenum input, GLenum mapping, GLenum componentUsage) {
  if (reject_in_begin("glFinalCombinerInputNV")) return;
  const Check c = check_final_combiner_input(variable, input, mapping, componentUsage, profile_.texture_units);
  if (!c) {
    error(c.error, "glFinalCombinerInputNV", c.message);
    return;
  }
  combiners_.final_var[static_cast<std::size_t>(variable_index(variable, 7))] =
      VariableState{input, mapping, componentUsage};
  combiner_plan_.reset();
}

void Context::combinerStageParameterfv(GLenum stage, GLenum pname, const float* params) {
  if (reject_in_begin("glCombinerStageParameterfvNV")) return;
  const char* fn = "glCombinerStageParameterfvNV";
  const int st = stage_index(stage, profile_.general_combiners);
  if (st < 0) {
    error(gl::INVALID_ENUM, fn, gl::enum_name(stage) + " is not COMBINER0_NV .. COMBINER" +
                                    std::to_string(profile_.general_combiners - 1) + "_NV");
    return;
  }
  if (pname != gl::CONSTANT_COLOR0_NV && pname != gl::CONSTANT_COLOR1_NV) {
    error(gl::INVALID_ENUM, fn, gl::enum_name(pname) + " is not CONSTANT_COLOR0_NV or CONSTANT_COLOR1_NV");
    return;
  }
  GeneralStageState& gs = combiners_.stages[static_cast<std::size_t>(st)];
  auto& dst = pname == gl::CONSTANT_COLOR0_NV ? gs.constant_color0 : gs.constant_color1;
  for (std::size_t i = 0; i < 4; ++i) dst[i] = clamp_color(params[i]);
  combiner_plan_.reset();
}

// ---- queries ------------------------------------------------------------------

namespace {

// The variable of a general stage named by (stage, portion, variable), or an error.
const VariableState* general_variable(Context& ctx, const CombinerState& s, const char* fn, GLenum stage,
                                      GLenum portion, GLenum variable) {
  const int st = stage_index(stage, ctx.profile().general_combiners);
  if (st < 0) {
    ctx.error(gl::INVALID_ENUM, fn, gl::enum_name(stage) + " is not a general combiner stage");
    return nullptr;
  }
  if (portion != gl::RGB && portion != gl::ALPHA) {
    ctx.error(gl::INVALID_ENUM, fn, "<portion> must be RGB or ALPHA");
    return nullptr;
  }
  const int v = variable_index(variable, 4);
  if (v < 0) {
    ctx.error(gl::INVALID_ENUM, fn, "<variable> must be VARIABLE_A_NV .. VARIABLE_D_NV");
    return nullptr;
  }
  const GeneralStageState& gs = s.stages[static_cast<std::size_t>(st)];
  return &(portion == gl::RGB ? gs.rgb : gs.alpha).var[static_cast<std::size_t>(v)];
}

bool input_parameter(Context& ctx, const char* fn, const VariableState& v, GLenum pname, std::int64_t& out) {
  switch (pname) {
    case gl::COMBINER_INPUT_NV: out = v.input; return true;
    case gl::COMBINER_MAPPING_NV: out = v.mapping; return true;
    case gl::COMBINER_COMPONENT_USAGE_NV: out = v.component_usage; return true;
    default: return ctx.error(gl::INVALID_ENUM, fn, gl::enum_name(pname) + " is not a combiner input parameter");
  }
}

bool output_parameter(Context& ctx, const CombinerState& s, const char* fn, GLenum stage, GLenum portion,
                      GLenum pname, std::int64_t& out) {
  const int st = stage_index(stage, ctx.profile().general_combiners);
  if (st < 0) return ctx.error(gl::INVALID_ENUM, fn, gl::enum_name(stage) + " is not a general combiner stage");
  if (portion != gl::RGB && portion != gl::ALPHA)
    return ctx.error(gl::INVALID_ENUM, fn, "<portion> must be RGB or ALPHA");
  const GeneralStageState& gs = s.stages[static_cast<std::size_t>(st)];
  const PortionState& p = portion == gl::RGB ? gs.rgb : gs.alpha;
  switch (pname) {
    case gl::COMBINER_AB_DOT_PRODUCT_NV: out = p.ab_dot_product; return true;
    case gl::COMBINER_CD_DOT_PRODUCT_NV: out = p.cd_dot_product; return true;
    case gl::COMBINER_MUX_SUM_NV: out = p.mux_sum; return true;
    case gl::COMBINER_SCALE_NV: out = p.scale; return true;
    case gl::COMBINER_BIAS_NV: out = p.bias; return true;
    case gl::COMBINER_AB_OUTPUT_NV: out = p.ab_output; return true;
    case gl::COMBINER_CD_OUTPUT_NV: out = p.cd_output; return true;
    case gl::COMBINER_SUM_OUTPUT_NV: out = p.sum_output; return true;
    default: return ctx.error(gl::INVALID_ENUM, fn, gl::enum_name(pname) + " is not a combiner output parameter");
  }
}

bool final_parameter(Context& ctx, const CombinerState& s, const char* fn, GLenum variable, GLenum pname,
                     std::int64_t& out) {
  const int v = variable_index(variable, 7);
  if (v < 0) return ctx.error(gl::INVALID_ENUM, fn, "<variable> must be VARIABLE_A_NV .. VARIABLE_G_NV");
  return input_parameter(ctx, fn, s.final_var[static_cast<std::size_t>(v)], pname, out);
}

}  // namespace

void Context::getCombinerInputParameterfv(GLenum stage, GLenum portion, GLenum variable, GLenum pname,
                                          float* params) {
  if (reject_in_begin("glGetCombinerInputParameterfvNV")) return;
  const char* fn = "glGetCombinerInputParameterfvNV";
  std::int64_t v = 0;
  if (const VariableState* var = general_variable(*this, combiners_, fn, stage, portion, variable))
    if (input_parameter(*this, fn, *var, pname, v)) params[0] = static_cast<float>(v);
}

void Context::getCombinerInputParameteriv(GLenum stage, GLenum portion, GLenum variable, GLenum pname,
                                          std::int32_t* params) {
  if (reject_in_begin("glGetCombinerInputParameterivNV")) return;
  const char* fn = "glGetCombinerInputParameterivNV";
  std::int64_t v = 0;
  if (const VariableState* var = general_variable(*this, combiners_, fn, stage, portion, variable))
    if (input_parameter(*this, fn, *var, pname, v)) params[0] = static_cast<std::int32_t>(v);
}

void Context::getCombinerOutputParameterfv(GLenum stage, GLenum portion, GLenum pname, float* params) {
  if (reject_in_begin("glGetCombinerOutputParameterfvNV")) return;
  std::int64_t v = 0;
  if (output_parameter(*this, combiners_, "glGetCombinerOutputParameterfvNV", stage, portion, pname, v))
    params[0] = static_cast<float>(v);
}

void Context::getCombinerOutputParameteriv(GLenum stage, GLenum portion, GLenum pname, std::int32_t* params) {
  if (reject_in_begin("glGetCombinerOutputParameterivNV")) return;
  std::int64_t v = 0;
  if (output_parameter(*this, combiners_, "glGetCombinerOutputParameterivNV", stage, portion, pname, v))
    params[0] = static_cast<std::int32_t>(v);
}

void Context::getFinalCombinerInputParameterfv(GLenum variable, GLenum pname, float* params) {
  if (reject_in_begin("glGetFinalCombinerInputParameterfvNV")) return;
  std::int64_t v = 0;
  if (final_parameter(*this, combiners_, "glGetFinalCombinerInputParameterfvNV", variable, pname, v))
    params[0] = static_cast<float>(v);
}

void Context::getFinalCombinerInputParameteriv(GLenum variable, GLenum pname, std::int32_t* params) {
  if (reject_in_begin("glGetFinalCombinerInputParameterivNV")) return;
  std::int64_t v = 0;
  if (final_parameter(*this, combiners_, "glGetFinalCombinerInputParameterivNV", variable, pname, v))
    params[0] = static_cast<std::int32_t>(v);
}

void Context::getCombinerStageParameterfv(GLenum stage, GLenum pname, float* params) {
  if (reject_in_begin("glGetCombinerStageParameterfvNV")) return;
  const char* fn = "glGetCombinerStageParameterfvNV";
  const int st = stage_index(stage, profile_.general_combiners);
  if (st < 0) {
    error(gl::INVALID_ENUM, fn, gl::enum_name(stage) + " is not a general combiner stage");
    return;
  }
  if (pname != gl::CONSTANT_COLOR0_NV && pname != gl::CONSTANT_COLOR1_NV) {
    error(gl::INVALID_ENUM, fn, gl::enum_name(pname) + " is not CONSTANT_COLOR0_NV or CONSTANT_COLOR1_NV");
    return;
  }
  const GeneralStageState& gs = combiners_.stages[static_cast<std::size_t>(st)];
  const auto& c = pname == gl::CONSTANT_COLOR0_NV ? gs.constant_color0 : gs.constant_color1;
  for (std::size_t i = 0; i < 4; ++i) params[i] = static_cast<float>(c[i]);
}

// ---- plan, switches, describe -------------------------------------------------

const CombinerPlan& Context::combiner_plan() {
  if (!combiner_plan_) {
    CombinerConfig cfg = CombinerConfig::from_profile(profile_);
    cfg.rounding = combiner_rounding_;
    cfg.rc2_secondary_alpha = combiner_rc2_secondary_alpha_;
    combiner_plan_ = std::make_unique<CombinerPlan>(plan_combiners(combiners_, cfg));
  }
  return *combiner_plan_;
}

void Context::set_combiner_rounding(CombinerRounding r) {
  combiner_rounding_ = r;
  combiner_plan_.reset();
}

void Context::set_combiner_rc2_secondary_alpha(bool on) {
  combiner_rc2_secondary_alpha_ = on;
  combiner_plan_.reset();
}

std::string Context::describe_combiners() { return describe(combiner_plan()); }

}  // namespace ffsim

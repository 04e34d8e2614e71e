// NV_register_combiners / NV_register_combiners2 GL entry points: every error of
// RC's Errors section (and of §3.8.12, which the Errors section restates), the
// INVALID_ENUM of tokens a parameter does not accept (GL121 §2.5), state left
// unchanged by a failing call, the legal combinations that must not fail, and
// the initial state of RC Tables .5/.6 and the New State tables through the queries.
#include <doctest/doctest.h>

#include <functional>
#include <string>

#include "sim/context.h"

using namespace ffsim;

namespace {

struct Row {
  const char* what;  // the rule, quoted from RC / RC2 or GL121
  GLenum expected;
  std::function<void(Context&)> call;
};

const float kColor[4] = {0.1f, 0.2f, 0.3f, 0.4f};

void run_rows(const char* profile, const std::vector<Row>& rows) {
  for (const Row& r : rows) {
    Context ctx(*find_builtin_profile(profile), 4, 4);
    const combiners::CombinerState before = ctx.combiner_state();
    r.call(ctx);
    const GLenum got = ctx.getError();
    if (got != r.expected) FAIL_CHECK(profile << ": " << r.what << ": got 0x" << std::hex << got);
    if (r.expected != gl::NO_ERROR) {
      if (!(ctx.combiner_state() == before)) FAIL_CHECK(profile << ": " << r.what << ": state changed on error");
      CHECK(ctx.error_log().size() == 1);
    }
  }
}

using C = Context;
constexpr GLenum S0 = gl::COMBINER0_NV, RGB = gl::RGB, ALPHA = gl::ALPHA, BLUE = gl::BLUE;
constexpr GLenum VA = gl::VARIABLE_A_NV, VB = gl::VARIABLE_B_NV, VD = gl::VARIABLE_D_NV, VE = gl::VARIABLE_E_NV,
                 VF = gl::VARIABLE_F_NV, VG = gl::VARIABLE_G_NV;
constexpr GLenum UI = gl::UNSIGNED_IDENTITY_NV, EN = gl::EXPAND_NORMAL_NV;
constexpr GLenum DIS = gl::DISCARD_NV, SP0 = gl::SPARE0_NV, SP1 = gl::SPARE1_NV, NONE = gl::NONE;

}  // namespace

TEST_CASE("combiners errors: every error RC lists, on geforce256 (2 stages, 2 texture units)") {
  run_rows("geforce256", {
    // CombinerParameter*NV
    {"NUM_GENERAL_COMBINERS_NV less than one (fv)", gl::INVALID_VALUE, [](C& c) { const float v = 0; c.combinerParameterfv(gl::NUM_GENERAL_COMBINERS_NV, &v); }},
    {"NUM_GENERAL_COMBINERS_NV greater than MAX (iv)", gl::INVALID_VALUE, [](C& c) { const std::int32_t v = 3; c.combinerParameteriv(gl::NUM_GENERAL_COMBINERS_NV, &v); }},
    {"NUM_GENERAL_COMBINERS_NV less than one (i)", gl::INVALID_VALUE, [](C& c) { c.combinerParameteri(gl::NUM_GENERAL_COMBINERS_NV, 0); }},
    {"NUM_GENERAL_COMBINERS_NV negative (f)", gl::INVALID_VALUE, [](C& c) { c.combinerParameterf(gl::NUM_GENERAL_COMBINERS_NV, -1); }},
    {"NUM_GENERAL_COMBINERS_NV = MAX is legal (body of 3.8.12.1, choice #27)", gl::NO_ERROR, [](C& c) { c.combinerParameteri(gl::NUM_GENERAL_COMBINERS_NV, 2); }},
    {"CombinerParameter pname not a combiner parameter", gl::INVALID_ENUM, [](C& c) { c.combinerParameterfv(gl::FOG, kColor); }},
    {"CONSTANT_COLOR0_NV through the scalar form", gl::INVALID_ENUM, [](C& c) { c.combinerParameterf(gl::CONSTANT_COLOR0_NV, 0.5f); }},
    {"CONSTANT_COLOR1_NV through the scalar int form", gl::INVALID_ENUM, [](C& c) { c.combinerParameteri(gl::CONSTANT_COLOR1_NV, 1); }},
    // CombinerInputNV
    {"componentUsage RGB with portion ALPHA", gl::INVALID_OPERATION, [](C& c) { c.combinerInput(S0, ALPHA, VA, gl::TEXTURE0, UI, RGB); }},
    {"componentUsage BLUE with portion RGB", gl::INVALID_OPERATION, [](C& c) { c.combinerInput(S0, RGB, VA, gl::TEXTURE0, UI, BLUE); }},
    {"componentUsage ALPHA with input FOG (RGB portion)", gl::INVALID_OPERATION, [](C& c) { c.combinerInput(S0, RGB, VB, gl::FOG, UI, ALPHA); }},
    {"componentUsage ALPHA with input FOG (ALPHA portion)", gl::INVALID_OPERATION, [](C& c) { c.combinerInput(S0, ALPHA, VB, gl::FOG, UI, ALPHA); }},
    {"FOG with RGB usage is legal", gl::NO_ERROR, [](C& c) { c.combinerInput(S0, RGB, VB, gl::FOG, UI, RGB); }},
    {"FOG blue in the ALPHA portion is legal", gl::NO_ERROR, [](C& c) { c.combinerInput(S0, ALPHA, VB, gl::FOG, UI, BLUE); }},
    {"stage beyond MAX_GENERAL_COMBINERS_NV", gl::INVALID_ENUM, [](C& c) { c.combinerInput(gl::COMBINER2_NV, RGB, VA, gl::ZERO, UI, RGB); }},
    {"portion not RGB or ALPHA", gl::INVALID_ENUM, [](C& c) { c.combinerInput(S0, BLUE, VA, gl::ZERO, UI, RGB); }},
    {"variable E in a general combiner", gl::INVALID_ENUM, [](C& c) { c.combinerInput(S0, RGB, VE, gl::ZERO, UI, RGB); }},
    {"pseudo-register E_TIMES_F_NV in a general combiner", gl::INVALID_ENUM, [](C& c) { c.combinerInput(S0, RGB, VA, gl::E_TIMES_F_NV, UI, RGB); }},
    {"pseudo-register SPARE0_PLUS_SECONDARY_COLOR_NV in a general combiner", gl::INVALID_ENUM, [](C& c) { c.combinerInput(S0, RGB, VA, gl::SPARE0_PLUS_SECONDARY_COLOR_NV, UI, RGB); }},
    {"TEXTURE2 with two texture units", gl::INVALID_ENUM, [](C& c) { c.combinerInput(S0, RGB, VA, gl::TEXTURE2, UI, RGB); }},
    {"DISCARD_NV as an input", gl::INVALID_ENUM, [](C& c) { c.combinerInput(S0, RGB, VA, DIS, UI, RGB); }},
    {"mapping not in Table .4", gl::INVALID_ENUM, [](C& c) { c.combinerInput(S0, RGB, VA, gl::ZERO, RGB, RGB); }},
    {"componentUsage not RGB, ALPHA or BLUE", gl::INVALID_ENUM, [](C& c) { c.combinerInput(S0, RGB, VA, gl::ZERO, UI, gl::RED); }},
    // CombinerOutputNV
    {"ALPHA portion with abDotProduct", gl::INVALID_VALUE, [](C& c) { c.combinerOutput(S0, ALPHA, SP0, DIS, DIS, NONE, NONE, true, false, false); }},
    {"ALPHA portion with cdDotProduct", gl::INVALID_VALUE, [](C& c) { c.combinerOutput(S0, ALPHA, DIS, SP0, DIS, NONE, NONE, false, true, false); }},
    {"SCALE_BY_ONE_HALF_NV with BIAS_BY_NEGATIVE_ONE_HALF_NV", gl::INVALID_OPERATION, [](C& c) { c.combinerOutput(S0, RGB, SP0, DIS, DIS, gl::SCALE_BY_ONE_HALF_NV, gl::BIAS_BY_NEGATIVE_ONE_HALF_NV, false, false, false); }},
    {"SCALE_BY_FOUR_NV with BIAS_BY_NEGATIVE_ONE_HALF_NV", gl::INVALID_OPERATION, [](C& c) { c.combinerOutput(S0, ALPHA, SP0, DIS, DIS, gl::SCALE_BY_FOUR_NV, gl::BIAS_BY_NEGATIVE_ONE_HALF_NV, false, false, false); }},
    {"SCALE_BY_TWO_NV with BIAS_BY_NEGATIVE_ONE_HALF_NV is legal", gl::NO_ERROR, [](C& c) { c.combinerOutput(S0, RGB, SP0, DIS, DIS, gl::SCALE_BY_TWO_NV, gl::BIAS_BY_NEGATIVE_ONE_HALF_NV, false, false, false); }},
    {"abOutput == cdOutput", gl::INVALID_OPERATION, [](C& c) { c.combinerOutput(S0, RGB, SP0, SP0, DIS, NONE, NONE, false, false, false); }},
    {"abOutput == sumOutput", gl::INVALID_OPERATION, [](C& c) { c.combinerOutput(S0, RGB, SP1, DIS, SP1, NONE, NONE, false, false, false); }},
    {"cdOutput == sumOutput", gl::INVALID_OPERATION, [](C& c) { c.combinerOutput(S0, ALPHA, DIS, gl::TEXTURE1, gl::TEXTURE1, NONE, NONE, false, false, false); }},
    {"all three DISCARD_NV is legal", gl::NO_ERROR, [](C& c) { c.combinerOutput(S0, RGB, DIS, DIS, DIS, NONE, NONE, false, false, false); }},
    {"dot products with a sum output are legal (v1.6)", gl::NO_ERROR, [](C& c) { c.combinerOutput(S0, RGB, SP0, SP1, gl::PRIMARY_COLOR_NV, NONE, NONE, true, true, false); }},
    {"output to ZERO (read only)", gl::INVALID_ENUM, [](C& c) { c.combinerOutput(S0, RGB, gl::ZERO, DIS, DIS, NONE, NONE, false, false, false); }},
    {"output to CONSTANT_COLOR0_NV (read only)", gl::INVALID_ENUM, [](C& c) { c.combinerOutput(S0, RGB, DIS, gl::CONSTANT_COLOR0_NV, DIS, NONE, NONE, false, false, false); }},
    {"output to FOG (read only)", gl::INVALID_ENUM, [](C& c) { c.combinerOutput(S0, RGB, DIS, DIS, gl::FOG, NONE, NONE, false, false, false); }},
    {"output to TEXTURE2 with two texture units", gl::INVALID_ENUM, [](C& c) { c.combinerOutput(S0, RGB, gl::TEXTURE2, DIS, DIS, NONE, NONE, false, false, false); }},
    {"scale not one of the four", gl::INVALID_ENUM, [](C& c) { c.combinerOutput(S0, RGB, SP0, DIS, DIS, gl::BIAS_BY_NEGATIVE_ONE_HALF_NV, NONE, false, false, false); }},
    {"bias not NONE or BIAS_BY_NEGATIVE_ONE_HALF_NV", gl::INVALID_ENUM, [](C& c) { c.combinerOutput(S0, RGB, SP0, DIS, DIS, NONE, gl::SCALE_BY_TWO_NV, false, false, false); }},
    {"output stage beyond MAX", gl::INVALID_ENUM, [](C& c) { c.combinerOutput(gl::COMBINER7_NV, RGB, SP0, DIS, DIS, NONE, NONE, false, false, false); }},
    {"output portion not RGB or ALPHA", gl::INVALID_ENUM, [](C& c) { c.combinerOutput(S0, gl::RED, SP0, DIS, DIS, NONE, NONE, false, false, false); }},
    // FinalCombinerInputNV
    {"E takes E_TIMES_F_NV", gl::INVALID_OPERATION, [](C& c) { c.finalCombinerInput(VE, gl::E_TIMES_F_NV, UI, RGB); }},
    {"F takes SPARE0_PLUS_SECONDARY_COLOR_NV", gl::INVALID_OPERATION, [](C& c) { c.finalCombinerInput(VF, gl::SPARE0_PLUS_SECONDARY_COLOR_NV, UI, RGB); }},
    {"G takes E_TIMES_F_NV", gl::INVALID_OPERATION, [](C& c) { c.finalCombinerInput(VG, gl::E_TIMES_F_NV, UI, ALPHA); }},
    {"A takes SPARE0_PLUS_SECONDARY_COLOR_NV", gl::INVALID_OPERATION, [](C& c) { c.finalCombinerInput(VA, gl::SPARE0_PLUS_SECONDARY_COLOR_NV, UI, RGB); }},
    {"A takes E_TIMES_F_NV (legal)", gl::NO_ERROR, [](C& c) { c.finalCombinerInput(VA, gl::E_TIMES_F_NV, UI, RGB); }},
    {"G with componentUsage RGB", gl::INVALID_OPERATION, [](C& c) { c.finalCombinerInput(VG, SP0, UI, RGB); }},
    {"G with componentUsage BLUE (legal since June 2000)", gl::NO_ERROR, [](C& c) { c.finalCombinerInput(VG, SP0, UI, BLUE); }},
    {"componentUsage BLUE for a variable other than G", gl::INVALID_OPERATION, [](C& c) { c.finalCombinerInput(VA, SP0, UI, BLUE); }},
    {"E_TIMES_F_NV with componentUsage ALPHA", gl::INVALID_OPERATION, [](C& c) { c.finalCombinerInput(VB, gl::E_TIMES_F_NV, UI, ALPHA); }},
    {"SPARE0_PLUS_SECONDARY_COLOR_NV with componentUsage ALPHA", gl::INVALID_OPERATION, [](C& c) { c.finalCombinerInput(VD, gl::SPARE0_PLUS_SECONDARY_COLOR_NV, UI, ALPHA); }},
    {"FOG alpha in the final combiner (legal)", gl::NO_ERROR, [](C& c) { c.finalCombinerInput(VA, gl::FOG, gl::UNSIGNED_INVERT_NV, ALPHA); }},
    {"final mapping other than UNSIGNED_*", gl::INVALID_ENUM, [](C& c) { c.finalCombinerInput(VA, SP0, EN, RGB); }},
    {"final variable not A..G", gl::INVALID_ENUM, [](C& c) { c.finalCombinerInput(gl::VARIABLE_G_NV + 1, SP0, UI, ALPHA); }},
    {"final input DISCARD_NV", gl::INVALID_ENUM, [](C& c) { c.finalCombinerInput(VA, DIS, UI, RGB); }},
    // CombinerStageParameterfvNV (RC2 lists no errors; unaccepted tokens are INVALID_ENUM)
    {"per-stage constant of a stage beyond MAX", gl::INVALID_ENUM, [](C& c) { c.combinerStageParameterfv(gl::COMBINER2_NV, gl::CONSTANT_COLOR0_NV, kColor); }},
    {"per-stage pname not a constant colour", gl::INVALID_ENUM, [](C& c) { c.combinerStageParameterfv(S0, gl::NUM_GENERAL_COMBINERS_NV, kColor); }},
    {"per-stage constant of an inactive stage (>= NUM) is legal", gl::NO_ERROR, [](C& c) { c.combinerStageParameterfv(gl::COMBINER1_NV, gl::CONSTANT_COLOR1_NV, kColor); }},
    // Queries
    {"GetCombinerInputParameter pname", gl::INVALID_ENUM, [](C& c) { std::int32_t v; c.getCombinerInputParameteriv(S0, RGB, VA, gl::COMBINER_SCALE_NV, &v); }},
    {"GetCombinerInputParameter stage", gl::INVALID_ENUM, [](C& c) { float v; c.getCombinerInputParameterfv(gl::COMBINER2_NV, RGB, VA, gl::COMBINER_INPUT_NV, &v); }},
    {"GetCombinerInputParameter variable", gl::INVALID_ENUM, [](C& c) { float v; c.getCombinerInputParameterfv(S0, RGB, VE, gl::COMBINER_INPUT_NV, &v); }},
    {"GetCombinerOutputParameter pname", gl::INVALID_ENUM, [](C& c) { std::int32_t v; c.getCombinerOutputParameteriv(S0, RGB, gl::COMBINER_INPUT_NV, &v); }},
    {"GetCombinerOutputParameter portion", gl::INVALID_ENUM, [](C& c) { float v; c.getCombinerOutputParameterfv(S0, BLUE, gl::COMBINER_SCALE_NV, &v); }},
    {"GetFinalCombinerInputParameter variable", gl::INVALID_ENUM, [](C& c) { std::int32_t v; c.getFinalCombinerInputParameteriv(gl::VARIABLE_G_NV + 1, gl::COMBINER_INPUT_NV, &v); }},
    {"GetFinalCombinerInputParameter pname", gl::INVALID_ENUM, [](C& c) { float v; c.getFinalCombinerInputParameterfv(VA, gl::COMBINER_BIAS_NV, &v); }},
    {"GetCombinerStageParameter stage", gl::INVALID_ENUM, [](C& c) { float v[4]; c.getCombinerStageParameterfv(gl::COMBINER2_NV, gl::CONSTANT_COLOR0_NV, v); }},
    {"GetCombinerStageParameter pname", gl::INVALID_ENUM, [](C& c) { float v[4]; c.getCombinerStageParameterfv(S0, gl::COMBINER_INPUT_NV, v); }},
  });
}

TEST_CASE("combiners errors: limits follow the profile (rgba10: 8 stages, 4 texture units)") {
  run_rows("rgba10", {
    {"NUM_GENERAL_COMBINERS_NV = 8 = MAX", gl::NO_ERROR, [](C& c) { c.combinerParameteri(gl::NUM_GENERAL_COMBINERS_NV, 8); }},
    {"NUM_GENERAL_COMBINERS_NV = 9 > MAX", gl::INVALID_VALUE, [](C& c) { c.combinerParameteri(gl::NUM_GENERAL_COMBINERS_NV, 9); }},
    {"COMBINER7_NV exists", gl::NO_ERROR, [](C& c) { c.combinerInput(gl::COMBINER7_NV, RGB, VA, gl::TEXTURE3, UI, RGB); }},
    {"TEXTURE3 output", gl::NO_ERROR, [](C& c) { c.combinerOutput(gl::COMBINER7_NV, ALPHA, gl::TEXTURE3, DIS, DIS, NONE, NONE, false, false, false); }},
    {"TEXTURE4 does not exist", gl::INVALID_ENUM, [](C& c) { c.combinerInput(S0, RGB, VA, gl::TEXTURE4, UI, RGB); }},
  });
}

TEST_CASE("combiners state: initial values through the queries (RC Tables .5, .6, New State)") {
  Context ctx(*find_builtin_profile("geforce256"), 4, 4);
  CHECK_FALSE(ctx.isEnabled(gl::REGISTER_COMBINERS_NV));
  CHECK_FALSE(ctx.isEnabled(gl::PER_STAGE_CONSTANTS_NV));
  CHECK(ctx.combiner_state().num_general_combiners == 1);
  CHECK(ctx.combiner_state().color_sum_clamp);
  const GLenum table5[2][4][3] = {
      {{gl::PRIMARY_COLOR_NV, RGB, UI}, {gl::ZERO, RGB, gl::UNSIGNED_INVERT_NV}, {gl::ZERO, RGB, UI}, {gl::ZERO, RGB, UI}},
      {{gl::PRIMARY_COLOR_NV, ALPHA, UI}, {gl::ZERO, ALPHA, gl::UNSIGNED_INVERT_NV}, {gl::ZERO, ALPHA, UI}, {gl::ZERO, ALPHA, UI}}};
  for (GLenum stage : {gl::COMBINER0_NV, gl::COMBINER1_NV})
    for (int p = 0; p < 2; ++p)
      for (int v = 0; v < 4; ++v) {
        std::int32_t in = 0, usage = 0, map = 0;
        const GLenum portion = p == 0 ? RGB : ALPHA, var = VA + static_cast<GLenum>(v);
        ctx.getCombinerInputParameteriv(stage, portion, var, gl::COMBINER_INPUT_NV, &in);
        ctx.getCombinerInputParameteriv(stage, portion, var, gl::COMBINER_COMPONENT_USAGE_NV, &usage);
        ctx.getCombinerInputParameteriv(stage, portion, var, gl::COMBINER_MAPPING_NV, &map);
        CHECK(static_cast<GLenum>(in) == table5[p][v][0]);
        CHECK(static_cast<GLenum>(usage) == table5[p][v][1]);
        CHECK(static_cast<GLenum>(map) == table5[p][v][2]);
      }
  const std::pair<GLenum, std::int32_t> outputs[] = {
      {gl::COMBINER_AB_DOT_PRODUCT_NV, 0}, {gl::COMBINER_CD_DOT_PRODUCT_NV, 0}, {gl::COMBINER_MUX_SUM_NV, 0},
      {gl::COMBINER_SCALE_NV, static_cast<std::int32_t>(NONE)}, {gl::COMBINER_BIAS_NV, static_cast<std::int32_t>(NONE)},
      {gl::COMBINER_AB_OUTPUT_NV, static_cast<std::int32_t>(DIS)}, {gl::COMBINER_CD_OUTPUT_NV, static_cast<std::int32_t>(DIS)},
      {gl::COMBINER_SUM_OUTPUT_NV, static_cast<std::int32_t>(SP0)}};
  for (auto [pname, want] : outputs)
    for (GLenum portion : {RGB, ALPHA}) {
      std::int32_t v = -1;
      float f = -1;
      ctx.getCombinerOutputParameteriv(gl::COMBINER1_NV, portion, pname, &v);
      ctx.getCombinerOutputParameterfv(gl::COMBINER1_NV, portion, pname, &f);
      CHECK(v == want);
      CHECK(f == static_cast<float>(want));
    }
  const GLenum table6[7][3] = {{gl::FOG, ALPHA, UI}, {gl::SPARE0_PLUS_SECONDARY_COLOR_NV, RGB, UI}, {gl::FOG, RGB, UI},
                               {gl::ZERO, RGB, UI}, {gl::ZERO, RGB, UI}, {gl::ZERO, RGB, UI}, {SP0, ALPHA, UI}};
  for (int v = 0; v < 7; ++v) {
    std::int32_t in = 0, usage = 0, map = 0;
    ctx.getFinalCombinerInputParameteriv(VA + static_cast<GLenum>(v), gl::COMBINER_INPUT_NV, &in);
    ctx.getFinalCombinerInputParameteriv(VA + static_cast<GLenum>(v), gl::COMBINER_COMPONENT_USAGE_NV, &usage);
    ctx.getFinalCombinerInputParameteriv(VA + static_cast<GLenum>(v), gl::COMBINER_MAPPING_NV, &map);
    CHECK(static_cast<GLenum>(in) == table6[v][0]);
    CHECK(static_cast<GLenum>(usage) == table6[v][1]);
    CHECK(static_cast<GLenum>(map) == table6[v][2]);
  }
  float k[4] = {9, 9, 9, 9};
  ctx.getCombinerStageParameterfv(gl::COMBINER1_NV, gl::CONSTANT_COLOR1_NV, k);
  for (float x : k) CHECK(x == 0);
  CHECK(ctx.getError() == gl::NO_ERROR);
}

TEST_CASE("combiners state: setters round trip through the queries, colours clamp, enables toggle") {
  Context ctx(*find_builtin_profile("geforce256"), 4, 4);
  ctx.enable(gl::REGISTER_COMBINERS_NV);
  ctx.enable(gl::PER_STAGE_CONSTANTS_NV);
  CHECK(ctx.isEnabled(gl::REGISTER_COMBINERS_NV));
  CHECK(ctx.isEnabled(gl::PER_STAGE_CONSTANTS_NV));
  ctx.disable(gl::REGISTER_COMBINERS_NV);
  CHECK_FALSE(ctx.isEnabled(gl::REGISTER_COMBINERS_NV));
  ctx.combinerInput(gl::COMBINER1_NV, ALPHA, VD, gl::TEXTURE1, gl::HALF_BIAS_NEGATE_NV, BLUE);
  float f = 0;
  ctx.getCombinerInputParameterfv(gl::COMBINER1_NV, ALPHA, VD, gl::COMBINER_MAPPING_NV, &f);
  CHECK(f == static_cast<float>(gl::HALF_BIAS_NEGATE_NV));
  ctx.combinerOutput(gl::COMBINER1_NV, RGB, SP1, gl::TEXTURE0, SP0, gl::SCALE_BY_TWO_NV,
                     gl::BIAS_BY_NEGATIVE_ONE_HALF_NV, true, false, true);
  std::int32_t v = 0;
  ctx.getCombinerOutputParameteriv(gl::COMBINER1_NV, RGB, gl::COMBINER_CD_OUTPUT_NV, &v);
  CHECK(static_cast<GLenum>(v) == gl::TEXTURE0);
  ctx.getCombinerOutputParameteriv(gl::COMBINER1_NV, RGB, gl::COMBINER_MUX_SUM_NV, &v);
  CHECK(v == 1);
  const float over[4] = {-0.5f, 0.25f, 1.5f, 1.0f};
  ctx.combinerParameterfv(gl::CONSTANT_COLOR1_NV, over);
  CHECK(ctx.combiner_state().constant_color1 == std::array<double, 4>{0, 0.25, 1, 1});  // clamped (3.8.12.1)
  ctx.combinerStageParameterfv(gl::COMBINER1_NV, gl::CONSTANT_COLOR0_NV, over);
  float k[4];
  ctx.getCombinerStageParameterfv(gl::COMBINER1_NV, gl::CONSTANT_COLOR0_NV, k);
  CHECK(k[0] == 0);
  CHECK(k[2] == 1);  // clamped when specified (RC2 v1.1)
  const std::int32_t ints[4] = {2147483647, -2147483647 - 1, 0, 1073741823};
  ctx.combinerParameteriv(gl::CONSTANT_COLOR0_NV, ints);  // GL121 Table 2.6 signed: (2c+1)/(2^32-1)
  CHECK(ctx.combiner_state().constant_color0[0] == 1.0);
  CHECK(ctx.combiner_state().constant_color0[1] == 0.0);
  CHECK(ctx.combiner_state().constant_color0[2] == 1.0 / 4294967295.0);
  ctx.combinerParameterf(gl::COLOR_SUM_CLAMP_NV, 0);
  CHECK_FALSE(ctx.combiner_state().color_sum_clamp);
  ctx.combinerParameterf(gl::NUM_GENERAL_COMBINERS_NV, 2);
  CHECK(ctx.combiner_state().num_general_combiners == 2);
  CHECK(ctx.combiner_plan().stages.size() == 2);
  ctx.combinerParameteri(gl::NUM_GENERAL_COMBINERS_NV, 1);  // the cached plan follows the state
  CHECK(ctx.combiner_plan().stages.size() == 1);
  CHECK(ctx.getError() == gl::NO_ERROR);
}

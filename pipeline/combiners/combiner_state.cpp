#include "pipeline/combiners/combiner_state.h"

namespace ffsim::combiners {

namespace {
bool is_texture(GLenum e, int texture_units) {
  return e >= gl::TEXTURE0 && e < gl::TEXTURE0 + static_cast<GLenum>(texture_units);
}
bool is_usage(GLenum e) { return e == gl::RGB || e == gl::ALPHA || e == gl::BLUE; }
constexpr Check ok{};
}  // namespace

bool is_register(GLenum e, int texture_units) {
  switch (e) {
    case gl::ZERO:
    case gl::CONSTANT_COLOR0_NV:
    case gl::CONSTANT_COLOR1_NV:
    case gl::FOG:
    case gl::PRIMARY_COLOR_NV:
    case gl::SECONDARY_COLOR_NV:
    case gl::SPARE0_NV:
    case gl::SPARE1_NV: return true;
    default: return is_texture(e, texture_units);
  }
}

bool is_output_register(GLenum e, int texture_units) {
  switch (e) {
    case gl::DISCARD_NV:
    case gl::PRIMARY_COLOR_NV:
    case gl::SECONDARY_COLOR_NV:
    case gl::SPARE0_NV:
    case gl::SPARE1_NV: return true;
    default: return is_texture(e, texture_units);
  }
}

bool is_general_mapping(GLenum e) { return e >= gl::UNSIGNED_IDENTITY_NV && e <= gl::SIGNED_NEGATE_NV; }

int stage_index(GLenum stage, int max_general_combiners) {
  if (stage < gl::COMBINER0_NV || stage >= gl::COMBINER0_NV + static_cast<GLenum>(max_general_combiners)) return -1;
  return static_cast<int>(stage - gl::COMBINER0_NV);
}

int variable_index(GLenum variable, int count) {
  if (variable < gl::VARIABLE_A_NV || variable >= gl::VARIABLE_A_NV + static_cast<GLenum>(count)) return -1;
  return static_cast<int>(variable - gl::VARIABLE_A_NV);
}

Check check_combiner_input(GLenum portion, GLenum variable, GLenum input, GLenum mapping, GLenum usage,
                           int texture_units) {
  if (portion != gl::RGB && portion != gl::ALPHA) return {gl::INVALID_ENUM, "<portion> must be RGB or ALPHA"};
  if (variable_index(variable, 4) < 0)
    return {gl::INVALID_ENUM, "<variable> must be VARIABLE_A_NV .. VARIABLE_D_NV"};
  if (!is_register(input, texture_units))
    return {gl::INVALID_ENUM, "<input> is not a combiner register (RC Table NV_register_combiners.1)"};
  if (!is_general_mapping(mapping)) return {gl::INVALID_ENUM, "<mapping> is not an input mapping (RC Table .4)"};
  if (!is_usage(usage)) return {gl::INVALID_ENUM, "<componentUsage> must be RGB, ALPHA or BLUE"};
  if (portion == gl::ALPHA && usage == gl::RGB)
    return {gl::INVALID_OPERATION, "componentUsage RGB is not allowed in the ALPHA portion"};
  if (portion == gl::RGB && usage == gl::BLUE)
    return {gl::INVALID_OPERATION, "componentUsage BLUE is not allowed in the RGB portion"};
  if (usage == gl::ALPHA && input == gl::FOG)
    return {gl::INVALID_OPERATION, "the FOG alpha (fog factor) is available only in the final combiner"};
  return ok;
}

Check check_combiner_output(GLenum portion, GLenum ab, GLenum cd, GLenum sum, GLenum scale, GLenum bias,
                            bool ab_dot, bool cd_dot, int texture_units) {
  if (portion != gl::RGB && portion != gl::ALPHA) return {gl::INVALID_ENUM, "<portion> must be RGB or ALPHA"};
  for (GLenum o : {ab, cd, sum})
    if (!is_output_register(o, texture_units))
      return {gl::INVALID_ENUM, "an output must be DISCARD_NV or a read/write register"};
  if (scale != gl::NONE && scale != gl::SCALE_BY_TWO_NV && scale != gl::SCALE_BY_FOUR_NV &&
      scale != gl::SCALE_BY_ONE_HALF_NV)
    return {gl::INVALID_ENUM, "<scale> must be NONE, SCALE_BY_TWO_NV, SCALE_BY_FOUR_NV or SCALE_BY_ONE_HALF_NV"};
  if (bias != gl::NONE && bias != gl::BIAS_BY_NEGATIVE_ONE_HALF_NV)
    return {gl::INVALID_ENUM, "<bias> must be NONE or BIAS_BY_NEGATIVE_ONE_HALF_NV"};
  if (portion == gl::ALPHA && (ab_dot || cd_dot))
    return {gl::INVALID_VALUE, "dot products are not available in the ALPHA portion"};
  if (bias == gl::BIAS_BY_NEGATIVE_ONE_HALF_NV && (scale == gl::SCALE_BY_ONE_HALF_NV || scale == gl::SCALE_BY_FOUR_NV))
    return {gl::INVALID_OPERATION, "BIAS_BY_NEGATIVE_ONE_HALF_NV cannot be combined with SCALE_BY_ONE_HALF_NV or SCALE_BY_FOUR_NV"};
  if ((ab != gl::DISCARD_NV && (ab == cd || ab == sum)) || (cd != gl::DISCARD_NV && cd == sum))
    return {gl::INVALID_OPERATION, "abOutput, cdOutput and sumOutput must name distinct registers (or DISCARD_NV)"};
  return ok;
}

Check check_final_combiner_input(GLenum variable, GLenum input, GLenum mapping, GLenum usage, int texture_units) {
  const int v = variable_index(variable, 7);
  if (v < 0) return {gl::INVALID_ENUM, "<variable> must be VARIABLE_A_NV .. VARIABLE_G_NV"};
  const bool pseudo = input == gl::E_TIMES_F_NV || input == gl::SPARE0_PLUS_SECONDARY_COLOR_NV;
  if (!pseudo && !is_register(input, texture_units))
    return {gl::INVALID_ENUM, "<input> is not a combiner register or final-combiner pseudo-register"};
  if (mapping != gl::UNSIGNED_IDENTITY_NV && mapping != gl::UNSIGNED_INVERT_NV)
    return {gl::INVALID_ENUM, "<mapping> must be UNSIGNED_IDENTITY_NV or UNSIGNED_INVERT_NV in the final combiner"};
  if (!is_usage(usage)) return {gl::INVALID_ENUM, "<componentUsage> must be RGB, ALPHA or BLUE"};
  if (v >= 4 && pseudo)
    return {gl::INVALID_OPERATION, "E, F and G cannot take E_TIMES_F_NV or SPARE0_PLUS_SECONDARY_COLOR_NV"};
  if (v == 0 && input == gl::SPARE0_PLUS_SECONDARY_COLOR_NV)
    return {gl::INVALID_OPERATION, "A cannot take SPARE0_PLUS_SECONDARY_COLOR_NV"};
  if (v == 6 && usage == gl::RGB) return {gl::INVALID_OPERATION, "G takes componentUsage ALPHA or BLUE"};
  if (v != 6 && usage == gl::BLUE) return {gl::INVALID_OPERATION, "componentUsage BLUE is only for G"};
  if (pseudo && usage != gl::RGB)
    return {gl::INVALID_OPERATION, "E_TIMES_F_NV and SPARE0_PLUS_SECONDARY_COLOR_NV take componentUsage RGB only"};
  return ok;
}

}  // namespace ffsim::combiners

// NV_register_combiners (RC) and NV_register_combiners2 (RC2) state, as plain
// data with the initial values of RC Tables NV_register_combiners.5 and .6 and
// the "New State" tables of RC and RC2. The enums are kept exactly as the GL
// calls set them so that the Get* queries return them; combiner_plan turns the
// state into the compact form the shading loop runs.
#pragma once
#include <array>
#include <cstdint>

#include "pipeline/gl/enums.h"

namespace ffsim::combiners {

inline constexpr int kMaxGeneralCombiners = 8;  // COMBINER0_NV .. COMBINER7_NV
inline constexpr int kMaxRegisterTextures = 4;  // TEXTURE0_ARB .. TEXTURE3_ARB

// One input variable: CombinerInputNV / FinalCombinerInputNV arguments.
struct VariableState {
  GLenum input = gl::ZERO;
  GLenum mapping = gl::UNSIGNED_IDENTITY_NV;
  GLenum component_usage = gl::RGB;
  bool operator==(const VariableState&) const = default;
};

// One portion (RGB or ALPHA) of a general combiner stage.
struct PortionState {
  std::array<VariableState, 4> var;  // A, B, C, D
  GLenum ab_output = gl::DISCARD_NV;
  GLenum cd_output = gl::DISCARD_NV;
  GLenum sum_output = gl::SPARE0_NV;
  GLenum scale = gl::NONE;
  GLenum bias = gl::NONE;
  bool ab_dot_product = false;
  bool cd_dot_product = false;
  bool mux_sum = false;
  bool operator==(const PortionState&) const = default;
};

struct GeneralStageState {
  PortionState rgb, alpha;
  // RC2 per-stage constants s#ccc0, s#ccc1 (clamped to [0,1] when specified).
  std::array<double, 4> constant_color0{0, 0, 0, 0};
  std::array<double, 4> constant_color1{0, 0, 0, 0};
  bool operator==(const GeneralStageState&) const = default;
};

struct CombinerState {
  bool enabled = false;              // REGISTER_COMBINERS_NV
  bool per_stage_constants = false;  // PER_STAGE_CONSTANTS_NV (RC2)
  int num_general_combiners = 1;     // NUM_GENERAL_COMBINERS_NV
  bool color_sum_clamp = true;       // COLOR_SUM_CLAMP_NV
  // gccc0, gccc1 (RC2 naming): clamped to [0,1] when specified.
  std::array<double, 4> constant_color0{0, 0, 0, 0};
  std::array<double, 4> constant_color1{0, 0, 0, 0};
  std::array<GeneralStageState, kMaxGeneralCombiners> stages = initial_stages();
  std::array<VariableState, 7> final_var = initial_final();  // A .. G
  bool operator==(const CombinerState&) const = default;

  // RC Table NV_register_combiners.5 (as corrected on October 31, 2000).
  static std::array<GeneralStageState, kMaxGeneralCombiners> initial_stages() {
    std::array<GeneralStageState, kMaxGeneralCombiners> s{};
    for (auto& st : s) {
      st.rgb.var = {VariableState{gl::PRIMARY_COLOR_NV, gl::UNSIGNED_IDENTITY_NV, gl::RGB},
                    VariableState{gl::ZERO, gl::UNSIGNED_INVERT_NV, gl::RGB},
                    VariableState{gl::ZERO, gl::UNSIGNED_IDENTITY_NV, gl::RGB},
                    VariableState{gl::ZERO, gl::UNSIGNED_IDENTITY_NV, gl::RGB}};
      st.alpha.var = {VariableState{gl::PRIMARY_COLOR_NV, gl::UNSIGNED_IDENTITY_NV, gl::ALPHA},
                      VariableState{gl::ZERO, gl::UNSIGNED_INVERT_NV, gl::ALPHA},
                      VariableState{gl::ZERO, gl::UNSIGNED_IDENTITY_NV, gl::ALPHA},
                      VariableState{gl::ZERO, gl::UNSIGNED_IDENTITY_NV, gl::ALPHA}};
    }
    return s;
  }
  // RC Table NV_register_combiners.6: standard colour sum and fog.
  static std::array<VariableState, 7> initial_final() {
    return {VariableState{gl::FOG, gl::UNSIGNED_IDENTITY_NV, gl::ALPHA},
            VariableState{gl::SPARE0_PLUS_SECONDARY_COLOR_NV, gl::UNSIGNED_IDENTITY_NV, gl::RGB},
            VariableState{gl::FOG, gl::UNSIGNED_IDENTITY_NV, gl::RGB},
            VariableState{gl::ZERO, gl::UNSIGNED_IDENTITY_NV, gl::RGB},
            VariableState{gl::ZERO, gl::UNSIGNED_IDENTITY_NV, gl::RGB},
            VariableState{gl::ZERO, gl::UNSIGNED_IDENTITY_NV, gl::RGB},
            VariableState{gl::SPARE0_NV, gl::UNSIGNED_IDENTITY_NV, gl::ALPHA}};
  }
};

// Validation shared by the GL entry points (sim/context_combiners.cpp) and the
// tests. Each returns gl::NO_ERROR or the error RC's Errors section (or the
// general GL rule for unaccepted enums, INVALID_ENUM) prescribes, and a message.
struct Check {
  GLenum error = gl::NO_ERROR;
  const char* message = "";
  explicit operator bool() const { return error == gl::NO_ERROR; }
};

// Register names accepted as <input> of CombinerInputNV (RC Table .1), for an
// implementation with `texture_units` texture units.
bool is_register(GLenum e, int texture_units);
// Register names with output status read/write (plus DISCARD_NV).
bool is_output_register(GLenum e, int texture_units);
bool is_general_mapping(GLenum e);

Check check_combiner_input(GLenum portion, GLenum variable, GLenum input, GLenum mapping, GLenum usage,
                           int texture_units);
Check check_combiner_output(GLenum portion, GLenum ab, GLenum cd, GLenum sum, GLenum scale, GLenum bias,
                            bool ab_dot, bool cd_dot, int texture_units);
Check check_final_combiner_input(GLenum variable, GLenum input, GLenum mapping, GLenum usage, int texture_units);

// COMBINER<i>_NV -> i when i < max_general_combiners, else -1.
int stage_index(GLenum stage, int max_general_combiners);
// VARIABLE_A_NV.. -> 0.., -1 when not one of the first `count` variables.
int variable_index(GLenum variable, int count);

}  // namespace ffsim::combiners

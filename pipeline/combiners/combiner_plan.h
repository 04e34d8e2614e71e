// The combiner plan: CombinerState turned into the compact form the shading
// loop runs, with everything nothing reads left out.
//
// Liveness runs backwards from the final combiner: a general-combiner output
// (AB, CD or SUM of the RGB or ALPHA portion) is computed only if a later stage
// or the final combiner reads a component it writes; a portion with no such
// output is skipped, and so are the products only skipped outputs use. The
// registers live at the input of stage 0 name the texture units that must be
// sampled (SPARE0 alpha counts as texture 0 alpha). Skipping never changes a bit
// of the result: tests/pipeline/test_combiner_plan.cpp compares the planned path
// with the compute-everything plan (plan_combiners(..., false)).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "pipeline/combiners/combiner_state.h"
#include "pipeline/combiners/input_mapping.h"
#include "pipeline/combiners/register_file.h"
#include "pipeline/number/profile.h"

namespace ffsim::combiners {

// Where a fixed-point stage rounds (docs/numerics.md §10, choice #22).
enum class CombinerRounding : std::uint8_t {
  PerStage,    // exact inside a stage, one rounding per register write (default)
  PerProduct,  // additionally round every product (and dot-product term) to the register grid
};

struct CombinerConfig {
  Arithmetic arithmetic = Arithmetic::Fixed;
  int combiner_bits = 9;
  int color_bits = 8;
  int texture_bits = 8;
  int texture_units = 2;
  int general_combiners = 2;
  CombinerRounding rounding = CombinerRounding::PerStage;
  // RC2 v1.2 defines SECONDARY_COLOR_NV alpha as the secondary colour's alpha
  // (NV2x); on NV1x it is undefined, which ffsim makes 0 (choice #24, default).
  bool rc2_secondary_alpha = false;

  static CombinerConfig from_profile(const Profile& p);
};

// One variable: register (or final pseudo-register), the components the three
// lanes read (RGB usage 0,1,2; ALPHA 3,3,3; BLUE 2,2,2) and its mapping.
struct PlannedVar {
  std::uint8_t reg = kZero;
  std::array<std::uint8_t, 3> comp{0, 1, 2};
  Mapping mapping = Mapping::UnsignedIdentity;
  MappingCoeffs k{};
};

struct PlannedPortion {
  bool run = false;  // any output computed
  bool need_ab = false, need_cd = false;
  bool ab_dot = false, cd_dot = false, mux = false;
  std::array<std::int8_t, 3> dest{-1, -1, -1};  // AB, CD, SUM register, -1 = not written
  std::int32_t scale2 = 2;                      // 2 * scale: 1 (x1/2), 2, 4, 8 (x4)
  bool bias = false;                            // BIAS_BY_NEGATIVE_ONE_HALF_NV
  std::array<PlannedVar, 4> var{};              // A, B, C, D
};

struct PlannedStage {
  int index = 0;
  PlannedPortion rgb, alpha;
  bool own_constants = false;  // RC2 per-stage constants replace CONSTANT_COLOR0/1 for this stage
  std::array<std::array<std::int32_t, 4>, 2> constant_codes{};
  std::array<std::array<double, 4>, 2> constant_values{};
};

struct PlannedFinal {
  std::array<PlannedVar, 7> var{};  // A .. G (mapping UnsignedIdentity or UnsignedInvert)
  bool need_ef = false;             // E_TIMES_F_NV read by A..D
  bool need_spare0_plus_secondary = false;
  bool color_sum_clamp = true;
};

struct CombinerPlan {
  CombinerConfig config;
  std::int32_t M = 255;  // register code of +1.0
  std::vector<PlannedStage> stages;  // the NUM_GENERAL_COMBINERS_NV active stages, in order
  PlannedFinal final;
  std::array<std::array<std::int32_t, 4>, 2> constant_codes{};  // global ccc0, ccc1 as register codes
  std::array<std::array<double, 4>, 2> constant_values{};
  // Inputs the plan reads (what the rasterizer must produce).
  std::array<bool, kMaxRegisterTextures> texture_needed{};
  bool primary_needed = false, secondary_needed = false;
  bool fog_factor_needed = false;  // FOG alpha (the fog colour is a per-draw constant)
  // The final RGB can exceed 2 (COLOR_SUM_CLAMP off and SPARE0_PLUS_SECONDARY in D
  // and in B or C): GeForce 256 computes such values incorrectly (RC "NVIDIA
  // Implementation Details"); ffsim computes the ideal value (choice #28).
  bool final_may_exceed_two = false;
  bool skip_dead = true;
};

// skip_dead = false gives the compute-everything plan (every portion runs,
// every output is written, every input is loaded): the reference for tests.
CombinerPlan plan_combiners(const CombinerState& state, const CombinerConfig& config, bool skip_dead = true);

}  // namespace ffsim::combiners

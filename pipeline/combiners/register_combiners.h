// Register-combiner shading: the entry point the rasterizer calls per span when
// REGISTER_COMBINERS_NV is enabled (RC §3.8.11: the fragment colour becomes fcoc;
// texture environments, colour sum and fog application are bypassed, texture
// fetching still happens).
//
//   CombinerPlan plan = plan_combiners(state, CombinerConfig::from_profile(profile));
//   shade_span(plan, inputs, fog_color, out);   // fixed: out = 4 codes per fragment
//
// Pure functions of (plan, inputs); the plan says which inputs are read
// (texture_needed, primary_needed, secondary_needed, fog_factor_needed), so a
// caller may leave the others nullptr.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "pipeline/combiners/combiner_plan.h"

namespace ffsim::combiners {

// Register values (real values: code / M in fixed profiles) after each general
// stage of the first fragment of a span, for single-pixel tracing (--probe).
struct RegisterTrace {
  std::vector<std::array<std::array<double, 4>, kRegisterCount>> after_stage;  // one per planned stage
};

// Fixed profiles: out receives 4 codes per fragment (R,G,B,A) at config.color_bits.
// fog_color: the GL fog colour (clamped to [0,1] when it was set), rounded to the
// colour width on entry like the constants (choice #36).
void shade_span(const CombinerPlan& plan, const CombinerInputsFixed& in, const std::array<double, 4>& fog_color,
                std::uint16_t* out, RegisterTrace* trace = nullptr);

// Float profiles (config.arithmetic Float32 or Float64): out receives 4 values per
// fragment in [0,1]; with Float32 every value is a binary32 (converted to double).
void shade_span(const CombinerPlan& plan, const CombinerInputsFloat& in, const std::array<double, 4>& fog_color,
                double* out, RegisterTrace* trace = nullptr);

}  // namespace ffsim::combiners

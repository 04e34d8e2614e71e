// The colour stage fed one known source colour (docs/performance.md 34.1).
//
// When every fragment of a group carries the same colour codes (no texturing,
// colour sum or register combiners, and one primary colour at every vertex),
// the blend equation and factors may write back exactly what each pixel holds,
// whatever it holds. The paper's antialiased passes (section 4.2) draw such a
// pass: GL_DST_ALPHA, GL_ONE with the source alpha clamp(penumbra/2 − 1, 0, 1),
// which is 0 at the default penumbra 2, so A = A_s·A_d + A_d = A_d everywhere.
// Left out, such a colour stage changes no bit.
#pragma once
#include <array>
#include <cstdint>

#include "pipeline/fragment/fragment_plan.h"

namespace ffsim {

// Whether the colour stage of a fixed-profile plan stores, for every written
// channel and every destination colour, the destination's own code when every
// fragment's colour codes are `source` (codes over M = k.color_max). Exact
// where it says yes (GL121 §4.1.6 with blend_code's rounding, blend.h):
//   - a kept channel (masked, or the key's equation leaves the destination);
//   - MIN with s_c = M, MAX with s_c = 0;
//   - FUNC_ADD, FUNC_REVERSE_SUBTRACT, or the destination term alone, when the
//     source term s_c·S is 0 for every destination (s_c = 0, or a factor S
//     that does not read the destination and is 0) and the destination factor
//     does not read the destination and is M (ONE, or e.g. ONE_MINUS_SRC_ALPHA
//     with A_s = 0): n = d_c·M, and floor((2n + M) / 2M) = d_c.
// Anything else (the source copied, FUNC_SUBTRACT, a logic op, float
// arithmetic) is no: the stage then runs.
bool colour_stage_keeps(const FragmentPlanKey& key, const FragmentConstants& k,
                        const std::array<std::uint32_t, 4>& source);

}  // namespace ffsim

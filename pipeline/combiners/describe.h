// A register-combiner setup printed as equations (for `--explain`): one line per
// output that is computed (dead outputs and skipped stages left out, as in the
// plan), trivial terms removed (products with 0 or 1, sums with 0, constant
// registers folded), e.g. for the paper's section-5 pass:
//
//   stage 0 rgb:   spare0.rgb = dot(expand(const0.rgb), expand(tex0.rgb))
//                  spare1.rgb = dot(expand(const1.rgb), expand(tex1.rgb))
//   stage 1 alpha: spare0.a = spare0.b + spare1.b
//   final:         fcoc.rgb = 0
//                  fcoc.a = max(spare0.a, 0)
//
// Notation: expand(x) = 2x - 1 (EXPAND_NORMAL), -expand(x) (EXPAND_NEGATE),
// (x - 1/2) / (1/2 - x) (HALF_BIAS_*), (1 - x) (UNSIGNED_INVERT), max(x, 0)
// (UNSIGNED_IDENTITY of a register an earlier stage may have made negative; it is
// dropped for registers that are still non-negative inputs), -x (SIGNED_NEGATE).
// Every general-combiner output is clamped to [-1, 1] (not printed).
#pragma once
#include <string>

#include "pipeline/combiners/combiner_plan.h"

namespace ffsim::combiners {

std::string describe(const CombinerPlan& plan);

}  // namespace ffsim::combiners

// The register combiners' span kernel (docs/performance.md): the arithmetic of
// shade_span (register_combiners.h) for fixed profiles, restructured for speed
// but not changed:
//   - registers in struct-of-arrays form, a chunk of fragments per pass, so each
//     mapping, product and output rounding is a loop over fragments the
//     compiler vectorises;
//   - the register maximum M a compile-time constant for the built-in widths
//     (255, 1023, 4095: divisions by 4M, 8M and M^4 become multiplications),
//     with 32-bit intermediates where the ranges allow (|mapped| <= 2M, a stage's
//     biased, scaled sum <= 208·M^2 and its doubled rounding numerator < 2^31
//     for M <= 2047);
//   - only what the plan marks live is loaded or computed.
// The generic shade_span stays the reference (and serves --probe's register
// trace); tests/pipeline/test_fast_combiners.cpp compares the two on random
// plans and inputs.
#pragma once
#include <array>
#include <cstdint>

#include "pipeline/combiners/combiner_plan.h"

namespace ffsim::combiners {

// shade_span(plan, in, fog_color, out) for a fixed-point plan. Returns false
// (nothing written) when the kernel does not apply (float arithmetic); the
// caller then runs shade_span.
bool shade_span_fast(const CombinerPlan& plan, const CombinerInputsFixed& in, const std::array<double, 4>& fog_color,
                     std::uint16_t* out);

}  // namespace ffsim::combiners

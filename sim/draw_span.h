// What the draw path keeps per window-space vertex (sim/draw.cpp builds them,
// sim/draw_span.cpp's span path and the per-fragment path read them).
#pragma once
#include <array>
#include <cstdint>

#include "pipeline/raster/triangle.h"
#include "sim/context.h"

namespace ffsim {

// Context::window_position and window_attributes write every member (depth 0
// without a depth buffer; tcw only for the units the draw's plan samples, the
// only ones any reader takes), so the draw path's vertex arrays
// (WindowVertices) grow without a fill; `WindowVertex{}` is all zeros.
struct WindowVertex {
  SnappedVertex p;
  std::array<std::uint32_t, 4> color_code, secondary_code;
  std::array<double, 4> color, secondary;
  std::uint32_t depth;
  std::array<std::array<double, 3>, kMaxTextureUnits> tcw;  // s/w, t/w, q/w
};

// The span path's sharing of texture coordinates (sim/draw_span.cpp): bit u is
// set when sampled unit u has the same s/w, t/w, q/w at all three vertices as the
// last earlier sampled unit whose coordinates are computed, and so the same s/q,
// t/q (computed once). (−0 == +0 gives the same sums, every sum starts from +0;
// a NaN never compares equal: it recomputes.)
unsigned coords_reuse_mask(const ShadingPlan& plan, const std::array<const WindowVertex*, 3>& tv);
// Fewer than two sampled units: every coords_reuse_mask is 0, whatever the triangle.
inline bool coords_may_be_reused(const ShadingPlan& plan) {
  int sampled = 0;
  for (const bool s : plan.sample) sampled += s ? 1 : 0;
  return sampled >= 2;
}

// s/q and t/q of unit u at the fragments of `runs` of a triangle (sim/draw_span.cpp):
// the per-fragment path's binary64 values rounded to binary32, as the sampler
// rounds them (sample_level), bit for bit. Writes runs.count values to s and t,
// plus up to 3 scratch values past the end (s and t must hold runs.count + 3).
void texture_coordinates(const std::array<const WindowVertex*, 3>& tv, int u, const TriangleCoverage& cov,
                         const FastRuns& runs, float* s, float* t);

}  // namespace ffsim

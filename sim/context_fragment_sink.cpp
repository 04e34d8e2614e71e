// Where fragments go: pixel-rectangle fragments (DrawPixels/CopyPixels) and the
// per-fragment operations (GL 1.2.1 §4.1) through the current plan.
//
// - pixel_fragments (GL121 §3.6.4 "Conversion to Fragments"): when a texture
//   unit is enabled, every fragment is textured with the raster position's
//   texture coordinates (s/q, t/q) at λ = 0, the texture environments run on the
//   fragment's colour as primary colour, and the colour sum adds a zero
//   secondary colour (spec-notes choice #12); then write_fragments. When nothing
//   shades (shading_active false) the span goes to write_fragments unchanged.
// - write_fragments (scissor, alpha, stencil, depth, blend, dither, masks,
//   GL121 §4.1): the cached per-fragment plan for the current state
//   (pipeline/fragment/fragment_plan.h).
#include <utility>

#include "sim/context.h"

namespace ffsim {

void Context::pixel_fragments(FragmentSpan& span) {
  const ShadingState st = shading_state();
  const ShadingPlan plan = shading_plan(st);
  if (shading_active(plan)) {
    if (on_explain_) on_explain_(ffsim::explain_shading(st, plan));
    UnitTexCoords tc{};
    for (int u = 0; u < kMaxTextureUnits; ++u) {
      const auto& r = raster_pos_.texcoord[u];
      tc[u] = {r[0] / r[3], r[1] / r[3], 0.0};  // λ = 0 (ρ ≡ 1, §3.8.5)
    }
    const bool fixed = st.color.fixed();
    const Rgba secondary{};  // zero
    for (int i = 0; i < span.count; ++i) {
      Rgba primary;
      const std::size_t o = 4 * static_cast<std::size_t>(i);
      for (int c = 0; c < 4; ++c) {
        if (fixed) primary.code[c] = span.codes[o + c];
        else primary.value[c] = span.values[o + c];
      }
      const Rgba out = shade_fragment(st, plan, primary, secondary, tc);
      for (int c = 0; c < 4; ++c) {
        if (fixed) span.codes[o + c] = static_cast<std::uint16_t>(out.code[c]);
        else span.values[o + c] = out.value[c];
      }
    }
  }
  write_fragments(span);
}

FragmentBuffers Context::fragment_buffers() {
  FragmentBuffers b;
  if (fb_.format().float_color()) b.values = fb_.values().data();
  else b.codes = fb_.codes().data();
  if (fb_.has_stencil()) b.stencil = fb_.stencil().data();
  if (fb_.has_depth()) b.depth = fb_.depth_untracked();  // (its writers report a change: depth_changed)
  return b;
}

void Context::sum_band_counts() {
  for (BandCounts& k : band_counts_) {
    fast_runs_ += std::exchange(k.fast_runs, 0);
    fragments_written_ += std::exchange(k.fragments, 0);
  }
}

void Context::write_fragments(FragmentSpan& span) {
  fragments_written_ += static_cast<std::uint64_t>(span.count);
  update_fragment_plan();
  const FragmentBuffers b = fragment_buffers();  // (a depth change is reported below)
  // --probe: the probed pixel's fragment and framebuffer before and after the
  // per-fragment operations (the plan itself is not instrumented).
  int probed = -1;
  std::string before;
  for (int i = 0; i < span.count && probed < 0; ++i)
    if (probe_.hits(span.x0 + i, span.y)) probed = i;
  if (probed >= 0) before = probe_describe_buffers(span.x0 + probed, span.y);
  const bool fl = fb_.format().float_color();
  std::string fragment;
  if (probed >= 0)
    fragment = fl ? describe_values(&span.values[4 * static_cast<std::size_t>(probed)])
                  : describe_codes(&span.codes[4 * static_cast<std::size_t>(probed)], fb_.format().color_bits);
  if (run_fragment_plan(*fragment_current_plan_, fragment_current_constants_, span, b, fb_.width())) fb_.depth_changed();
  if (probed >= 0)
    probe_.record("write_fragments", std::string("fragment ") + fragment + (span.depth.empty() ? std::string()
                                         : std::string(" depth ") + std::to_string(span.depth[static_cast<std::size_t>(probed)])) +
                                         "\n    before: " + before + "\n    after:  " +
                                         probe_describe_buffers(span.x0 + probed, span.y));
}

}  // namespace ffsim

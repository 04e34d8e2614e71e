#include "pipeline/texenv/shading.h"

#include "pipeline/gl/enum_names.h"

namespace ffsim {

bool ShadingPlan::any_texturing() const {
  for (int u = 0; u < kShadeUnits; ++u)
    if (sample[u] || env[u]) return true;
  return false;
}

ShadingPlan full_shading_plan(const ShadingState& st) {
  ShadingPlan p;
  for (int u = 0; u < kShadeUnits; ++u) p.sample[u] = p.env[u] = st.units[u].texture != nullptr;
  p.color_sum = st.color_sum;
  return p;
}

ShadingPlan plan_shading(const ShadingState& st) {
  ShadingPlan p;
  p.color_sum = st.color_sum;
  bool needed = true;  // is the output of the unit being looked at read downstream?
  for (int u = kShadeUnits - 1; u >= 0; --u) {
    const ShadeUnit& su = st.units[u];
    if (su.texture == nullptr) continue;  // disabled: passes its input through
    if (!needed) continue;                // overwritten by a later unit
    const TexEnvReads r = texenv_reads(su.env, su.texture->levels[su.texture->params.base_level].base);
    p.env[u] = true;
    p.sample[u] = r.texture;
    needed = r.previous;
  }
  return p;
}

std::string explain_shading(const ShadingState& st, const ShadingPlan& plan) {
  std::string out;
  for (int u = 0; u < st.unit_count; ++u) {
    const ShadeUnit& su = st.units[u];
    out += "texture unit " + std::to_string(u) + ": ";
    if (su.texture == nullptr) {
      out += "off\n";
      continue;
    }
    if (!plan.env[u]) {
      out += "skipped (a later unit ignores its result)\n";
      continue;
    }
    if (plan.sample[u]) {
      const TextureParams& tp = su.texture->params;
      out += std::string("sample TEXTURE_") + (su.dims == 1 ? "1D" : "2D") + " min " + gl::enum_name(tp.min_filter) +
             " mag " + gl::enum_name(tp.mag_filter) + "; ";
    } else {
      out += "no sampling (no TEXTURE source); ";
    }
    out += "env " + gl::enum_name(su.env.mode);
    if (su.env.mode == gl::COMBINE)
      out += " rgb " + gl::enum_name(su.env.combine_rgb) + " alpha " + gl::enum_name(su.env.combine_alpha);
    out += "\n";
  }
  out += plan.color_sum ? "color sum: primary + secondary\n" : "color sum: off\n";
  return out;
}

void fetch_texels(const ShadingState& st, const ShadingPlan& plan, const UnitTexCoords& tc, UnitTexels& out) {
  for (int u = 0; u < kShadeUnits; ++u) {
    if (!plan.sample[u]) continue;
    const ShadeUnit& su = st.units[u];
    out[u] = sample_texture(*su.texture, su.dims, tc[u].s, tc[u].t, tc[u].lambda, st.sample);
  }
}

Rgba texture_environments(const ShadingState& st, const ShadingPlan& plan, const Rgba& primary,
                          const Rgba& secondary, const UnitTexels& texels) {
  Rgba c = primary;
  for (int u = 0; u < kShadeUnits; ++u) {
    if (!plan.env[u]) continue;
    if (plan.sample[u]) {
      c = texture_environment(st.units[u].env, c, primary, texels[u], st.color);
    } else {
      // Not sampled: the environment reads no texel values, but the classic
      // functions still branch on the texture's base format, which is state.
      Texel t{};
      t.base = st.units[u].texture->levels[static_cast<std::size_t>(st.units[u].texture->params.base_level)].base;
      c = texture_environment(st.units[u].env, c, primary, t, st.color);
    }
  }
  if (plan.color_sum) c = color_sum(c, secondary, st.color);
  return c;
}

}  // namespace ffsim

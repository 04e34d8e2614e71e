#include "pipeline/combiners/combiner_plan.h"

#include <algorithm>

#include "pipeline/number/snorm.h"
#include "pipeline/number/unorm.h"

namespace ffsim::combiners {

CombinerConfig CombinerConfig::from_profile(const Profile& p) {
  CombinerConfig c;
  c.arithmetic = p.arithmetic;
  c.combiner_bits = p.combiner_bits;
  c.color_bits = p.color_bits;
  c.texture_bits = p.texture_bits;
  c.texture_units = p.texture_units;
  c.general_combiners = p.general_combiners;
  return c;
}

namespace {

using Live = std::uint64_t;  // bit 4*register + component

constexpr Live bit(int reg, int comp) { return Live{1} << (4 * reg + comp); }

PlannedVar plan_var(const VariableState& v, std::int32_t M) {
  PlannedVar p;
  const int r = register_index(v.input);
  p.reg = static_cast<std::uint8_t>(r < 0 ? kZero : r);
  if (v.component_usage == gl::ALPHA) p.comp = {3, 3, 3};
  else if (v.component_usage == gl::BLUE) p.comp = {2, 2, 2};
  else p.comp = {0, 1, 2};
  p.mapping = mapping_from_gl(v.mapping);
  p.k = mapping_coeffs(p.mapping, M);
  return p;
}

// Components of ordinary registers a variable reads (pseudo-registers read none).
Live reads(const PlannedVar& v, int lanes) {
  if (v.reg >= kRegisterCount) return 0;
  Live m = 0;
  for (int i = 0; i < lanes; ++i) m |= bit(v.reg, v.comp[static_cast<std::size_t>(i)]);
  return m;
}

PlannedPortion plan_portion(const PortionState& s, std::int32_t M) {
  PlannedPortion p;
  for (std::size_t i = 0; i < 4; ++i) p.var[i] = plan_var(s.var[i], M);
  p.ab_dot = s.ab_dot_product;
  p.cd_dot = s.cd_dot_product;
  p.mux = s.mux_sum;
  const GLenum outs[3] = {s.ab_output, s.cd_output, s.sum_output};
  for (std::size_t i = 0; i < 3; ++i)
    p.dest[i] = static_cast<std::int8_t>(outs[i] == gl::DISCARD_NV ? -1 : register_index(outs[i]));
  switch (s.scale) {
    case gl::SCALE_BY_ONE_HALF_NV: p.scale2 = 1; break;
    case gl::SCALE_BY_TWO_NV: p.scale2 = 4; break;
    case gl::SCALE_BY_FOUR_NV: p.scale2 = 8; break;
    default: p.scale2 = 2; break;
  }
  p.bias = s.bias == gl::BIAS_BY_NEGATIVE_ONE_HALF_NV;
  p.run = p.need_ab = p.need_cd = true;
  return p;
}

// Liveness of one portion: drops outputs nobody reads (when skip_dead), returns
// the components it writes and adds the ones it reads.
void portion_liveness(PlannedPortion& p, Live live_after, int comp_mask, int lanes, bool skip_dead,
                      Live& writes, Live& reads_out) {
  for (auto& d : p.dest) {
    if (d < 0) continue;
    const Live m = static_cast<Live>(comp_mask) << (4 * d);
    writes |= m;
    if (skip_dead && (live_after & m) == 0) d = -1;
  }
  if (skip_dead) {
    const bool sum = p.dest[2] >= 0;
    p.need_ab = p.dest[0] >= 0 || sum;
    p.need_cd = p.dest[1] >= 0 || sum;
    p.run = p.need_ab || p.need_cd;
  }
  if (p.need_ab) reads_out |= reads(p.var[0], lanes) | reads(p.var[1], lanes);
  if (p.need_cd) reads_out |= reads(p.var[2], lanes) | reads(p.var[3], lanes);
  if (p.mux && (p.dest[2] >= 0 || !skip_dead)) reads_out |= bit(kSpare0, 3);
}

int final_var_max(const PlannedVar& v, bool clamp) {  // upper bound of a final RGB variable, in units of 1
  if (v.mapping == Mapping::UnsignedInvert) return 1;
  if (v.reg == kZero) return 0;
  if (v.reg == kSpare0PlusSecondary && !clamp) return 2;
  return 1;
}

}  // namespace

CombinerPlan plan_combiners(const CombinerState& s, const CombinerConfig& cfg, bool skip_dead) {
  CombinerPlan p;
  p.config = cfg;
  p.M = snorm_max(cfg.combiner_bits);
  p.skip_dead = skip_dead;
  const std::int32_t M = p.M;
  auto code = [&](double x) {
    return snorm_from_unorm(unorm_from_double(x, cfg.color_bits), cfg.color_bits, cfg.combiner_bits);
  };
  for (std::size_t c = 0; c < 4; ++c) {
    p.constant_values[0][c] = s.constant_color0[c];
    p.constant_values[1][c] = s.constant_color1[c];
    p.constant_codes[0][c] = code(s.constant_color0[c]);
    p.constant_codes[1][c] = code(s.constant_color1[c]);
  }

  const int ngc = std::clamp(s.num_general_combiners, 1, std::min(cfg.general_combiners, kMaxGeneralCombiners));
  for (int i = 0; i < ngc; ++i) {
    const GeneralStageState& gs = s.stages[static_cast<std::size_t>(i)];
    PlannedStage st;
    st.index = i;
    st.rgb = plan_portion(gs.rgb, M);
    st.alpha = plan_portion(gs.alpha, M);
    st.own_constants = s.per_stage_constants;
    for (std::size_t c = 0; c < 4; ++c) {
      st.constant_values[0][c] = gs.constant_color0[c];
      st.constant_values[1][c] = gs.constant_color1[c];
      st.constant_codes[0][c] = code(gs.constant_color0[c]);
      st.constant_codes[1][c] = code(gs.constant_color1[c]);
    }
    p.stages.push_back(st);
  }

  PlannedFinal& f = p.final;
  for (std::size_t v = 0; v < 7; ++v) f.var[v] = plan_var(s.final_var[v], M);
  f.color_sum_clamp = s.color_sum_clamp;
  Live live = reads(f.var[6], 1);
  for (std::size_t v = 0; v < 4; ++v) {
    live |= reads(f.var[v], 3);
    if (f.var[v].reg == kETimesF) f.need_ef = true;
    if (f.var[v].reg == kSpare0PlusSecondary) f.need_spare0_plus_secondary = true;
  }
  if (f.need_ef || !skip_dead) live |= reads(f.var[4], 3) | reads(f.var[5], 3);
  if (f.need_spare0_plus_secondary || !skip_dead) {
    for (int c = 0; c < 3; ++c) live |= bit(kSpare0, c) | bit(kSecondaryColor, c);
  }
  if (!skip_dead) f.need_ef = f.need_spare0_plus_secondary = true;
  p.final_may_exceed_two = std::max(final_var_max(f.var[1], f.color_sum_clamp),
                                    final_var_max(f.var[2], f.color_sum_clamp)) +
                               final_var_max(f.var[3], f.color_sum_clamp) >
                           2;

  for (int i = ngc - 1; i >= 0; --i) {
    PlannedStage& st = p.stages[static_cast<std::size_t>(i)];
    Live writes = 0, rd = 0;
    portion_liveness(st.rgb, live, 0x7, 3, skip_dead, writes, rd);
    portion_liveness(st.alpha, live, 0x8, 1, skip_dead, writes, rd);
    live = (live & ~writes) | rd;
  }

  if (!skip_dead) live = ~Live{0};
  for (int u = 0; u < kMaxRegisterTextures; ++u)
    p.texture_needed[static_cast<std::size_t>(u)] = (live & (Live{0xF} << (4 * (kTexture0 + u)))) != 0;
  if (live & bit(kSpare0, 3)) p.texture_needed[0] = true;  // SPARE0 alpha starts as texture 0 alpha
  p.primary_needed = (live & (Live{0xF} << (4 * kPrimaryColor))) != 0;
  p.secondary_needed = (live & (Live{0xF} << (4 * kSecondaryColor))) != 0;
  p.fog_factor_needed = (live & bit(kFog, 3)) != 0;
  return p;
}

}  // namespace ffsim::combiners

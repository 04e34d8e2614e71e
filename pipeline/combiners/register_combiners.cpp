#include "pipeline/combiners/register_combiners.h"

#include <cstring>

#include "pipeline/combiners/final_combiner.h"
#include "pipeline/combiners/general_combiner.h"
#include "pipeline/number/snorm.h"
#include "pipeline/number/unorm.h"

namespace ffsim::combiners {

namespace {

// Unsigned code at `bits` -> register code (exact when the grids agree).
struct Entry {
  int bits, combiner_bits;
  bool identity;
  Entry(int b, int cb, std::int32_t M) : bits(b), combiner_bits(cb), identity(static_cast<std::uint32_t>(M) == unorm_max(b)) {}
  std::int32_t operator()(std::uint16_t k) const {
    return identity ? std::int32_t{k} : snorm_from_unorm(k, bits, combiner_bits);
  }
};

template <class T>
void record(RegisterTrace* trace, int i, const RegisterSet<T>& r, double scale) {
  if (!trace || i != 0) return;
  auto& snap = trace->after_stage.emplace_back();
  for (int k = 0; k < kRegisterCount; ++k)
    for (int c = 0; c < 4; ++c) snap[static_cast<std::size_t>(k)][static_cast<std::size_t>(c)] = static_cast<double>(r.v[k][c]) / scale;
}

template <class Acc>
void shade_fixed(const CombinerPlan& plan, const CombinerInputsFixed& in, const std::array<double, 4>& fog_color,
                 std::uint16_t* out, RegisterTrace* trace) {
  const CombinerConfig& cfg = plan.config;
  const std::int32_t M = plan.M;
  const Entry color(cfg.color_bits, cfg.combiner_bits, M), texel(cfg.texture_bits, cfg.combiner_bits, M);
  std::int32_t fog[3];
  for (int c = 0; c < 3; ++c)
    fog[c] = color(static_cast<std::uint16_t>(unorm_from_double(fog_color[static_cast<std::size_t>(c)], cfg.color_bits)));
  const bool per_product = cfg.rounding == CombinerRounding::PerProduct;
  bool own_constants = false;
  for (const PlannedStage& st : plan.stages) own_constants |= st.own_constants;

  RegisterSet<std::int32_t> r;
  for (int i = 0; i < in.count; ++i) {
    std::memset(&r, 0, sizeof r);
    for (int c = 0; c < 4; ++c) {
      r.v[kConstantColor0][c] = plan.constant_codes[0][static_cast<std::size_t>(c)];
      r.v[kConstantColor1][c] = plan.constant_codes[1][static_cast<std::size_t>(c)];
    }
    for (int c = 0; c < 3; ++c) r.v[kFog][c] = fog[c];
    r.v[kFog][3] = in.fog_factor ? color(in.fog_factor[i]) : M;
    const std::size_t q = 4 * static_cast<std::size_t>(i);
    if (plan.primary_needed)
      for (int c = 0; c < 4; ++c) r.v[kPrimaryColor][c] = color(in.primary[q + static_cast<std::size_t>(c)]);
    if (plan.secondary_needed && in.secondary) {
      for (int c = 0; c < 3; ++c) r.v[kSecondaryColor][c] = color(in.secondary[q + static_cast<std::size_t>(c)]);
      if (cfg.rc2_secondary_alpha) r.v[kSecondaryColor][3] = color(in.secondary[q + 3]);
    }
    for (int u = 0; u < kMaxRegisterTextures; ++u) {
      const std::uint16_t* t = in.texture[static_cast<std::size_t>(u)];
      if (!plan.texture_needed[static_cast<std::size_t>(u)] || !t) continue;
      for (int c = 0; c < 4; ++c) r.v[kTexture0 + u][c] = texel(t[q + static_cast<std::size_t>(c)]);
    }
    r.v[kSpare0][3] = r.v[kTexture0][3];
    for (const PlannedStage& st : plan.stages) {
      if (st.own_constants)
        for (int c = 0; c < 4; ++c) {
          r.v[kConstantColor0][c] = st.constant_codes[0][static_cast<std::size_t>(c)];
          r.v[kConstantColor1][c] = st.constant_codes[1][static_cast<std::size_t>(c)];
        }
      general_combiner_fixed(st, r, M, per_product);
      record(trace, i, r, static_cast<double>(M));
    }
    if (own_constants)  // RC2: the final combiner always reads the global constants
      for (int c = 0; c < 4; ++c) {
        r.v[kConstantColor0][c] = plan.constant_codes[0][static_cast<std::size_t>(c)];
        r.v[kConstantColor1][c] = plan.constant_codes[1][static_cast<std::size_t>(c)];
      }
    final_combiner_fixed<Acc>(plan.final, r, M, cfg.color_bits, out + q);
  }
}

template <class T>
void shade_float(const CombinerPlan& plan, const CombinerInputsFloat& in, const std::array<double, 4>& fog_color,
                 double* out, RegisterTrace* trace) {
  const CombinerConfig& cfg = plan.config;
  RegisterSet<T> r;
  for (int i = 0; i < in.count; ++i) {
    for (auto& reg : r.v)
      for (T& x : reg) x = T(0);
    for (std::size_t c = 0; c < 4; ++c) {
      r.v[kConstantColor0][c] = static_cast<T>(plan.constant_values[0][c]);
      r.v[kConstantColor1][c] = static_cast<T>(plan.constant_values[1][c]);
    }
    for (std::size_t c = 0; c < 3; ++c) r.v[kFog][c] = static_cast<T>(fog_color[c]);
    r.v[kFog][3] = in.fog_factor ? static_cast<T>(in.fog_factor[i]) : T(1);
    const std::size_t q = 4 * static_cast<std::size_t>(i);
    if (plan.primary_needed)
      for (std::size_t c = 0; c < 4; ++c) r.v[kPrimaryColor][c] = static_cast<T>(in.primary[q + c]);
    if (plan.secondary_needed && in.secondary) {
      for (std::size_t c = 0; c < 3; ++c) r.v[kSecondaryColor][c] = static_cast<T>(in.secondary[q + c]);
      if (cfg.rc2_secondary_alpha) r.v[kSecondaryColor][3] = static_cast<T>(in.secondary[q + 3]);
    }
    for (std::size_t u = 0; u < kMaxRegisterTextures; ++u) {
      const double* t = in.texture[u];
      if (!plan.texture_needed[u] || !t) continue;
      for (std::size_t c = 0; c < 4; ++c) r.v[kTexture0 + u][c] = static_cast<T>(t[q + c]);
    }
    r.v[kSpare0][3] = r.v[kTexture0][3];
    bool own = false;
    for (const PlannedStage& st : plan.stages) {
      if (st.own_constants) {
        own = true;
        for (std::size_t c = 0; c < 4; ++c) {
          r.v[kConstantColor0][c] = static_cast<T>(st.constant_values[0][c]);
          r.v[kConstantColor1][c] = static_cast<T>(st.constant_values[1][c]);
        }
      }
      general_combiner_float<T>(st, r);
      record(trace, i, r, 1.0);
    }
    if (own)
      for (std::size_t c = 0; c < 4; ++c) {
        r.v[kConstantColor0][c] = static_cast<T>(plan.constant_values[0][c]);
        r.v[kConstantColor1][c] = static_cast<T>(plan.constant_values[1][c]);
      }
    T o[4];
    final_combiner_float<T>(plan.final, r, o);
    for (std::size_t c = 0; c < 4; ++c) out[q + c] = static_cast<double>(o[c]);
  }
}

}  // namespace

void shade_span(const CombinerPlan& plan, const CombinerInputsFixed& in, const std::array<double, 4>& fog_color,
                std::uint16_t* out, RegisterTrace* trace) {
  if (final_needs_int128(plan.M, plan.config.color_bits)) shade_fixed<Int128>(plan, in, fog_color, out, trace);
  else shade_fixed<std::int64_t>(plan, in, fog_color, out, trace);
}

void shade_span(const CombinerPlan& plan, const CombinerInputsFloat& in, const std::array<double, 4>& fog_color,
                double* out, RegisterTrace* trace) {
  if (plan.config.arithmetic == Arithmetic::Float32) shade_float<float>(plan, in, fog_color, out, trace);
  else shade_float<double>(plan, in, fog_color, out, trace);
}

}  // namespace ffsim::combiners

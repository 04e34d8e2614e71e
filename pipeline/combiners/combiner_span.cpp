#include "pipeline/combiners/combiner_span.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <type_traits>

#if defined(__AVX2__) || defined(__SSE4_1__)
#include <immintrin.h>
#endif

#include "pipeline/combiners/final_combiner.h"
#include "pipeline/combiners/register_combiners.h"
#include "pipeline/number/rgba_lanes.h"
#include "pipeline/number/snorm.h"
#include "pipeline/number/unorm.h"

namespace ffsim::combiners {

namespace {

constexpr int kChunk = 64;  // fragments per pass

// Register lanes are filled and copied n rounded up to 8 at a time (every lane
// array holds kChunk, a multiple of 8; lanes >= n are scratch nobody reads):
// fixed-width vector stores instead of a memset/memcpy per register component,
// whose start-up cost (rep stos/movs) was a third of the kernel's time. The empty
// asm statement keeps GCC from turning the loops back into memset/memcpy.
inline int lanes8(int n) { return (n + 7) & ~7; }
inline void fill_lanes(std::int32_t* d, int n, std::int32_t v) {
#ifdef __AVX2__
  const __m256i x = _mm256_set1_epi32(v);
  for (int i = 0; i < lanes8(n); i += 8) {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(d + i), x);
    __asm__ volatile("" ::: "memory");
  }
#else
  std::fill_n(d, n, v);
#endif
}
inline void copy_lanes(const std::int32_t* s, int n, std::int32_t* d) {
#ifdef __AVX2__
  for (int i = 0; i < lanes8(n); i += 8) {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(d + i), _mm256_loadu_si256(reinterpret_cast<const __m256i*>(s + i)));
    __asm__ volatile("" ::: "memory");
  }
#else
  std::copy_n(s, n, d);
#endif
}

// kM: the register maximum M when fixed at compile time (0: plan.M at run time).
// P: the integer type of mapped products and stage sums (see the header).
template <std::int32_t kM, class Acc>
struct Kernel {
  using P = std::conditional_t<kM != 0 && kM <= 2047, std::int32_t, std::int64_t>;
  // Registers are left uninitialised here: run() zeroes the first n entries of
  // each chunk (short runs of small triangles must not pay for 12 KB of zeroes).
  Kernel(const CombinerPlan& p, std::int32_t m) : plan(p), M_rt(m) {}
  const CombinerPlan& plan;
  const std::int32_t M_rt;
  std::int32_t M() const { return kM ? kM : M_rt; }

  alignas(64) std::int32_t reg[kRegisterCount][4][kChunk];

  // div_round_half_away (snorm.h) in P.
  static P round_away(P num, P den) {
    const P q = (2 * (num < 0 ? -num : num) + den) / (2 * den);
    return num < 0 ? -q : q;
  }

  // Input entry (register_combiners.cpp's Entry): identity when the grids agree.
  void load(const std::uint16_t* src, int bits, int comps, int reg_index, int n, std::size_t first) {
    const bool identity = static_cast<std::uint32_t>(M()) == unorm_max(bits);
#ifdef __SSE4_1__
    if (identity && comps == 4) {  // four fragments at a time: interleaved RGBA codes transposed to the four lanes
      std::int32_t(&r)[4][kChunk] = reg[reg_index];
      const std::uint16_t* s = src + 4 * first;
      int i = 0;
      for (; i + 4 <= n; i += 4) rgba16_to_lanes(s + 4 * i, r[0] + i, r[1] + i, r[2] + i, r[3] + i);
      for (; i < n; ++i)
        for (int c = 0; c < 4; ++c) r[c][i] = s[4 * i + c];
      for (int c = 0; c < 4; ++c) std::fill(r[c] + n, r[c] + lanes8(n), 0);  // the scratch lanes (see run)
      return;
    }
#endif
    for (int c = 0; c < comps; ++c) {
      std::int32_t* d = reg[reg_index][c];
      const std::uint16_t* s = src + 4 * first + static_cast<std::size_t>(c);
      if (identity)
        for (int i = 0; i < n; ++i) d[i] = s[4 * i];
      else
        for (int i = 0; i < n; ++i) d[i] = snorm_from_unorm(s[4 * i], bits, plan.config.combiner_bits);
      std::fill(d + n, d + lanes8(n), 0);  // the scratch lanes up to a multiple of 8 (see run)
    }
  }

  void set_constants(const std::array<std::array<std::int32_t, 4>, 2>& k, int n) {
    for (int c = 0; c < 4; ++c) {
      fill_lanes(reg[kConstantColor0][c], n, k[0][static_cast<std::size_t>(c)]);
      fill_lanes(reg[kConstantColor1][c], n, k[1][static_cast<std::size_t>(c)]);
    }
  }

  // portion_fixed<L> over the chunk: outputs o (AB, CD, SUM/MUX) into out[o][l].
  template <int L>
  void portion(const PlannedPortion& p, bool per_product, int n, std::int32_t (&out)[3][3][kChunk]) {
    const P M = this->M(), four_m = 4 * M, eight_m = 8 * M, two_m2 = 2 * M * M;
    P mv[4][3][kChunk];
    for (int v = 0; v < 4; ++v) {
      if (v < 2 ? !p.need_ab : !p.need_cd) continue;
      const PlannedVar& var = p.var[static_cast<std::size_t>(v)];
      const MappingCoeffs k = var.k;
      for (int l = 0; l < L; ++l) {
        const std::int32_t* src = reg[var.reg][var.comp[static_cast<std::size_t>(l)]];
        for (int i = 0; i < n; ++i) mv[v][l][i] = static_cast<P>(k.mul * std::clamp(src[i], k.lo, k.hi) + k.add);
      }
    }
    P ab[3][kChunk], cd[3][kChunk];
    auto products = [&](int a, int b, bool dot, P(&r)[3][kChunk]) {
      if (per_product)  // every product first rounded to the register grid
        for (int l = 0; l < L; ++l)
          for (int i = 0; i < n; ++i) r[l][i] = four_m * round_away(mv[a][l][i] * mv[b][l][i], four_m);
      else
        for (int l = 0; l < L; ++l)
          for (int i = 0; i < n; ++i) r[l][i] = mv[a][l][i] * mv[b][l][i];
      if (L == 3 && dot)  // the sum of the three lane products, broadcast
        for (int i = 0; i < n; ++i) r[0][i] = r[1][i] = r[2][i] = r[0][i] + r[1][i] + r[2][i];
    };
    if (p.need_ab) products(0, 1, p.ab_dot, ab);
    if (p.need_cd) products(2, 3, p.cd_dot, cd);
    const std::int32_t* spare0_a = reg[kSpare0][3];
    const P scale2 = p.scale2, bias = p.bias ? two_m2 : 0;
    // output_code: round((x + bias)·2·scale / 8M) half away, clamp to [−M, M].
    auto code = [&](P x) { return static_cast<std::int32_t>(std::clamp(round_away((x - bias) * scale2, eight_m), -M, M)); };
    for (int o = 0; o < 3; ++o) {
      if (p.dest[static_cast<std::size_t>(o)] < 0) continue;
      // A dot product's lanes are equal (broadcast above), and so are a sum or MUX
      // of two: the code is computed for lane 0 and copied.
      const bool equal_lanes = L == 3 && (o == 0 ? p.ab_dot : o == 1 ? p.cd_dot : p.ab_dot && p.cd_dot);
      for (int l = 0; l < L; ++l) {
        std::int32_t* d = out[o][l];
        if (equal_lanes && l > 0) {
          copy_lanes(out[o][0], n, d);
          continue;
        }
        const P* x_ab = ab[l];
        const P* x_cd = cd[l];
        if (o == 0)
          for (int i = 0; i < n; ++i) d[i] = code(x_ab[i]);
        else if (o == 1)
          for (int i = 0; i < n; ++i) d[i] = code(x_cd[i]);
        else if (p.mux)  // MUX: spare0.a >= 1/2 (exact: 2·spare0.a >= M) selects CD
          for (int i = 0; i < n; ++i) d[i] = code(2 * P{spare0_a[i]} >= M ? x_cd[i] : x_ab[i]);
        else
          for (int i = 0; i < n; ++i) d[i] = code(x_ab[i] + x_cd[i]);
      }
    }
  }

  void stage(const PlannedStage& st, bool per_product, int n) {
    std::int32_t rgb[3][3][kChunk], alpha[3][3][kChunk];
    if (st.rgb.run) portion<3>(st.rgb, per_product, n, rgb);
    if (st.alpha.run) portion<1>(st.alpha, per_product, n, alpha);
    // write_outputs: RGB outputs to R, G, B, then alpha outputs to A.
    if (st.rgb.run)
      for (int o = 0; o < 3; ++o)
        if (const int d = st.rgb.dest[static_cast<std::size_t>(o)]; d >= 0)
          for (int c = 0; c < 3; ++c) copy_lanes(rgb[o][c], n, reg[d][c]);
    if (st.alpha.run)
      for (int o = 0; o < 3; ++o)
        if (const int d = st.alpha.dest[static_cast<std::size_t>(o)]; d >= 0) copy_lanes(alpha[o][0], n, reg[d][3]);
  }

  // final_combiner_fixed<Acc> over the chunk, variable by variable. F: the lanes'
  // type. Every lane value is at most 2·M² (units of 1/M², spare0 + secondary
  // before its clamp), so a compile-time M <= 2047 keeps them in int32 (the
  // compiler vectorises them); the RGB sums go to Acc.
  using F = std::conditional_t<kM != 0 && kM <= 2047, std::int32_t, std::int64_t>;
  // A final combiner whose A..D are ZERO gives every fragment the same RGB: its
  // three codes, once computed in a span's first chunk (the low 48 bits).
  bool rgb_known = false;
  std::uint64_t rgb_word = 0;

  void final(int n, std::uint16_t* out) {
    const PlannedFinal& f = plan.final;
    const std::int32_t Mi = M();
    const F m = Mi, m2 = m * m;
    const int color_bits = plan.config.color_bits;
    const Acc nmax = (Acc{1} << color_bits) - 1;
    const Acc m4 = Acc{m2} * m2;
    // final_reg: UNSIGNED_INVERT 1 − clamp01, UNSIGNED_IDENTITY max(0, ·), in units of 1/M.
    auto final_reg = [&](const PlannedVar& v, int lane, int count, F* r) {
      const std::int32_t* c = reg[v.reg][v.comp[static_cast<std::size_t>(lane)]];
      if (v.mapping == Mapping::UnsignedInvert)
        for (int i = 0; i < count; ++i) r[i] = Mi - std::clamp(c[i], 0, Mi);
      else
        for (int i = 0; i < count; ++i) r[i] = std::max(c[i], 0);
    };
    F ef[3][kChunk], sps[3][kChunk], e[kChunk], fv[kChunk];
    if (f.need_ef)
      for (int l = 0; l < 3; ++l) {
        final_reg(f.var[4], l, n, e);
        final_reg(f.var[5], l, n, fv);
        for (int i = 0; i < n; ++i) ef[l][i] = e[i] * fv[i];
      }
    if (f.need_spare0_plus_secondary)
      for (int l = 0; l < 3; ++l)
        for (int i = 0; i < n; ++i) {
          const F s = F{std::max(reg[kSpare0][l][i], 0)} + std::max(reg[kSecondaryColor][l][i], 0);
          sps[l][i] = f.color_sum_clamp ? std::min(s, m) : s;
        }
    auto wide = [&](const PlannedVar& v, int l, int count, F* w) {  // units of 1/M^2
      const bool inv = v.mapping == Mapping::UnsignedInvert;
      if (v.reg == kETimesF) {
        for (int i = 0; i < count; ++i) w[i] = inv ? m2 - std::clamp(ef[l][i], F{0}, m2) : std::max(ef[l][i], F{0});
      } else if (v.reg == kSpare0PlusSecondary) {
        for (int i = 0; i < count; ++i) w[i] = inv ? m2 - std::min(sps[l][i] * m, m2) : sps[l][i] * m;
      } else {
        final_reg(v, l, count, w);
        for (int i = 0; i < count; ++i) w[i] *= m;
      }
    };
    F a[kChunk], b[kChunk], c[kChunk], d[kChunk];
    // A, B, C, D all ZERO (a pass that computes only alpha): RGB is one constant,
    // computed from the first fragment's (zero) lanes.
    bool rgb_const = true;
    for (std::size_t v = 0; v < 4; ++v) rgb_const &= f.var[v].reg == kZero;
    const int rgb_count = rgb_const ? 1 : n;
    for (int l = 0; l < 3 && !(rgb_const && rgb_known); ++l) {
      wide(f.var[0], l, rgb_count, a);
      wide(f.var[1], l, rgb_count, b);
      wide(f.var[2], l, rgb_count, c);
      wide(f.var[3], l, rgb_count, d);
      for (int i = 0; i < rgb_count; ++i) {
        Acc x = Acc{a[i]} * b[i] + (Acc{m2} - a[i]) * c[i] + Acc{d[i]} * Acc{m2};
        if (x > m4) x = m4;
        out[4 * i + l] = static_cast<std::uint16_t>((2 * x * nmax + m4) / (2 * m4));
      }
    }
    // G: code = floor((2·e·N + M) / 2M), e in [0, M]; below 2^32 for M <= 32767.
    final_reg(f.var[6], 0, n, e);
    std::uint32_t g[kChunk];
    if constexpr (kM != 0 && kM <= 32767) {
      const auto nm = static_cast<std::uint32_t>(nmax);
      for (int i = 0; i < n; ++i) g[i] = (2 * static_cast<std::uint32_t>(e[i]) * nm + kM) / (2 * std::uint32_t{kM});
    } else {
      for (int i = 0; i < n; ++i) g[i] = static_cast<std::uint32_t>((2 * Acc{e[i]} * nmax + m) / (2 * Acc{m}));
    }
    if (rgb_const) {  // each fragment's four codes as one 64-bit word: the constant RGB and its alpha
      if (!rgb_known) {
        rgb_word = std::uint64_t{out[0]} | std::uint64_t{out[1]} << 16 | std::uint64_t{out[2]} << 32;
        rgb_known = true;
      }
      const std::uint64_t rgb = rgb_word;
      static_assert(std::endian::native == std::endian::little, "R in the low 16 bits is the first code in memory");
      for (int i = 0; i < n; ++i) {
        const std::uint64_t px = rgb | std::uint64_t{g[i]} << 48;
        std::memcpy(out + 4 * i, &px, sizeof px);
      }
      return;
    }
    for (int i = 0; i < n; ++i) out[4 * i + 3] = static_cast<std::uint16_t>(g[i]);
  }

  void run(const CombinerInputsFixed& in, const std::array<double, 4>& fog_color, std::uint16_t* out) {
    const CombinerConfig& cfg = plan.config;
    const bool per_product = cfg.rounding == CombinerRounding::PerProduct;
    bool own_constants = false;
    for (const PlannedStage& st : plan.stages) own_constants |= st.own_constants;
    std::int32_t fog[3];
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t k = unorm_from_double(fog_color[static_cast<std::size_t>(c)], cfg.color_bits);
      fog[c] = static_cast<std::uint32_t>(M()) == unorm_max(cfg.color_bits)
                   ? static_cast<std::int32_t>(k)
                   : snorm_from_unorm(k, cfg.color_bits, cfg.combiner_bits);
    }
    // The reference starts every fragment from zeroed registers. Every register is
    // zeroed once, for the first chunk's lanes (the widest); a later chunk
    // re-zeroes only the registers a stage writes. The others are rewritten in
    // every chunk by the set-up below (constants, fog, loaded inputs, spare0.a)
    // or never written, so they hold the same values as after a full zeroing.
    bool dest[kRegisterCount] = {};
    for (const PlannedStage& st : plan.stages)
      for (const PlannedPortion* p : {&st.rgb, &st.alpha})
        if (p->run)
          for (const std::int8_t d : p->dest)
            if (d >= 0) dest[d] = true;
    for (int first = 0; first < in.count; first += kChunk) {
      const int n = std::min(kChunk, in.count - first);
      const auto f0 = static_cast<std::size_t>(first);
      for (int r = 0; r < kRegisterCount; ++r)
        if (first == 0 || dest[r])
          for (auto& comp : reg[r]) fill_lanes(comp, n, 0);
      // The constant colours and fog RGB are set in the first chunk (the widest)
      // and hold in the later ones: no stage writes them. (Plans with per-stage
      // constants, which overwrite them, set them again in every chunk.)
      if (first == 0 || own_constants || dest[kConstantColor0] || dest[kConstantColor1] || dest[kFog]) {
        set_constants(plan.constant_codes, n);
        for (int c = 0; c < 3; ++c) fill_lanes(reg[kFog][c], n, fog[c]);
      }
      if (in.fog_factor) {
        const bool identity = static_cast<std::uint32_t>(M()) == unorm_max(cfg.color_bits);
        for (int i = 0; i < n; ++i) {
          const std::uint16_t k = in.fog_factor[f0 + static_cast<std::size_t>(i)];
          reg[kFog][3][i] = identity ? std::int32_t{k} : snorm_from_unorm(k, cfg.color_bits, cfg.combiner_bits);
        }
        std::fill(reg[kFog][3] + n, reg[kFog][3] + lanes8(n), 0);
      } else {
        fill_lanes(reg[kFog][3], n, M());
      }
      if (plan.primary_needed) load(in.primary, cfg.color_bits, 4, kPrimaryColor, n, f0);
      if (plan.secondary_needed && in.secondary)
        load(in.secondary, cfg.color_bits, cfg.rc2_secondary_alpha ? 4 : 3, kSecondaryColor, n, f0);
      for (int u = 0; u < kMaxRegisterTextures; ++u) {
        const std::uint16_t* t = in.texture[static_cast<std::size_t>(u)];
        if (plan.texture_needed[static_cast<std::size_t>(u)] && t) load(t, cfg.texture_bits, 4, kTexture0 + u, n, f0);
      }
      copy_lanes(reg[kTexture0][3], n, reg[kSpare0][3]);
      // The general stages run on n rounded up to a multiple of 8 lanes: the
      // vectorised loops then need no scalar remainder (a triangle's group of about
      // 60 fragments spent much of its time there). The extra lanes hold defined,
      // in-range values (zeroed registers, zero inputs) and are never stored.
      const int n8 = lanes8(n);
      for (const PlannedStage& st : plan.stages) {
        if (st.own_constants) set_constants(st.constant_codes, n);
        stage(st, per_product, n8);
      }
      if (own_constants) set_constants(plan.constant_codes, n);  // RC2: the final combiner reads the global ones
      final(n, out + 4 * f0);
    }
  }
};

template <std::int32_t kM, class Acc>
void run_kernel(const CombinerPlan& plan, const CombinerInputsFixed& in, const std::array<double, 4>& fog,
                std::uint16_t* out) {
  Kernel<kM, Acc> k(plan, plan.M);  // ~30 KB of stack
  k.run(in, fog, out);
}

// Registers a general stage or the final combiner may read: the plan only holds
// ordinary registers there (pseudo-registers only in final A..D).
bool plan_supported(const CombinerPlan& plan) {
  for (const PlannedStage& st : plan.stages)
    for (const PlannedPortion* p : {&st.rgb, &st.alpha})
      for (const PlannedVar& v : p->var)
        if (v.reg >= kRegisterCount) return false;
  for (std::size_t v = 4; v < 7; ++v)
    if (plan.final.var[v].reg >= kRegisterCount) return false;
  return true;
}

}  // namespace

bool shade_span_fast(const CombinerPlan& plan, const CombinerInputsFixed& in, const std::array<double, 4>& fog_color,
                     std::uint16_t* out) {
  if (plan.config.arithmetic != Arithmetic::Fixed || !plan_supported(plan)) return false;
  if (in.count <= 0) return true;
  const bool wide = final_needs_int128(plan.M, plan.config.color_bits);
  if (wide) {
    run_kernel<0, Int128>(plan, in, fog_color, out);
    return true;
  }
  switch (plan.M) {
    case 255: run_kernel<255, std::int64_t>(plan, in, fog_color, out); break;
    case 1023: run_kernel<1023, std::int64_t>(plan, in, fog_color, out); break;
    default: run_kernel<0, std::int64_t>(plan, in, fog_color, out); break;
  }
  return true;
}

}  // namespace ffsim::combiners

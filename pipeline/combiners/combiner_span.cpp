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
#include "pipeline/number/const_divide.h"
#include "pipeline/number/rgba_lanes.h"
#include "pipeline/number/snorm.h"
#include "pipeline/number/unorm.h"

namespace ffsim::combiners {

namespace {

constexpr int kChunk = 64;  // fragments per pass

// Register lanes are filled n rounded up to 8 at a time (every lane array holds
// kChunk, a multiple of 8; lanes >= n are scratch the stages compute on and
// nobody stores): fixed-width vector stores instead of a memset per array, whose
// start-up cost (rep stos) was a third of the kernel's time. The empty asm
// statement keeps GCC from turning the loop back into memset.
inline int lanes8(int n) { return (n + 7) & ~7; }
inline void fill_lanes(std::int32_t* d, int n, std::int32_t v) {
#ifdef __AVX2__
  const __m256i x = _mm256_set1_epi32(v);
  for (int i = 0; i < lanes8(n); i += 8) {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(d + i), x);
    __asm__ volatile("" ::: "memory");
  }
#else
  std::fill_n(d, lanes8(n), v);  // the scratch lanes too: the stages read them
#endif
}

// One variable of a fused product loop: its source lanes and its mapping
// (mapped = mul·clamp(c, lo, hi) + add, input_mapping.h).
struct Src {
  const std::int32_t* p;
  std::int32_t lo, hi, mul, add;
};

// One product term x∘y. A term whose y is the same for every fragment of the
// span (ZERO, a constant colour, the fog colour, a register nothing wrote) is
// folded: K·(mul·clamp(c) + add) = (K·mul)·clamp(c) + K·add with K = y's mapped
// value, exact in integers, so x alone carries it (one clamp and one
// multiply-add instead of two mappings and a multiply).
struct Term {
  Src x, y;  // a folded term: x only
};

// Product kinds in fused_output's template: the number of terms (1: A∘B of one
// lane, 3: the dot product over three lanes; 0: not part of X), plus kFolded
// when every term is folded.
constexpr int kFolded = 8;

// div_round_half_away (snorm.h) in P: the division is unsigned (the numerator
// is non-negative), which vectorises in fewer instructions.
template <class P>
[[gnu::always_inline]] inline P round_away(P num, P den) {
  using U = std::make_unsigned_t<P>;
  const P q = static_cast<P>(static_cast<U>(2 * (num < 0 ? -num : num) + den) / static_cast<U>(2 * den));
  return num < 0 ? -q : q;
}
// ... clamped to [−max, max] (the output code's clamp).
template <class P>
[[gnu::always_inline]] inline P round_away_clamped(P num, P den, P max) {
  return std::clamp(round_away(num, den), -max, max);
}

// The output code's rounding, round_away_clamped(num, 8M, M), for a
// compile-time M: q = floor((|num| + 4M) / 8M) = floor(floor((|num| + 4M) / 8) / M)
// (nested floors of positive integers), and |num| >= 8M² − 4M gives q >= M,
// so |num| is first capped there: the dividend is then at most M², which
// ConstDivide turns into one 32-bit multiply and a shift when that is exact
// (M = 255; not M = 1023, which divides).
template <class P, std::int32_t kM>
[[gnu::always_inline]] inline P output_rounding(P num) {
  using Div = ConstDivide<static_cast<std::uint32_t>(kM), static_cast<std::uint32_t>(kM) * static_cast<std::uint32_t>(kM)>;
  if constexpr (kM != 0 && Div::exact && std::is_same_v<P, std::int32_t>) {
    const P a = std::min(num < 0 ? -num : num, 8 * kM * kM - 4 * kM);
    const P q = static_cast<P>(Div::divide(static_cast<std::uint32_t>(a + 4 * kM) >> 3));
    return num < 0 ? -q : q;
  } else {
    return round_away_clamped(num, static_cast<P>(8 * kM), static_cast<P>(kM));
  }
}

// A variable's mapped value at fragment i.
template <class P>
[[gnu::always_inline]] inline P mapped(const Src& s, int i) {
  // max then min (lo <= hi for every mapping): two instructions per eight lanes.
  return static_cast<P>(s.mul * std::min(std::max(s.p[i], s.lo), s.hi) + s.add);
}
// Term t at fragment i: x∘y, or x alone when folded; rounded to the register
// grid (4M units) first with per-product rounding.
template <class P, bool kFoldedTerm, bool kPerProduct>
[[gnu::always_inline]] inline P product(const Term& t, int i, P four_m) {
  P x;
  if constexpr (kFoldedTerm) x = mapped<P>(t.x, i);
  else x = mapped<P>(t.x, i) * mapped<P>(t.y, i);
  if constexpr (kPerProduct) x = four_m * round_away(x, four_m);
  return x;
}
// The sum of a product's terms at fragment i (kind: see kFolded).
template <class P, int kKind, bool kPerProduct>
[[gnu::always_inline]] inline P product_sum(const Term& t0, const Term& t1, const Term& t2, int i, P four_m) {
  constexpr bool f = (kKind & kFolded) != 0;
  if constexpr ((kKind & 7) == 0) return 0;
  else if constexpr ((kKind & 7) == 1) return product<P, f, kPerProduct>(t0, i, four_m);
  else
    return product<P, f, kPerProduct>(t0, i, four_m) + product<P, f, kPerProduct>(t1, i, four_m) +
           product<P, f, kPerProduct>(t2, i, four_m);
}

// The output code of one portion output over n lanes, in one loop from the
// register lanes to the code: out[i] = code(X) with X = AB, CD, AB + CD or
// MUX(AB, CD). kAB, kCD: the products' kinds (above); ab and cd hold their terms.
// kPerProduct: every product rounded to the register grid first
// (CombinerRounding::PerProduct). code(X) = round((X + bias)·2·scale / 8M) half
// away, clamped to [−M, M] (general_combiner.h's output_code).
template <class P, std::int32_t kM, int kAB, int kCD, bool kMux, bool kPerProduct>
void fused_output(const Term* ab, const Term* cd, const std::int32_t* spare0_a, P M_rt, P scale2, P bias, int n,
                  std::int32_t* __restrict out) {
  const P M = kM ? P{kM} : M_rt, four_m = 4 * M, eight_m = 8 * M;
  const int scale_shift = std::countr_zero(static_cast<std::uint32_t>(scale2));
  // The terms in locals (the loop then keeps their fields in registers).
  const Term a0 = ab[0], a1 = ab[(kAB & 7) == 3 ? 1 : 0], a2 = ab[(kAB & 7) == 3 ? 2 : 0];
  const Term c0 = cd[0], c1 = cd[(kCD & 7) == 3 ? 1 : 0], c2 = cd[(kCD & 7) == 3 ? 2 : 0];
  for (int i = 0; i < n; ++i) {
    const P x_ab = product_sum<P, kAB, kPerProduct>(a0, a1, a2, i, four_m);
    const P x_cd = product_sum<P, kCD, kPerProduct>(c0, c1, c2, i, four_m);
    P x;
    if constexpr (kMux) x = 2 * P{spare0_a[i]} >= M ? x_cd : x_ab;  // spare0.a >= 1/2, exact
    else x = x_ab + x_cd;
    // scale2 is 1, 2, 4 or 8: a shift (exact for negative x too).
    const P scaled = (x - bias) << scale_shift;
    if constexpr (kM != 0) out[i] = static_cast<std::int32_t>(output_rounding<P, kM>(scaled));
    else out[i] = static_cast<std::int32_t>(round_away_clamped(scaled, eight_m, M));
  }
}

// kind as a compile-time constant: f(std::integral_constant<int, kind>).
template <class F>
void with_kind(int kind, F f) {
  switch (kind) {
    case 1: return f(std::integral_constant<int, 1>{});
    case 3: return f(std::integral_constant<int, 3>{});
    case 1 | kFolded: return f(std::integral_constant<int, 1 | kFolded>{});
    case 3 | kFolded: return f(std::integral_constant<int, 3 | kFolded>{});
    default: return f(std::integral_constant<int, 0>{});
  }
}

// fused_output with its kinds and flags as compile-time constants. Folded
// kinds occur only with a compile-time M and without per-product rounding
// (portion() folds nothing otherwise), which keeps the instantiations few.
template <class P, std::int32_t kM>
void fused_output_rt(int ab_kind, int cd_kind, bool mux, bool per_product, const Term* ab, const Term* cd,
                     const std::int32_t* spare0_a, P M, P scale2, P bias, int n, std::int32_t* out) {
  with_kind(ab_kind, [&](auto kab) {
    with_kind(cd_kind, [&](auto kcd) {
      constexpr int a = kab.value, c = kcd.value;
      constexpr bool folded = ((a | c) & kFolded) != 0;
      if constexpr (a != 0 || c != 0) {
        if (mux) {
          if constexpr (a != 0 && c != 0 && !folded) {
            if (per_product) fused_output<P, kM, a, c, true, true>(ab, cd, spare0_a, M, scale2, bias, n, out);
            else fused_output<P, kM, a, c, true, false>(ab, cd, spare0_a, M, scale2, bias, n, out);
          } else if constexpr (a != 0 && c != 0 && kM != 0) {
            fused_output<P, kM, a, c, true, false>(ab, cd, spare0_a, M, scale2, bias, n, out);
          }
        } else if constexpr (!folded) {
          if (per_product) fused_output<P, kM, a, c, false, true>(ab, cd, spare0_a, M, scale2, bias, n, out);
          else fused_output<P, kM, a, c, false, false>(ab, cd, spare0_a, M, scale2, bias, n, out);
        } else if constexpr (kM != 0) {
          fused_output<P, kM, a, c, false, false>(ab, cd, spare0_a, M, scale2, bias, n, out);
        }
      }
    });
  });
}

// The register lanes of a span (the part of the kernel that does not depend on
// M or the accumulator types; one copy of this code for every instantiation).
//
// Registers are views: view[r][c] points at the lanes that hold component c of
// register r for the current chunk. A stage's outputs go to fresh lane arrays
// and their registers' views are pointed at them, so nothing is copied: a dot
// product's three equal lanes are one array, SPARE0 alpha starts as a view of
// TEXTURE0 alpha, and unwritten registers view one array of zeroes. Lane arrays
// are left uninitialised here: run() fills the first lanes8(n) of the first
// chunk (short runs of small triangles must not pay for full chunks).
struct RegisterLanes {
  const std::int32_t* view[kRegisterCount][4];
  alignas(64) std::int32_t zero[kChunk];
  alignas(64) std::int32_t constant[2][4][kChunk];  // CONSTANT_COLOR0/1: the global ones
  alignas(64) std::int32_t stage_constant[2][4][kChunk];  // the stage's own (RC2 PER_STAGE_CONSTANTS)
  alignas(64) std::int32_t fog[4][kChunk];
  alignas(64) std::int32_t input[kRegisterCount][4][kChunk];  // the loaded inputs (primary, secondary, textures)
  // The program's outputs, one array per op: per stage at most 3 outputs x 3 RGB
  // lanes and 3 alpha.
  static constexpr int kMaxOps = kMaxGeneralCombiners * 12;
  alignas(64) std::int32_t output[kMaxOps][kChunk];

  // Input entry (register_combiners.cpp's Entry) into input[reg_index]: identity
  // when the grids agree (M the register maximum, combiner_bits its width).
  void load(const std::uint16_t* src, int bits, int comps, int reg_index, int n, std::size_t first, std::int32_t M,
            int combiner_bits) {
    const bool identity = static_cast<std::uint32_t>(M) == unorm_max(bits);
    std::int32_t(&r)[4][kChunk] = input[reg_index];
#ifdef __SSE4_1__
    if (identity && comps == 4) {  // four fragments at a time: interleaved RGBA codes transposed to the four lanes
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
      std::int32_t* d = r[c];
      const std::uint16_t* s = src + 4 * first + static_cast<std::size_t>(c);
      if (identity)
        for (int i = 0; i < n; ++i) d[i] = s[4 * i];
      else
        for (int i = 0; i < n; ++i) d[i] = snorm_from_unorm(s[4 * i], bits, combiner_bits);
      std::fill(d + n, d + lanes8(n), 0);  // the scratch lanes up to a multiple of 8 (see run)
    }
  }

  static void fill_constants(const std::array<std::array<std::int32_t, 4>, 2>& k, std::int32_t (&to)[2][4][kChunk],
                             int n) {
    for (int q = 0; q < 2; ++q)
      for (int c = 0; c < 4; ++c) fill_lanes(to[q][c], n, k[static_cast<std::size_t>(q)][static_cast<std::size_t>(c)]);
  }
  void view_constants(std::int32_t (&from)[2][4][kChunk]) {
    for (int c = 0; c < 4; ++c) {
      view[kConstantColor0][c] = from[0][c];
      view[kConstantColor1][c] = from[1][c];
    }
  }
};

// kM: the register maximum M when fixed at compile time (0: plan.M at run time).
// P: the integer type of mapped products and stage sums (see the header).
template <std::int32_t kM, class Acc>
struct Kernel : RegisterLanes {
  using P = std::conditional_t<kM != 0 && kM <= 2047, std::int32_t, std::int64_t>;
  Kernel(const CombinerPlan& p, std::int32_t m) : plan(p), M_rt(m) {}
  const CombinerPlan& plan;
  const std::int32_t M_rt;
  std::int32_t M() const { return kM ? kM : M_rt; }

  // Which views hold one value for the whole span (filled once per span, never
  // written by a stage): ZERO and unwritten registers, the constants, the fog
  // colour, and FOG alpha without per-fragment fog.
  bool span_constant[kRegisterCount][4];

  // One fused loop of the span's program: an output's lanes (fused_output_rt).
  struct Op {
    int ab_kind, cd_kind;
    bool mux;
    P scale2, bias;
    const std::int32_t* spare0_a;
    std::int32_t* out;
    Term ab[3], cd[3];
  };
  Op ops[kMaxOps];
  int op_count = 0;
  int stage_end[kMaxGeneralCombiners];  // ops of stage s: [stage_end[s-1], stage_end[s])

  // The terms of product x∘y over `count` lanes (three for a dot product) from
  // lane `first`: folded when every term has a span-constant side (kM fixed and
  // no per-product rounding only, see fused_output_rt). Returns the kind.
  int make_terms(const Src* x, const bool* x_const, const Src* y, const bool* y_const, int first, int count, bool fold,
                 Term* out) const {
    for (int t = first; t < first + count; ++t) fold &= x_const[t] || y_const[t];
    for (int t = first; t < first + count; ++t) {
      Term& term = out[t - first];
      if (!fold) {
        term = {x[t], y[t]};
        continue;
      }
      const bool y_k = y_const[t];
      const Src& k = y_k ? y[t] : x[t];  // the constant side
      const Src& v = y_k ? x[t] : y[t];
      const std::int32_t kv = map_fixed(MappingCoeffs{k.lo, k.hi, k.mul, k.add}, k.p[0]);
      term.x = {v.p, v.lo, v.hi, kv * v.mul, kv * v.add};
      term.y = {};
    }
    return count | (fold ? kFolded : 0);
  }

  // One portion of the program: an op per live output lane, computed into a
  // fresh array (one for the three lanes of a dot product's, or a sum or MUX of
  // two). Returns in out[o][l] the arrays of output o, lane l.
  template <int L>
  void portion(const PlannedPortion& p, bool per_product, const std::int32_t* (&out)[3][3]) {
    Src src[4][3];
    bool constant[4][3];
    for (int v = 0; v < 4; ++v) {
      const PlannedVar& var = p.var[static_cast<std::size_t>(v)];
      for (int l = 0; l < L; ++l) {
        const int c = var.comp[static_cast<std::size_t>(l)];
        src[v][l] = {view[var.reg][c], var.k.lo, var.k.hi, var.k.mul, var.k.add};
        constant[v][l] = span_constant[var.reg][c];
      }
    }
    const P M = this->M();
    const bool fold = kM != 0 && !per_product;
    const bool ab_dot = L == 3 && p.ab_dot, cd_dot = L == 3 && p.cd_dot;
    for (int o = 0; o < 3; ++o) {
      if (p.dest[static_cast<std::size_t>(o)] < 0) continue;
      const bool use_ab = o != 1, use_cd = o != 0;
      // Lanes of a dot product are equal, and so are those of a sum or MUX of two.
      const bool equal_lanes = (!use_ab || ab_dot) && (!use_cd || cd_dot);
      for (int l = 0; l < L; ++l) {
        if (equal_lanes && l > 0) {
          out[o][l] = out[o][0];
          continue;
        }
        Op& op = ops[op_count];
        op.out = output[op_count++];
        op.mux = o == 2 && p.mux;
        op.scale2 = p.scale2;
        op.bias = p.bias ? 2 * M * M : 0;
        op.spare0_a = view[kSpare0][3];
        op.ab_kind = !use_ab ? 0
                     : ab_dot ? make_terms(src[0], constant[0], src[1], constant[1], 0, 3, fold, op.ab)
                              : make_terms(src[0], constant[0], src[1], constant[1], l, 1, fold, op.ab);
        op.cd_kind = !use_cd ? 0
                     : cd_dot ? make_terms(src[2], constant[2], src[3], constant[3], 0, 3, fold, op.cd)
                              : make_terms(src[2], constant[2], src[3], constant[3], l, 1, fold, op.cd);
        out[o][l] = op.out;
      }
    }
  }

  // A stage of the program: both portions read the stage's input registers,
  // then the outputs are written (their views moved): RGB outputs to R, G, B,
  // then alpha outputs to A.
  void record_stage(const PlannedStage& st, bool per_product) {
    const std::int32_t* rgb[3][3];
    const std::int32_t* alpha[3][3];
    if (st.rgb.run) portion<3>(st.rgb, per_product, rgb);
    if (st.alpha.run) portion<1>(st.alpha, per_product, alpha);
    if (st.rgb.run)
      for (int o = 0; o < 3; ++o)
        if (const int d = st.rgb.dest[static_cast<std::size_t>(o)]; d >= 0)
          for (int c = 0; c < 3; ++c) {
            view[d][c] = rgb[o][c];
            span_constant[d][c] = false;
          }
    if (st.alpha.run)
      for (int o = 0; o < 3; ++o)
        if (const int d = st.alpha.dest[static_cast<std::size_t>(o)]; d >= 0) {
          view[d][3] = alpha[o][0];
          span_constant[d][3] = false;
        }
  }

  void run_ops(int begin, int end, bool per_product, int n) {
    for (int i = begin; i < end; ++i) {
      const Op& op = ops[i];
      fused_output_rt<P, kM>(op.ab_kind, op.cd_kind, op.mux, per_product, op.ab, op.cd, op.spare0_a, M(), op.scale2,
                             op.bias, n, op.out);
    }
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
      const std::int32_t* c = view[v.reg][v.comp[static_cast<std::size_t>(lane)]];
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
      for (int l = 0; l < 3; ++l) {
        const std::int32_t* s0 = view[kSpare0][l];
        const std::int32_t* s1 = view[kSecondaryColor][l];
        for (int i = 0; i < n; ++i) {
          const F s = F{std::max(s0[i], 0)} + std::max(s1[i], 0);
          sps[l][i] = f.color_sum_clamp ? std::min(s, m) : s;
        }
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
    if (nmax == Acc{m}) {  // the colour grid is the register grid: (2eM + M) / 2M = e
      for (int i = 0; i < n; ++i) g[i] = static_cast<std::uint32_t>(e[i]);
    } else if constexpr (kM != 0 && kM <= 32767) {
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
    const bool color_identity = static_cast<std::uint32_t>(M()) == unorm_max(cfg.color_bits);
    // Every fragment starts from zeroed registers with the inputs entered (the
    // reference's order). The per-span values (zeroes, constants, fog colour,
    // fog alpha without fog) are filled for the first chunk's lanes, the widest,
    // and hold for the later chunks: nothing writes those arrays.
    const int n0 = std::min(kChunk, in.count);
    fill_lanes(zero, n0, 0);
    fill_constants(plan.constant_codes, constant, n0);
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t k = unorm_from_double(fog_color[static_cast<std::size_t>(c)], cfg.color_bits);
      fill_lanes(fog[c], n0, color_identity ? static_cast<std::int32_t>(k) : snorm_from_unorm(k, cfg.color_bits, cfg.combiner_bits));
    }
    if (!in.fog_factor) fill_lanes(fog[3], n0, M());  // FOG alpha = 1 with fog disabled
    // The registers' views at the input of stage 0, then the span's program: the
    // views are the same in every chunk (only the arrays' contents change), so
    // the stages are planned once, with the views they read and write.
    const bool secondary = plan.secondary_needed && in.secondary;
    for (int r = 0; r < kRegisterCount; ++r)
      for (int c = 0; c < 4; ++c) {
        const bool loaded = (r == kPrimaryColor && plan.primary_needed) || (r == kSecondaryColor && secondary && (c < 3 || cfg.rc2_secondary_alpha)) ||
                            (r >= kTexture0 && plan.texture_needed[static_cast<std::size_t>(r - kTexture0)] && in.texture[static_cast<std::size_t>(r - kTexture0)]);
        view[r][c] = loaded ? input[r][c] : zero;
        span_constant[r][c] = !loaded;
      }
    view_constants(constant);
    for (int c = 0; c < 4; ++c) view[kFog][c] = fog[c];
    span_constant[kFog][3] = !in.fog_factor;
    view[kSpare0][3] = view[kTexture0][3];  // SPARE0 alpha = texture 0 alpha
    span_constant[kSpare0][3] = span_constant[kTexture0][3];
    op_count = 0;
    for (std::size_t s = 0; s < plan.stages.size(); ++s) {
      const PlannedStage& st = plan.stages[s];
      if (st.own_constants) {  // the folded constants are read while recording: the stage's own in place
        fill_constants(st.constant_codes, stage_constant, n0);
        view_constants(stage_constant);
      }
      record_stage(st, per_product);
      stage_end[s] = op_count;
    }
    if (own_constants) view_constants(constant);  // RC2: the final combiner reads the global ones

    for (int first = 0; first < in.count; first += kChunk) {
      const int n = std::min(kChunk, in.count - first);
      const auto f0 = static_cast<std::size_t>(first);
      if (in.fog_factor) {
        for (int i = 0; i < n; ++i) {
          const std::uint16_t k = in.fog_factor[f0 + static_cast<std::size_t>(i)];
          fog[3][i] = color_identity ? std::int32_t{k} : snorm_from_unorm(k, cfg.color_bits, cfg.combiner_bits);
        }
        std::fill(fog[3] + n, fog[3] + lanes8(n), 0);
      }
      const int cb = cfg.combiner_bits;
      if (plan.primary_needed) load(in.primary, cfg.color_bits, 4, kPrimaryColor, n, f0, M(), cb);
      if (secondary) load(in.secondary, cfg.color_bits, cfg.rc2_secondary_alpha ? 4 : 3, kSecondaryColor, n, f0, M(), cb);
      for (int u = 0; u < kMaxRegisterTextures; ++u) {
        const std::uint16_t* t = in.texture[static_cast<std::size_t>(u)];
        if (plan.texture_needed[static_cast<std::size_t>(u)] && t) load(t, cfg.texture_bits, 4, kTexture0 + u, n, f0, M(), cb);
      }
      // The general stages run on n rounded up to a multiple of 8 lanes: the
      // vectorised loops then need no scalar remainder (a triangle's group of about
      // 60 fragments spent much of its time there). The extra lanes hold defined,
      // in-range values (zeroes, zero inputs) and are never stored.
      const int n8 = lanes8(n);
      for (std::size_t s = 0; s < plan.stages.size(); ++s) {
        const PlannedStage& st = plan.stages[s];
        if (st.own_constants) fill_constants(st.constant_codes, stage_constant, n);
        run_ops(s == 0 ? 0 : stage_end[s - 1], stage_end[s], per_product, n8);
      }
      final(n, out + 4 * f0);
    }
  }
};

template <std::int32_t kM, class Acc>
[[gnu::noinline]] void run_kernel(const CombinerPlan& plan, const CombinerInputsFixed& in,
                                  const std::array<double, 4>& fog, std::uint16_t* out) {  // ~80 KB of stack
  Kernel<kM, Acc> k(plan, plan.M);
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
  // Outputs go to read/write registers only (RC: DISCARD, PRIMARY, SECONDARY,
  // SPARE0/1, TEXTURE<i>); the views of ZERO, the constants and FOG are per span.
  for (const PlannedStage& st : plan.stages)
    for (const PlannedPortion* p : {&st.rgb, &st.alpha})
      for (const std::int8_t d : p->dest)
        if (d >= 0 && (d < kPrimaryColor || d >= kRegisterCount)) return false;
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

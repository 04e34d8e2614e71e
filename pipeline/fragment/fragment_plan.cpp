#include "pipeline/fragment/fragment_plan.h"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <type_traits>
#include <vector>

#ifdef __SSE4_1__
#include <immintrin.h>
#endif

#include "pipeline/fragment/test_func.h"
#include "pipeline/fragment/write_mask.h"
#include "pipeline/number/rgba_lanes.h"
#include "pipeline/number/unorm.h"

namespace ffsim {

namespace {

bool uses_src_factor(ChannelOp op) {
  return op == ChannelOp::SrcTerm || op == ChannelOp::Add || op == ChannelOp::Sub || op == ChannelOp::RevSub;
}
bool uses_dst_factor(ChannelOp op) {
  return op == ChannelOp::DstTerm || op == ChannelOp::Add || op == ChannelOp::Sub || op == ChannelOp::RevSub;
}
bool reads_dst(ChannelOp op, GLenum src_factor, int c) {
  if (op == ChannelOp::Keep || op == ChannelOp::Zero || op == ChannelOp::Copy) return false;
  if (op == ChannelOp::SrcTerm) {  // only the source factor can reference the destination
    return src_factor == gl::DST_COLOR || src_factor == gl::ONE_MINUS_DST_COLOR || src_factor == gl::DST_ALPHA ||
           src_factor == gl::ONE_MINUS_DST_ALPHA || (src_factor == gl::SRC_ALPHA_SATURATE && c != 3);
  }
  return true;
}

// What blending computes for channel c, with the trivial terms removed.
ChannelOp blend_channel_op(GLenum eq, GLenum sf, GLenum df, int c) {
  if (eq == gl::MIN) return ChannelOp::Min;
  if (eq == gl::MAX) return ChannelOp::Max;
  if (c == 3 && sf == gl::SRC_ALPHA_SATURATE) sf = gl::ONE;  // (f, f, f, 1)
  const bool s = sf != gl::ZERO, d = df != gl::ZERO;
  const ChannelOp src_only = sf == gl::ONE ? ChannelOp::Copy : ChannelOp::SrcTerm;
  const ChannelOp dst_only = df == gl::ONE ? ChannelOp::Keep : ChannelOp::DstTerm;
  if (eq == gl::FUNC_SUBTRACT) return !s ? ChannelOp::Zero : !d ? src_only : ChannelOp::Sub;
  if (eq == gl::FUNC_REVERSE_SUBTRACT) return !d ? ChannelOp::Zero : !s ? dst_only : ChannelOp::RevSub;
  if (!s && !d) return ChannelOp::Zero;
  return !d ? src_only : !s ? dst_only : ChannelOp::Add;
}

std::uint32_t stencil_max_of(int bits) { return bits > 0 ? unorm_max(bits) : 0; }

}  // namespace

FragmentPlanKey fragment_plan_key(const FragmentOpsState& s, const FragmentTarget& t) {
  FragmentPlanKey k;
  k.arith = t.arith;
  const bool fixed = t.arith == Arithmetic::Fixed;

  const GLenum af = s.alpha.enabled ? s.alpha.func : gl::ALWAYS;

  bool depth = s.depth.enabled && t.depth_bits > 0;
  const GLenum df = depth ? s.depth.func : gl::ALWAYS;
  const bool dw = depth && s.depth_mask;
  if (depth && df == gl::ALWAYS && !dw) depth = false;  // passes everything, writes nothing

  bool st = s.stencil.enabled && t.stencil_bits > 0;
  GLenum sf = gl::ALWAYS, sfail = gl::KEEP, dpfail = gl::KEEP, dppass = gl::KEEP;
  if (st) {
    sf = s.stencil.func;
    if ((s.stencil_writemask & stencil_max_of(t.stencil_bits)) != 0) {
      sfail = s.stencil.sfail;
      dpfail = s.stencil.dpfail;
      dppass = s.stencil.dppass;
    }
    if (sf == gl::ALWAYS) sfail = gl::KEEP;
    if (sf == gl::NEVER) dpfail = dppass = gl::KEEP;
    if (!depth || df == gl::ALWAYS) dpfail = gl::KEEP;
    if (depth && df == gl::NEVER) dppass = gl::KEEP;
    if (sf == gl::ALWAYS && sfail == gl::KEEP && dpfail == gl::KEEP && dppass == gl::KEEP) st = false;
  }
  const bool stencil_writes = st && (sfail != gl::KEEP || dpfail != gl::KEEP || dppass != gl::KEEP);

  const bool logic = s.logic.enabled && fixed;  // float colour has no bits to combine (numerics §9.6)
  const bool blend = s.blend.enabled && !logic;  // §4.1.8: the logic op replaces blending
  bool any_write = false, any_logic = false, any_src = false, any_dst = false;
  for (int c = 0; c < 4; ++c) {
    ChannelOp op = ChannelOp::Copy;
    if (!s.color_mask[c]) op = ChannelOp::Keep;
    else if (logic) op = s.logic.op == gl::COPY ? ChannelOp::Copy
                       : s.logic.op == gl::NOOP ? ChannelOp::Keep
                       : s.logic.op == gl::CLEAR ? ChannelOp::Zero
                                                 : ChannelOp::Logic;
    else if (blend) op = blend_channel_op(s.blend.equation, s.blend.src, s.blend.dst, c);
    k.channel[c] = op;
    any_write |= op != ChannelOp::Keep;
    any_logic |= op == ChannelOp::Logic;
    any_src |= uses_src_factor(op);
    any_dst |= uses_dst_factor(op);
  }

  const bool discard_all = af == gl::NEVER || (st && sf == gl::NEVER && sfail == gl::KEEP) ||
                           (depth && df == gl::NEVER && !st);
  if (discard_all || (!any_write && !stencil_writes && !dw)) {
    FragmentPlanKey none;
    none.arith = t.arith;
    none.nothing = true;
    return none;
  }
  k.alpha_func = af == gl::ALWAYS ? 0 : af;
  if (st) {
    k.stencil = true;
    k.stencil_func = sf;
    k.sfail = sfail;
    k.dpfail = dpfail;
    k.dppass = dppass;
  }
  if (depth) {
    k.depth = true;
    k.depth_func = df;
    k.depth_write = dw;
  }
  // The equation is part of each channel's operation; a factor is kept only if a
  // channel's operation uses it.
  if (any_src) k.blend_src = s.blend.src;
  if (any_dst) k.blend_dst = s.blend.dst;
  if (any_logic) k.logic_op = s.logic.op;
  return k;
}

FragmentPlan build_fragment_plan(const FragmentPlanKey& key) {
  FragmentPlan p;
  p.key = key;
  for (int c = 0; c < 4; ++c) {
    p.write_color |= key.channel[c] != ChannelOp::Keep;
    p.read_dst_color |= reads_dst(key.channel[c], key.blend_src, c);
  }
  p.lanes8 = blend_lanes8(key);
  return p;
}

FragmentConstants fragment_constants(const FragmentOpsState& s, const FragmentTarget& t) {
  FragmentConstants k;
  k.rect = write_rect(s.scissor, t.width, t.height);
  k.color_bits = t.color_bits;
  k.color_max = unorm_max(t.color_bits);
  k.alpha_ref_code = alpha_ref_code(s.alpha.ref, t.color_bits);
  k.alpha_ref_value = alpha_ref_value(s.alpha.ref, t.arith);
  k.stencil_max = stencil_max_of(t.stencil_bits);
  k.stencil_ref = stencil_ref_clamped(s.stencil.ref, k.stencil_max);
  k.stencil_value_mask = s.stencil.value_mask & k.stencil_max;
  k.stencil_writemask = s.stencil_writemask & k.stencil_max;
  for (int c = 0; c < 4; ++c) {
    const double v = clamp01(s.blend.color[c]);
    k.blend_color_given[c] = v;
    k.blend_color_code[c] = unorm_from_double(v, t.color_bits);
    k.blend_color_value[c] = t.arith == Arithmetic::Float32 ? static_cast<double>(static_cast<float>(v)) : v;
  }
  const FragmentPlanKey key = fragment_plan_key(s, t);
  if (key.stencil && t.stencil_bits > 0 && t.stencil_bits <= 8) {
    FragmentConstants::StencilTables& st = k.stencil_tables;
    st = {true, key.stencil_func, key.sfail, key.dpfail, key.dppass, {}, {}, {}, {}};
    const std::uint32_t ref_m = k.stencil_ref & k.stencil_value_mask;
    for (std::uint32_t v = 0; v < 256; ++v) {  // the per-fragment rules of stencil_depth_stage
      st.pass[v] = test_func<std::uint32_t>(key.stencil_func, ref_m, v & k.stencil_value_mask) ? 1 : 0;
      st.after_sfail[v] = static_cast<std::uint8_t>(stencil_write(key.sfail, v, k.stencil_ref, k.stencil_max, k.stencil_writemask));
      st.after_dpfail[v] = static_cast<std::uint8_t>(stencil_write(key.dpfail, v, k.stencil_ref, k.stencil_max, k.stencil_writemask));
      st.after_dppass[v] = static_cast<std::uint8_t>(stencil_write(key.dppass, v, k.stencil_ref, k.stencil_max, k.stencil_writemask));
    }
  }
  return k;
}

// ---------------------------------------------------------------------------
// The planned path.

namespace {

constexpr int kChunk = 256;  // fragments per pass over the stages (stack-sized mask)

// Where a chunk's fragment j lands: pixel index y·width + x. A span's fragments
// are consecutive pixels of a row (RowPixels); a primitive's fragments gathered
// from several rows are listed (ListPixels, run_fragment_plan_pixels).
struct RowPixels {
  std::size_t first;
  std::size_t operator()(int j) const { return first + static_cast<std::size_t>(j); }
};
struct ListPixels {
  const std::uint32_t* pixel;
  std::size_t operator()(int j) const { return pixel[j]; }
};

// Float colour stage for one channel (F = float for Float32, double for Float64),
// per fragment.
template <class F>
void color_channel_float(const FragmentPlan& plan, const FragmentConstants& k, const FragmentSpan& sp,
                         const FragmentBuffers& b, std::size_t row, int start, int n, const std::uint8_t* alive, int c,
                         Arithmetic arith) {
  F kc[4];
  for (int q = 0; q < 4; ++q) kc[q] = static_cast<F>(k.blend_color_value[q]);
  const GLenum sf = plan.key.blend_src, df = plan.key.blend_dst;
  const ChannelOp op = plan.key.channel[c];
  if (op == ChannelOp::Keep || op == ChannelOp::Logic) return;  // Logic never occurs on float colour
  for (int j = 0; j < n; ++j) {
    if (!alive[j]) continue;
    const std::size_t i = static_cast<std::size_t>(start + j);
    const std::size_t p = row + static_cast<std::size_t>(sp.x0 + start + j);
    double* out = b.values + 4 * p;
    if (op == ChannelOp::Copy) {
      out[c] = store_float_color(sp.values[4 * i + c], arith);
      continue;
    }
    F s[4], d[4] = {0, 0, 0, 0};
    for (int q = 0; q < 4; ++q) s[q] = static_cast<F>(sp.values[4 * i + q]);
    if (plan.read_dst_color)
      for (int q = 0; q < 4; ++q) d[q] = static_cast<F>(out[q]);
    F r = 0;
    switch (op) {
      case ChannelOp::Zero: r = 0; break;
      case ChannelOp::SrcTerm: r = clamp01(s[c] * blend_factor<F>(sf, c, s, d, kc, F(1))); break;
      case ChannelOp::DstTerm: r = clamp01(d[c] * blend_factor<F>(df, c, s, d, kc, F(1))); break;
      case ChannelOp::Add:
      case ChannelOp::Sub:
      case ChannelOp::RevSub:
        r = blend_value<F>(op == ChannelOp::Add ? gl::FUNC_ADD : op == ChannelOp::Sub ? gl::FUNC_SUBTRACT : gl::FUNC_REVERSE_SUBTRACT, s[c], blend_factor<F>(sf, c, s, d, kc, F(1)), d[c],
                           blend_factor<F>(df, c, s, d, kc, F(1)));
        break;
      case ChannelOp::Min: r = clamp01(std::min(s[c], d[c])); break;
      case ChannelOp::Max: r = clamp01(std::max(s[c], d[c])); break;
      default: break;
    }
    out[c] = static_cast<double>(r);
  }
}

// Fixed colour: a chunk of fragments de-interleaved into per-channel arrays, each
// written channel computed by a loop specialised by its operation and factors,
// then stored where the fragment survived. kM is the colour maximum M when known at
// compile time (255: 32-bit arithmetic and division by a constant), 0 otherwise.
template <std::uint32_t kM>
struct FixedKernel {
  using I = std::conditional_t<kM == 255, std::int32_t, std::int64_t>;
  std::uint32_t M;
  std::uint32_t src[4][kChunk];
  std::uint32_t dst[4][kChunk];

  std::uint32_t max() const { return kM ? kM : M; }

  // Factor `f` for channel c of every fragment of the chunk: the source or
  // destination array itself when the factor is one of them (no copy), else
  // computed into `scratch`.
  const std::uint32_t* factor(GLenum f, int c, const std::uint32_t* kc, int n, std::uint32_t* scratch) const {
    const std::uint32_t m = max();
    std::uint32_t* out = scratch;
    switch (f) {
      case gl::ZERO: std::fill_n(out, n, 0u); return out;
      case gl::ONE: std::fill_n(out, n, m); return out;
      case gl::SRC_COLOR: return src[c];
      case gl::ONE_MINUS_SRC_COLOR: for (int j = 0; j < n; ++j) out[j] = m - src[c][j]; return out;
      case gl::DST_COLOR: return dst[c];
      case gl::ONE_MINUS_DST_COLOR: for (int j = 0; j < n; ++j) out[j] = m - dst[c][j]; return out;
      case gl::SRC_ALPHA: return src[3];
      case gl::ONE_MINUS_SRC_ALPHA: for (int j = 0; j < n; ++j) out[j] = m - src[3][j]; return out;
      case gl::DST_ALPHA: return dst[3];
      case gl::ONE_MINUS_DST_ALPHA: for (int j = 0; j < n; ++j) out[j] = m - dst[3][j]; return out;
      case gl::CONSTANT_COLOR: std::fill_n(out, n, kc[c]); return out;
      case gl::ONE_MINUS_CONSTANT_COLOR: std::fill_n(out, n, m - kc[c]); return out;
      case gl::CONSTANT_ALPHA: std::fill_n(out, n, kc[3]); return out;
      case gl::ONE_MINUS_CONSTANT_ALPHA: std::fill_n(out, n, m - kc[3]); return out;
      case gl::SRC_ALPHA_SATURATE:
        if (c == 3) std::fill_n(out, n, m);
        else for (int j = 0; j < n; ++j) out[j] = std::min(src[3][j], m - dst[3][j]);
        return out;
      default: std::fill_n(out, n, 0u); return out;
    }
  }

  // rnd(clamp01(v / M^2) * M) of the numerator v over M^2 (blend.h's blend_code),
  // branch free: clamping v to [0, M^2] first gives 0 and M at the ends.
  std::uint32_t finish(I v) const {
    const I m = static_cast<I>(max());
    v = v < 0 ? 0 : v;
    v = v > m * m ? m * m : v;
    if constexpr (kM == 255) {
      // floor((2v + 255) / 510) = floor((v + 127) / 255) (2v + 255 is odd, so
      // the half lost by halving never reaches the next multiple), and
      // floor(y / 255) = (y + 1 + (y >> 8)) >> 8 for 0 <= y < 65535 (checked for
      // every y; here y <= 65025 + 127): shifts and adds, where the vectorised
      // division by 510 took multiplies and shuffles per lane.
      const auto y = static_cast<std::uint32_t>(v) + 127u;
      return (y + 1u + (y >> 8)) >> 8;
    } else {
      return static_cast<std::uint32_t>((2 * v + m) / (2 * m));
    }
  }

  void channel(const FragmentPlanKey& key, const std::uint32_t* kc, int c, int n, std::uint32_t* out) const {
    const std::uint32_t m = max();
    std::uint32_t s_scratch[kChunk], d_scratch[kChunk];
    const std::uint32_t *S = nullptr, *D = nullptr;  // the factors (factor())
    const std::uint32_t* cs = src[c];
    const std::uint32_t* cd = dst[c];
    switch (key.channel[c]) {
      case ChannelOp::Keep: return;
      case ChannelOp::Zero: std::fill_n(out, n, 0u); return;
      case ChannelOp::Copy: std::copy_n(cs, n, out); return;
      case ChannelOp::SrcTerm:
        S = factor(key.blend_src, c, kc, n, s_scratch);
        for (int j = 0; j < n; ++j) out[j] = finish(static_cast<I>(cs[j]) * static_cast<I>(S[j]));
        return;
      case ChannelOp::DstTerm:
        D = factor(key.blend_dst, c, kc, n, d_scratch);
        for (int j = 0; j < n; ++j) out[j] = finish(static_cast<I>(cd[j]) * static_cast<I>(D[j]));
        return;
      case ChannelOp::Add:
        if (key.blend_src == gl::ONE && key.blend_dst == gl::ONE) {
          // finish((s + d)·M) = min(s + d, M): (2(s + d)M + M) / 2M = s + d, and the
          // clamp at M² gives M (numerics §7). The additive pass of the paper.
          for (int j = 0; j < n; ++j) out[j] = std::min(cs[j] + cd[j], m);
          return;
        }
        S = factor(key.blend_src, c, kc, n, s_scratch);
        D = factor(key.blend_dst, c, kc, n, d_scratch);
        for (int j = 0; j < n; ++j)
          out[j] = finish(static_cast<I>(cs[j]) * static_cast<I>(S[j]) + static_cast<I>(cd[j]) * static_cast<I>(D[j]));
        return;
      case ChannelOp::Sub:
        if (key.blend_src == gl::ONE && key.blend_dst == gl::ONE) {  // finish((s − d)·M) = max(s − d, 0)
          for (int j = 0; j < n; ++j) out[j] = cs[j] > cd[j] ? cs[j] - cd[j] : 0u;
          return;
        }
        S = factor(key.blend_src, c, kc, n, s_scratch);
        D = factor(key.blend_dst, c, kc, n, d_scratch);
        for (int j = 0; j < n; ++j)
          out[j] = finish(static_cast<I>(cs[j]) * static_cast<I>(S[j]) - static_cast<I>(cd[j]) * static_cast<I>(D[j]));
        return;
      case ChannelOp::RevSub:
        if (key.blend_src == gl::ONE && key.blend_dst == gl::ONE) {  // finish((d − s)·M) = max(d − s, 0)
          for (int j = 0; j < n; ++j) out[j] = cd[j] > cs[j] ? cd[j] - cs[j] : 0u;
          return;
        }
        S = factor(key.blend_src, c, kc, n, s_scratch);
        D = factor(key.blend_dst, c, kc, n, d_scratch);
        for (int j = 0; j < n; ++j)
          out[j] = finish(static_cast<I>(cd[j]) * static_cast<I>(D[j]) - static_cast<I>(cs[j]) * static_cast<I>(S[j]));
        return;
      case ChannelOp::Min: for (int j = 0; j < n; ++j) out[j] = std::min(cs[j], cd[j]); return;
      case ChannelOp::Max: for (int j = 0; j < n; ++j) out[j] = std::max(cs[j], cd[j]); return;
      case ChannelOp::Logic: for (int j = 0; j < n; ++j) out[j] = logic_op(key.logic_op, cs[j], cd[j], m); return;
    }
  }
};

// The written channels all copy the source, or all use one of the integer forms
// of FixedKernel::channel with (ONE, ONE) factors, or MIN / MAX: computed on the
// interleaved codes
// directly (no de-interleaving), the same values. 0: not applicable.
enum class Interleaved : std::uint8_t { None, Copy, Add, Sub, RevSub, Min, Max };

Interleaved interleaved_op(const FragmentPlanKey& key) {
  Interleaved op = Interleaved::None;
  for (int c = 0; c < 4; ++c) {
    const ChannelOp ch = key.channel[c];
    if (ch == ChannelOp::Keep) continue;
    const bool one_one = key.blend_src == gl::ONE && key.blend_dst == gl::ONE;
    Interleaved o = Interleaved::None;
    if (ch == ChannelOp::Copy) o = Interleaved::Copy;
    else if (ch == ChannelOp::Add && one_one) o = Interleaved::Add;
    else if (ch == ChannelOp::Sub && one_one) o = Interleaved::Sub;
    else if (ch == ChannelOp::RevSub && one_one) o = Interleaved::RevSub;
    else if (ch == ChannelOp::Min) o = Interleaved::Min;
    else if (ch == ChannelOp::Max) o = Interleaved::Max;
    if (o == Interleaved::None || (op != Interleaved::None && o != op)) return Interleaved::None;
    op = o;
  }
  return op;
}

// One operation of Interleaved on two codes (the same values as FixedKernel::channel).
template <Interleaved kOp>
inline std::uint16_t interleaved_value(std::uint16_t m, std::uint16_t s, std::uint16_t d) {
  if constexpr (kOp == Interleaved::Copy) return s;
  else if constexpr (kOp == Interleaved::Add) return static_cast<std::uint16_t>(std::min<std::uint32_t>(std::uint32_t{s} + d, m));
  else if constexpr (kOp == Interleaved::Sub) return static_cast<std::uint16_t>(s > d ? s - d : 0);
  else if constexpr (kOp == Interleaved::RevSub) return static_cast<std::uint16_t>(d > s ? d - s : 0);
  else if constexpr (kOp == Interleaved::Min) return std::min(s, d);
  else return std::max(s, d);
}

// Prefetches, for writing, the framebuffer codes [px + 1024, px + codes + 1024):
// the next chunk's pixels of a row (1024 codes = 256 pixels = kChunk), a line per
// 64 bytes. The colour stage's reads of consecutive pixels otherwise wait on
// memory (a 1024^2 window is 8 MB of colour; docs/performance.md 12.6). A
// prefetch never faults, past the framebuffer's end included (the address is
// formed as an integer: no pointer past the array).
inline void prefetch_next_chunk(const std::uint16_t* px, int codes) {
  const auto base = reinterpret_cast<std::uintptr_t>(px);
  for (int i = 0; i < codes; i += 32)
    __builtin_prefetch(reinterpret_cast<const void*>(base + 2 * static_cast<std::uintptr_t>(i + 1024)), 1);
}

// Every fragment survives (no alpha, stencil or depth test) and every channel is
// written, on consecutive pixels: the operation on the 4n codes, nothing masked.
template <Interleaved kOp>
void color_interleaved_all(std::uint16_t m, const std::uint16_t* in, std::uint16_t* px, int codes) {
  // Only after a full chunk (a long span: its next chunk, or the next row of a
  // large quad, follows); a short run's row beyond it belongs to other primitives.
  if (codes == 4 * kChunk) prefetch_next_chunk(px, codes);
  for (int i = 0; i < codes; ++i) px[i] = interleaved_value<kOp>(m, in[i], px[i]);
}

#ifdef __SSE4_1__
// interleaved_value on a pixel's four codes in 16-bit lanes: ADD as
// min(adds(s, d), M) (a sum above 65535 saturates there, and min gives M either
// way), the subtractions as saturating subtractions (max(·, 0)), MIN/MAX lane-wise.
template <Interleaved kOp>
inline __m128i interleaved_lanes(__m128i m, __m128i s, __m128i d) {
  if constexpr (kOp == Interleaved::Copy) return s;
  else if constexpr (kOp == Interleaved::Add) return _mm_min_epu16(_mm_adds_epu16(s, d), m);
  else if constexpr (kOp == Interleaved::Sub) return _mm_subs_epu16(s, d);
  else if constexpr (kOp == Interleaved::RevSub) return _mm_subs_epu16(d, s);
  else if constexpr (kOp == Interleaved::Min) return _mm_min_epu16(s, d);
  else return _mm_max_epu16(s, d);
}
#endif

#ifdef __AVX2__
template <Interleaved kOp>
inline __m256i interleaved_lanes(__m256i m, __m256i s, __m256i d) {  // interleaved_lanes on four pixels
  if constexpr (kOp == Interleaved::Copy) return s;
  else if constexpr (kOp == Interleaved::Add) return _mm256_min_epu16(_mm256_adds_epu16(s, d), m);
  else if constexpr (kOp == Interleaved::Sub) return _mm256_subs_epu16(s, d);
  else if constexpr (kOp == Interleaved::RevSub) return _mm256_subs_epu16(d, s);
  else if constexpr (kOp == Interleaved::Min) return _mm256_min_epu16(s, d);
  else return _mm256_max_epu16(s, d);
}
#endif

template <Interleaved kOp, class Px>
void color_interleaved(std::uint16_t m, const std::uint16_t* in, std::uint16_t* fb, Px pixel, int n,
                       const std::uint16_t* wmask, const std::uint8_t* alive) {
#ifdef __SSE4_1__
  {  // a pixel (four 16-bit codes) at a time in the low 64 bits of a register
    const __m128i vm = _mm_set1_epi16(static_cast<std::int16_t>(m));
    const __m128i vw = _mm_setr_epi16(static_cast<std::int16_t>(wmask[0]), static_cast<std::int16_t>(wmask[1]),
                                      static_cast<std::int16_t>(wmask[2]), static_cast<std::int16_t>(wmask[3]), 0, 0, 0, 0);
    int j = 0;
#ifdef __AVX2__
    if constexpr (std::is_same_v<Px, RowPixels>) {  // consecutive pixels: four at a time in a 256-bit register
      const __m256i vm4 = _mm256_set1_epi16(static_cast<std::int16_t>(m));
      const __m256i vw4 = _mm256_broadcastq_epi64(vw);
      std::uint16_t* row = fb + 4 * pixel(0);
      for (; j + 4 <= n; j += 4) {
        const __m256i d = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(row + 4 * j));
        const __m256i s = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(in + 4 * j));
        std::int32_t a4;
        std::memcpy(&a4, alive + j, sizeof a4);
        // alive[j..j+3] (0 or 1) widened to one 64-bit lane per pixel, then all ones where alive
        const __m256i live = _mm256_cmpgt_epi64(_mm256_cvtepu8_epi64(_mm_cvtsi32_si128(a4)), _mm256_setzero_si256());
        const __m256i w = _mm256_and_si256(vw4, live);
        const __m256i r = interleaved_lanes<kOp>(vm4, s, d);
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(row + 4 * j), _mm256_or_si256(_mm256_and_si256(r, w), _mm256_andnot_si256(w, d)));
      }
    }
#endif
    for (; j < n; ++j) {
      std::uint16_t* px = fb + 4 * pixel(j);
      const __m128i d = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(px));
      const __m128i s = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(in + 4 * j));
      const __m128i w = _mm_and_si128(vw, _mm_set1_epi16(static_cast<std::int16_t>(-static_cast<int>(alive[j] != 0))));
      const __m128i r = interleaved_lanes<kOp>(vm, s, d);
      _mm_storel_epi64(reinterpret_cast<__m128i*>(px), _mm_or_si128(_mm_and_si128(r, w), _mm_andnot_si128(w, d)));
    }
  }
#else
  for (int j = 0; j < n; ++j) {
    const std::uint16_t a = alive[j] ? 0xFFFF : 0;
    std::uint16_t* px = fb + 4 * pixel(j);
    for (int c = 0; c < 4; ++c) {
      const std::uint16_t d = px[c];
      const std::uint16_t r = interleaved_value<kOp>(m, in[4 * j + c], d);
      const std::uint16_t w = a & wmask[c];
      px[c] = static_cast<std::uint16_t>((r & w) | (d & ~w));
    }
  }
#endif
}

// Copy on listed pixels: the written channels of each surviving fragment stored,
// nothing read. (color_interleaved's (s & w) | (d & ~w) with Copy's r = s is s on
// the written channels of a surviving fragment and d elsewhere: the stores leave
// every other code as it is.) kMask: the written channels, bit c for channel c.
template <unsigned kMask>
void copy_listed(const std::uint16_t* in, std::uint16_t* fb, ListPixels pixel, int n, const std::uint8_t* alive) {
  for (int j = 0; j < n; ++j) {
    if (!alive[j]) continue;
    std::uint16_t* px = fb + 4 * pixel(j);
    const std::uint16_t* s = in + 4 * static_cast<std::size_t>(j);
    if constexpr (kMask == 0xF) {
      std::memcpy(px, s, 4 * sizeof(std::uint16_t));
    } else if constexpr (kMask == 0x7) {
      std::memcpy(px, s, 2 * sizeof(std::uint16_t));
      px[2] = s[2];
    } else {
      for (int c = 0; c < 4; ++c)
        if (kMask & (1u << c)) px[c] = s[c];
    }
  }
}

// f(the operation as a compile-time constant), for an operation other than None.
template <class F>
void with_interleaved(Interleaved op, F f) {
  switch (op) {
    case Interleaved::Copy: return f(std::integral_constant<Interleaved, Interleaved::Copy>{});
    case Interleaved::Add: return f(std::integral_constant<Interleaved, Interleaved::Add>{});
    case Interleaved::Sub: return f(std::integral_constant<Interleaved, Interleaved::Sub>{});
    case Interleaved::RevSub: return f(std::integral_constant<Interleaved, Interleaved::RevSub>{});
    case Interleaved::Min: return f(std::integral_constant<Interleaved, Interleaved::Min>{});
    default: return f(std::integral_constant<Interleaved, Interleaved::Max>{});
  }
}

// The colour stage of 8-bit colour (M = 255) with four pixels' channels at
// once (blend_lanes8.h; plan.lanes8.usable).
template <class Px>
void color_lanes8(const FragmentPlan& plan, const FragmentConstants& k, const std::uint16_t* in, std::uint16_t* fb,
                  Px pixel, int n, const std::uint8_t* alive) {
  const std::uint32_t* kc = k.blend_color_code.data();
  if constexpr (std::is_same_v<Px, RowPixels>) blend_lanes8_row(plan.lanes8, kc, in, fb, pixel.first, n, alive);
  else blend_lanes8_list(plan.lanes8, kc, in, fb, pixel.pixel, n, alive);
}

// The fixed colour stage of a chunk: `in` its colour codes, fragment j at
// pixel pixel(j) of `fb`.
template <std::uint32_t kM, class Px>
void color_stage_fixed(const FragmentPlan& plan, const FragmentConstants& k, const std::uint16_t* in, std::uint16_t* fb,
                       Px pixel, int n, const std::uint8_t* alive) {
  if (const Interleaved op = interleaved_op(plan.key); op != Interleaved::None) {
    std::uint16_t wmask[4];
    for (int c = 0; c < 4; ++c) wmask[c] = plan.key.channel[c] != ChannelOp::Keep ? 0xFFFF : 0;
    const auto m = static_cast<std::uint16_t>(kM ? kM : k.color_max);
    if constexpr (std::is_same_v<Px, RowPixels>) {
      const FragmentPlanKey& key = plan.key;
      if (key.alpha_func == 0 && !key.stencil && !key.depth && (wmask[0] & wmask[1] & wmask[2] & wmask[3])) {
        std::uint16_t* px = fb + 4 * pixel(0);
        with_interleaved(op, [&](auto o) { color_interleaved_all<o.value>(m, in, px, 4 * n); });
        return;
      }
    }
    if constexpr (std::is_same_v<Px, ListPixels>) {
      if (op == Interleaved::Copy) {  // the paper's alpha-only and RGB passes without blending
        const unsigned mask = (wmask[0] & 1u) | (wmask[1] & 2u) | (wmask[2] & 4u) | (wmask[3] & 8u);
        switch (mask) {
          case 0x8: return copy_listed<0x8>(in, fb, pixel, n, alive);
          case 0x7: return copy_listed<0x7>(in, fb, pixel, n, alive);
          case 0xF: return copy_listed<0xF>(in, fb, pixel, n, alive);
          default: break;  // (other masks: color_interleaved)
        }
      }
      if (kM == 255 && plan.lanes8.usable) return color_lanes8(plan, k, in, fb, pixel, n, alive);  // gathered 4 at a time
    }
    with_interleaved(op, [&](auto o) { color_interleaved<o.value>(m, in, fb, pixel, n, wmask, alive); });
    return;
  }
  if (kM == 255 && plan.lanes8.usable) return color_lanes8(plan, k, in, fb, pixel, n, alive);
  FixedKernel<kM> kern;
  kern.M = k.color_max;
  // One written channel c (the paper's alpha-only passes): FixedKernel::channel and
  // its factors read only channel c and alpha of the source and the destination,
  // so only those are de-interleaved, and only channel c is stored (the same
  // values; the other channels are kept as the write mask keeps them).
  int written = -1, count = 0;
  for (int c = 0; c < 4; ++c)
    if (plan.key.channel[c] != ChannelOp::Keep) written = c, ++count;
  if (count == 1) {
    const int c = written;
    for (int j = 0; j < n; ++j) {
      kern.src[c][j] = in[4 * j + c];
      kern.src[3][j] = in[4 * j + 3];
    }
    if (plan.read_dst_color) {
      int j0 = 0;
#if defined(__AVX2__)
      if constexpr (std::is_same_v<Px, ListPixels>) {
        // Eight pixels' channel c and alpha by 32-bit gathers: the code pair
        // (2, 3) at byte 8p + 4 and, when c < 2, the pair (0, 1) at 8p (little
        // endian: the lower channel in the low half). Pixel indices are below
        // 2^26 (run_fragment_plan_pixels), so the gather indices 2p + 1 and 2p fit.
        const int* base = reinterpret_cast<const int*>(fb);
        const __m256i lo16 = _mm256_set1_epi32(0xFFFF);
        for (; j0 + 8 <= n; j0 += 8) {
          const __m256i p2 = _mm256_slli_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(pixel.pixel + j0)), 1);
          const __m256i hi = _mm256_i32gather_epi32(base, _mm256_add_epi32(p2, _mm256_set1_epi32(1)), 4);  // B | A << 16
          _mm256_storeu_si256(reinterpret_cast<__m256i*>(kern.dst[3] + j0), _mm256_srli_epi32(hi, 16));
          if (c == 2) _mm256_storeu_si256(reinterpret_cast<__m256i*>(kern.dst[2] + j0), _mm256_and_si256(hi, lo16));
          if (c < 2) {
            const __m256i low = _mm256_i32gather_epi32(base, p2, 4);  // R | G << 16
            _mm256_storeu_si256(reinterpret_cast<__m256i*>(kern.dst[c] + j0),
                                c == 0 ? _mm256_and_si256(low, lo16) : _mm256_srli_epi32(low, 16));
          }
        }
      }
#endif
      for (int j = j0; j < n; ++j) {
        const std::uint16_t* px = fb + 4 * pixel(j);
        kern.dst[c][j] = px[c];
        kern.dst[3][j] = px[3];
      }
    }
    std::uint32_t out[kChunk];
    kern.channel(plan.key, k.blend_color_code.data(), c, n, out);
    for (int j = 0; j < n; ++j)
      if (alive[j]) fb[4 * pixel(j) + static_cast<std::size_t>(c)] = static_cast<std::uint16_t>(out[j]);
    return;
  }
  int j1 = 0;
#ifdef __SSE4_1__
  // Four pixels' codes at a time transposed to the four channel arrays.
  auto split4 = [](__m128i x01, __m128i x23, std::uint32_t (&to)[4][kChunk], int j) {
    rgba16_to_lanes(x01, x23, to[0] + j, to[1] + j, to[2] + j, to[3] + j);
  };
  for (; j1 + 4 <= n; j1 += 4)
    split4(_mm_loadu_si128(reinterpret_cast<const __m128i*>(in + 4 * j1)),
           _mm_loadu_si128(reinterpret_cast<const __m128i*>(in + 4 * j1 + 8)), kern.src, j1);
#endif
  for (int j = j1; j < n; ++j)
    for (int q = 0; q < 4; ++q) kern.src[q][j] = in[4 * j + q];
  if (plan.read_dst_color) {
    int j2 = 0;
#ifdef __SSE4_1__
    auto px64 = [&](int j) { return _mm_loadl_epi64(reinterpret_cast<const __m128i*>(fb + 4 * pixel(j))); };
    for (; j2 + 4 <= n; j2 += 4)
      split4(_mm_unpacklo_epi64(px64(j2), px64(j2 + 1)), _mm_unpacklo_epi64(px64(j2 + 2), px64(j2 + 3)), kern.dst, j2);
#endif
    for (int j = j2; j < n; ++j) {
      const std::uint16_t* px = fb + 4 * pixel(j);
      for (int q = 0; q < 4; ++q) kern.dst[q][j] = px[q];
    }
  }
  const std::uint32_t* kc = k.blend_color_code.data();
  std::uint32_t out[4][kChunk];
  std::uint16_t wmask[4];
  for (int c = 0; c < 4; ++c) {
    const bool written = plan.key.channel[c] != ChannelOp::Keep;
    wmask[c] = written ? 0xFFFF : 0;
    if (written) kern.channel(plan.key, kc, c, n, out[c]);
    else std::fill_n(out[c], n, 0u);
  }
  // Masked store: written channels of surviving fragments only.
  int j0 = 0;
#ifdef __SSE4_1__
  {  // four fragments at a time: the channel arrays packed to 16 bits and transposed
     // to pixels (codes <= M < 2^16: packus keeps them), each pixel blended as in
     // color_interleaved
    const __m128i vw = _mm_setr_epi16(static_cast<std::int16_t>(wmask[0]), static_cast<std::int16_t>(wmask[1]),
                                      static_cast<std::int16_t>(wmask[2]), static_cast<std::int16_t>(wmask[3]),
                                      static_cast<std::int16_t>(wmask[0]), static_cast<std::int16_t>(wmask[1]),
                                      static_cast<std::int16_t>(wmask[2]), static_cast<std::int16_t>(wmask[3]));
    auto load4 = [](const std::uint32_t* p) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p)); };
    auto put = [&](int j, __m128i pixel_codes) {  // pixel_codes: this pixel's four codes in the low 64 bits
      std::uint16_t* px = fb + 4 * pixel(j);
      const __m128i d = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(px));
      const __m128i w = _mm_and_si128(vw, _mm_set1_epi16(static_cast<std::int16_t>(-static_cast<int>(alive[j] != 0))));
      _mm_storel_epi64(reinterpret_cast<__m128i*>(px), _mm_or_si128(_mm_and_si128(pixel_codes, w), _mm_andnot_si128(w, d)));
    };
    for (; j0 + 4 <= n; j0 += 4) {
      const __m128i rg = _mm_packus_epi32(load4(out[0] + j0), load4(out[1] + j0));  // r0..r3 g0..g3
      const __m128i ba = _mm_packus_epi32(load4(out[2] + j0), load4(out[3] + j0));  // b0..b3 a0..a3
      const __m128i rb = _mm_unpacklo_epi16(rg, ba), ga = _mm_unpackhi_epi16(rg, ba);  // r0 b0 r1 b1 .., g0 a0 ..
      const __m128i p01 = _mm_unpacklo_epi16(rb, ga), p23 = _mm_unpackhi_epi16(rb, ga);  // r0 g0 b0 a0 r1 g1 b1 a1, ..
      put(j0, p01);
      put(j0 + 1, _mm_unpackhi_epi64(p01, p01));
      put(j0 + 2, p23);
      put(j0 + 3, _mm_unpackhi_epi64(p23, p23));
    }
  }
#endif
  for (int j = j0; j < n; ++j) {
    const std::uint16_t a = alive[j] ? 0xFFFF : 0;
    std::uint16_t* px = fb + 4 * pixel(j);
    for (int c = 0; c < 4; ++c) {
      const std::uint16_t m = a & wmask[c];
      px[c] = static_cast<std::uint16_t>((static_cast<std::uint16_t>(out[c][j]) & m) | (px[c] & ~m));
    }
  }
}

void color_stage(const FragmentPlan& plan, const FragmentConstants& k, const FragmentSpan& sp, const FragmentBuffers& b,
                 std::size_t row, int start, int n, const std::uint8_t* alive, Arithmetic arith) {
  switch (arith) {
    case Arithmetic::Fixed: {
      const std::uint16_t* in = sp.codes.data() + 4 * static_cast<std::size_t>(start);
      const RowPixels pixel{row + static_cast<std::size_t>(sp.x0 + start)};
      if (k.color_max == 255) color_stage_fixed<255>(plan, k, in, b.codes, pixel, n, alive);
      else color_stage_fixed<0>(plan, k, in, b.codes, pixel, n, alive);
      return;
    }
    case Arithmetic::Float32:
      for (int c = 0; c < 4; ++c) color_channel_float<float>(plan, k, sp, b, row, start, n, alive, c, arith);
      return;
    case Arithmetic::Float64:
      for (int c = 0; c < 4; ++c) color_channel_float<double>(plan, k, sp, b, row, start, n, alive, c, arith);
      return;
  }
}

// What a depth stage saw (ListedDepthTest): `cmp` (may be null) receives each
// fragment's comparison z OP stored, alive or not; would_store whether one
// passing the comparison has z != stored; stored whether a depth changed.
struct DepthOutcome {
  std::uint8_t* cmp = nullptr;
  bool would_store = false;
  bool stored = false;
};

// Stencil and depth tests with the stencil operations for a chunk: fragment j
// has depth z[j] and lands on pixel(j); a failing fragment's `alive` is cleared.
// The depth test alone (no stencil), for one comparison chosen outside the loop:
// branch free, so the depth loads of a chunk overlap instead of waiting behind
// mispredicted test results. A failing or dead fragment rewrites the stored
// depth unchanged (its own pixel: no other fragment of the chunk touches it).
#if defined(__AVX2__) && defined(__BMI2__)
// test_func(F, a, b) on eight unsigned 32-bit lanes: all ones where it holds.
// (AVX2 compares signed lanes only: a <= b is min_epu32(a, b) == a.)
template <GLenum F>
inline __m256i test_lanes(__m256i a, __m256i b) {
  const __m256i ones = _mm256_set1_epi32(-1);
  const __m256i le = _mm256_cmpeq_epi32(_mm256_min_epu32(a, b), a);
  const __m256i eq = _mm256_cmpeq_epi32(a, b);
  if constexpr (F == gl::LESS) return _mm256_andnot_si256(eq, le);
  else if constexpr (F == gl::EQUAL) return eq;
  else if constexpr (F == gl::LEQUAL) return le;
  else if constexpr (F == gl::GREATER) return _mm256_xor_si256(le, ones);
  else if constexpr (F == gl::NOTEQUAL) return _mm256_xor_si256(eq, ones);
  else if constexpr (F == gl::GEQUAL) return _mm256_or_si256(_mm256_xor_si256(le, ones), eq);
  else if constexpr (F == gl::NEVER) return _mm256_setzero_si256();
  else return ones;  // ALWAYS
}

// f(std::integral_constant<GLenum, F>) for the eight functions; false for any
// other token (it reaches no caller: keys hold valid functions).
template <class Fn>
bool with_test_lanes(GLenum func, Fn&& f) {
  switch (func) {
    case gl::NEVER: f(std::integral_constant<GLenum, gl::NEVER>{}); return true;
    case gl::LESS: f(std::integral_constant<GLenum, gl::LESS>{}); return true;
    case gl::EQUAL: f(std::integral_constant<GLenum, gl::EQUAL>{}); return true;
    case gl::LEQUAL: f(std::integral_constant<GLenum, gl::LEQUAL>{}); return true;
    case gl::GREATER: f(std::integral_constant<GLenum, gl::GREATER>{}); return true;
    case gl::NOTEQUAL: f(std::integral_constant<GLenum, gl::NOTEQUAL>{}); return true;
    case gl::GEQUAL: f(std::integral_constant<GLenum, gl::GEQUAL>{}); return true;
    case gl::ALWAYS: f(std::integral_constant<GLenum, gl::ALWAYS>{}); return true;
    default: return false;
  }
}

// The alpha test on eight fragments' fixed codes at a time: each fragment's
// alpha (its 16-bit code at 4j + 3) shifted down in its 64-bit lane, two
// registers' lanes interleaved into 32-bit lanes and put back in order, then
// a_s OP ref as test_func. Returns the fragments done (a multiple of 8).
template <GLenum F>
int alpha_test_fixed8(const std::uint16_t* in, std::uint32_t ref, int n, std::uint8_t* alive) {
  const __m256i r = _mm256_set1_epi32(static_cast<int>(ref));
  const __m256i order = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7);
  int j = 0;
  for (; j + 8 <= n; j += 8) {
    const __m256i lo = _mm256_srli_epi64(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(in + 4 * j)), 48);
    const __m256i hi = _mm256_srli_epi64(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(in + 4 * j + 16)), 48);
    // lo's 32-bit lanes: a0 0 a1 0 | a2 0 a3 0; hi's a4..a7 likewise. Or'd with hi
    // one lane up: a0 a4 a1 a5 | a2 a6 a3 a7, which `order` sorts.
    const __m256i a = _mm256_permutevar8x32_epi32(_mm256_or_si256(lo, _mm256_slli_epi64(hi, 32)), order);
    const auto bits = static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(test_lanes<F>(a, r))));
    const std::uint64_t a8 = _pdep_u64(bits, 0x0101010101010101ull);  // one byte 0 or 1 per fragment
    std::memcpy(alive + j, &a8, sizeof a8);
  }
  return j;
}
#endif

// The alpha test on fixed codes: fragment j's alpha is in[4j + 3].
void alpha_test_fixed(GLenum func, const std::uint16_t* in, std::uint32_t ref, int n, std::uint8_t* alive) {
#if defined(__AVX2__) && defined(__BMI2__)
  int done = 0;
  with_test_lanes(func, [&](auto f) { done = alpha_test_fixed8<decltype(f)::value>(in, ref, n, alive); });
  in += 4 * static_cast<std::ptrdiff_t>(done);
  alive += done;
  n -= done;
#endif
  // (by value: a byte store may alias anything, so captured references would be
  // loaded again for every fragment)
  with_test_func<std::uint32_t>(func, [=](auto op) {
    for (int j = 0; j < n; ++j) alive[j] = op(in[4 * j + 3], ref);
  });
}

#if defined(__AVX2__) && defined(__BMI2__)

// depth_only on listed pixels, eight fragments at a time: the stored depths
// gathered, the test and `alive` branch free, and the stores only where a depth
// changes (a surviving fragment whose depth differs from the stored one: the
// paper's later passes, LEQUAL on the same geometry, store nothing). The pixels of
// a chunk are distinct, so the gathers read what the scalar loop would. Returns
// the fragments done (a multiple of 8).
template <GLenum F>
int depth_only_listed8(bool write, const std::uint32_t* z, std::uint32_t* depth, const std::uint32_t* pixel, int n,
                       std::uint8_t* alive, DepthOutcome& out) {
  int j = 0;
  unsigned would_store = 0, stored = 0;
  for (; j + 8 <= n; j += 8) {
    // Pixel indices are below 2^26 (run_fragment_plan_pixels): the gather's
    // signed 32-bit indices hold them.
    const __m256i idx = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(pixel + j));
    const __m256i zb = _mm256_i32gather_epi32(reinterpret_cast<const int*>(depth), idx, 4);
    const __m256i zz = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(z + j));
    std::uint64_t a8;
    std::memcpy(&a8, alive + j, sizeof a8);
    const __m256i live = _mm256_cmpgt_epi32(_mm256_cvtepu8_epi32(_mm_cvtsi64_si128(static_cast<long long>(a8))),
                                            _mm256_setzero_si256());
    const __m256i test = test_lanes<F>(zz, zb);
    const __m256i pass = _mm256_and_si256(live, test);
    const auto bits = static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(pass)));
    a8 = _pdep_u64(bits, 0x0101010101010101ull);  // one byte 0 or 1 per fragment
    std::memcpy(alive + j, &a8, sizeof a8);
    // Passing the comparison with a depth other than the stored one: stored
    // where the fragment is also alive.
    const auto differs = static_cast<unsigned>(
        _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_andnot_si256(_mm256_cmpeq_epi32(zz, zb), test))));
    if (out.cmp) {
      const std::uint64_t c8 = _pdep_u64(static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(test))),
                                         0x0101010101010101ull);
      std::memcpy(out.cmp + j, &c8, sizeof c8);
      would_store |= differs;
    }
    if (write) {
      auto store = differs & bits;
      stored |= store;
      for (; store; store &= store - 1) {
        const int i = std::countr_zero(store);
        depth[pixel[j + i]] = z[j + i];
      }
    }
  }
  out.would_store |= would_store != 0;
  out.stored |= stored != 0;
  return j;
}
#endif

template <class Px, class Cmp>
void depth_only(bool write, const std::uint32_t* z, std::uint32_t* depth, Px pixel, int n, std::uint8_t* alive,
                DepthOutcome& out, Cmp cmp) {
  bool would_store = false, stored = false;
  for (int j = 0; j < n; ++j) {
    const std::size_t p = pixel(j);
    const std::uint32_t zb = depth[p];
    const bool test = cmp(z[j], zb);
    const bool pass = alive[j] && test;
    alive[j] = pass;
    if (out.cmp) out.cmp[j] = test;
    would_store |= test && z[j] != zb;
    stored |= pass && z[j] != zb;
    if (write) depth[p] = pass ? z[j] : zb;
  }
  out.would_store |= would_store;
  out.stored |= write && stored;
}

template <class Px>
void depth_only_stage(GLenum func, bool write, const std::uint32_t* z, std::uint32_t* depth, Px pixel, int n,
                      std::uint8_t* alive, DepthOutcome& out) {
#if defined(__AVX2__) && defined(__BMI2__)
  if constexpr (std::is_same_v<Px, ListPixels>) {
    int done = 0;  // (NEVER too: its lanes fail every fragment and store nothing)
    with_test_lanes(func, [&](auto f) {
      done = depth_only_listed8<decltype(f)::value>(write, z, depth, pixel.pixel, n, alive, out);
    });
    // The remaining fragments (fewer than 8) by the loops below.
    z += done;
    pixel.pixel += done;
    alive += done;
    if (out.cmp) out.cmp += done;
    n -= done;
  }
#endif
  switch (func) {  // test_func's table (test_func.h)
    case gl::NEVER:
      std::fill_n(alive, n, std::uint8_t{0});
      if (out.cmp) std::fill_n(out.cmp, n, std::uint8_t{0});
      return;
    case gl::LESS: return depth_only(write, z, depth, pixel, n, alive, out, [](std::uint32_t a, std::uint32_t b) { return a < b; });
    case gl::EQUAL: return depth_only(write, z, depth, pixel, n, alive, out, [](std::uint32_t a, std::uint32_t b) { return a == b; });
    case gl::LEQUAL: return depth_only(write, z, depth, pixel, n, alive, out, [](std::uint32_t a, std::uint32_t b) { return a <= b; });
    case gl::GREATER: return depth_only(write, z, depth, pixel, n, alive, out, [](std::uint32_t a, std::uint32_t b) { return a > b; });
    case gl::NOTEQUAL: return depth_only(write, z, depth, pixel, n, alive, out, [](std::uint32_t a, std::uint32_t b) { return a != b; });
    case gl::GEQUAL: return depth_only(write, z, depth, pixel, n, alive, out, [](std::uint32_t a, std::uint32_t b) { return a >= b; });
    case gl::ALWAYS: return depth_only(write, z, depth, pixel, n, alive, out, [](std::uint32_t, std::uint32_t) { return true; });
    default:
      std::fill_n(alive, n, std::uint8_t{0});
      if (out.cmp) std::fill_n(out.cmp, n, std::uint8_t{0});
      return;
  }
}

// The stencil test of a plan whose three operations are KEEP (stencil_ops_kept):
// a failing fragment's `alive` is cleared; the buffer is only read.
template <class Px>
void stencil_test_kept(const FragmentPlanKey& key, const FragmentConstants& k, const std::uint8_t* S, Px pixel, int n,
                       std::uint8_t* alive) {
  const FragmentConstants::StencilTables& st = k.stencil_tables;
  if (st.valid && st.func == key.stencil_func) {
    const std::uint8_t* const pass = st.pass.data();
    for (int j = 0; j < n; ++j) alive[j] &= pass[S[pixel(j)]];
    return;
  }
  const std::uint32_t vm = k.stencil_value_mask, ref_m = k.stencil_ref & vm;
  for (int j = 0; j < n; ++j)
    alive[j] &= test_func<std::uint32_t>(key.stencil_func, ref_m, S[pixel(j)] & vm) ? 1 : 0;
}

template <class Px>
void stencil_depth_stage(const FragmentPlanKey& key, const FragmentConstants& k, const std::uint32_t* z,
                         const FragmentBuffers& b, Px pixel, int n, std::uint8_t* alive, DepthOutcome& out) {
  if (!key.stencil) {
    depth_only_stage(key.depth_func, key.depth_write, z, b.depth, pixel, n, alive, out);
    return;
  }
  out.stored |= key.depth && key.depth_write;  // (not tracked exactly with the stencil test)
  // The stencil test, then the depth test if enabled, with the stencil operations.
  const FragmentConstants::StencilTables& st = k.stencil_tables;
  if (st.valid && st.func == key.stencil_func && st.sfail == key.sfail && st.dpfail == key.dpfail &&
      st.dppass == key.dppass) {
    // The same rules looked up by stored value (no switch per fragment).
    // (The buffers and tables as locals: a byte store may alias anything, so
    // members and captured references would be loaded again for every fragment.)
    std::uint8_t* const S = b.stencil;
    const std::uint8_t *const spass_of = st.pass.data(), *const sfail = st.after_sfail.data();
    const std::uint8_t *const dpfail = st.after_dpfail.data(), *const dppass = st.after_dppass.data();
    if (!key.depth) {  // without a branch per fragment: a dead fragment keeps the stored value
      auto one = [=](int j) {
        const std::size_t p = pixel(j);
        const std::uint8_t old = S[p];
        const bool a = alive[j] != 0, pass = spass_of[old] != 0;
        const std::uint8_t next = pass ? dppass[old] : sfail[old];
        S[p] = a ? next : old;
        alive[j] = a && pass;
      };
      int j = 0;
#if defined(__AVX2__)
      if constexpr (std::is_same_v<Px, RowPixels>) {
        // A row's 32 stored values at once when they are all equal (a cleared or
        // marked region, the common case): the tables' entries for that value,
        // the store selected by `alive`. The same values as `one` on each.
        std::uint8_t* const row = S + pixel.first;
        const __m256i zero = _mm256_setzero_si256();
        for (; j + 32 <= n; j += 32) {
          const __m256i old = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(row + j));
          const std::uint8_t v = row[j];
          if (_mm256_movemask_epi8(_mm256_cmpeq_epi8(old, _mm256_set1_epi8(static_cast<char>(v)))) != -1) {
            for (int i = j; i < j + 32; ++i) one(i);  // mixed values
            continue;
          }
          const __m256i a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(alive + j));
          const bool pass = spass_of[v] != 0;
          const std::uint8_t next = pass ? dppass[v] : sfail[v];
          const __m256i live = _mm256_cmpgt_epi8(a, zero);  // (alive bytes are 0 or 1)
          _mm256_storeu_si256(reinterpret_cast<__m256i*>(row + j),
                              _mm256_blendv_epi8(old, _mm256_set1_epi8(static_cast<char>(next)), live));
          if (!pass) _mm256_storeu_si256(reinterpret_cast<__m256i*>(alive + j), zero);
        }
      }
#endif
      for (; j < n; ++j) one(j);
      return;
    }
    // With the depth test, the same selects; the comparison chosen once. A
    // fragment stores its depth where it passes both tests (and writes are on).
    std::uint32_t* const D = b.depth;
    const bool write = key.depth_write;
    with_test_func<std::uint32_t>(key.depth_func, [=](auto op) {
      for (int j = 0; j < n; ++j) {
        const std::size_t p = pixel(j);
        const std::uint8_t old = S[p];
        const std::uint32_t zb = D[p];
        const bool a = alive[j] != 0, spass = spass_of[old] != 0, dpass = op(z[j], zb);
        const std::uint8_t next = !spass ? sfail[old] : !dpass ? dpfail[old] : dppass[old];
        S[p] = a ? next : old;
        const bool pass = a && spass && dpass;
        if (write) D[p] = pass ? z[j] : zb;
        alive[j] = pass;
      }
    });
    return;
  }
  const std::uint32_t ref = k.stencil_ref, vm = k.stencil_value_mask, wm = k.stencil_writemask, smax = k.stencil_max;
  const std::uint32_t ref_m = ref & vm;
  for (int j = 0; j < n; ++j) {
    if (!alive[j]) continue;
    const std::size_t p = pixel(j);
    const std::uint32_t old = b.stencil[p];
    if (!test_func<std::uint32_t>(key.stencil_func, ref_m, old & vm)) {
      b.stencil[p] = static_cast<std::uint8_t>(stencil_write(key.sfail, old, ref, smax, wm));
      alive[j] = 0;
      continue;
    }
    if (key.depth) {
      if (!test_func<std::uint32_t>(key.depth_func, z[j], b.depth[p])) {
        b.stencil[p] = static_cast<std::uint8_t>(stencil_write(key.dpfail, old, ref, smax, wm));
        alive[j] = 0;
        continue;
      }
      if (key.depth_write) b.depth[p] = z[j];
    }
    b.stencil[p] = static_cast<std::uint8_t>(stencil_write(key.dppass, old, ref, smax, wm));
  }
}

void check_span(const FragmentSpan& sp, bool fixed) {
  const std::size_t need = 4 * static_cast<std::size_t>(sp.count);
  if ((fixed ? sp.codes.size() : sp.values.size()) < need)
    throw std::invalid_argument("fragment span: fewer colour components than 4 x count");
}

}  // namespace

bool run_fragment_plan(const FragmentPlan& plan, const FragmentConstants& k, const FragmentSpan& sp,
                       const FragmentBuffers& b, int width) {
  const FragmentPlanKey& key = plan.key;
  if (key.nothing) return false;
  const SpanRange range = scissor_span(k.rect, sp.y, sp.x0, sp.count);
  if (range.empty()) return false;
  const bool fixed = key.arith == Arithmetic::Fixed;
  check_span(sp, fixed);
  if (key.depth && sp.depth.size() < static_cast<std::size_t>(sp.count))
    throw std::invalid_argument("fragment span: the depth test is enabled but the span carries no depth");
  const std::size_t row = static_cast<std::size_t>(sp.y) * static_cast<std::size_t>(width);
  std::uint8_t alive[kChunk];
  DepthOutcome depth_out;
  for (int start = range.begin; start < range.end; start += kChunk) {
    const int n = std::min(kChunk, range.end - start);
    std::fill_n(alive, n, std::uint8_t{1});
    // Alpha test: A_s OP ref.
    if (key.alpha_func != 0) {
      const GLenum f = key.alpha_func;
      if (fixed) {
        alpha_test_fixed(f, sp.codes.data() + 4 * static_cast<std::size_t>(start), k.alpha_ref_code, n, alive);
      } else {
        const bool f32 = key.arith == Arithmetic::Float32;
        for (int j = 0; j < n; ++j) {
          const double a = sp.values[4 * static_cast<std::size_t>(start + j) + 3];
          alive[j] = test_func<double>(f, f32 ? static_cast<double>(static_cast<float>(a)) : a, k.alpha_ref_value);
        }
      }
    }
    // Stencil and depth tests with the stencil operations.
    if (key.stencil || key.depth)
      stencil_depth_stage(key, k, key.depth ? sp.depth.data() + start : nullptr, b,
                          RowPixels{row + static_cast<std::size_t>(sp.x0 + start)}, n, alive, depth_out);
    // Blending / logic op, dithering (identity), masked colour writes.
    if (plan.write_color) color_stage(plan, k, sp, b, row, start, n, alive, key.arith);
  }
  return depth_out.stored;
}

void run_fragment_plan_pixels(const FragmentPlan& plan, const FragmentConstants& k, const std::uint16_t* codes,
                              const std::uint32_t* depth, const std::uint32_t* pixel, int n, const FragmentBuffers& b,
                              ListedDepthTest* depth_test) {
  const FragmentPlanKey& key = plan.key;
  if (depth_test) {
    depth_test->recorded = false;
    depth_test->would_store = false;
    depth_test->stored = false;
  }
  if (key.nothing || n <= 0) return;
  if (key.arith != Arithmetic::Fixed) throw std::invalid_argument("run_fragment_plan_pixels: fixed colour only");
  if (key.depth && depth == nullptr)
    throw std::invalid_argument("run_fragment_plan_pixels: the depth test is enabled but no depth was given");
  // The depth test alone may take known comparisons or record them
  // (ListedDepthTest); a stencil test that writes nothing is then a mask before it.
  const bool depth_alone = depth_test_alone(key);
  const bool stencil_mask = depth_alone && key.stencil;
  const std::uint8_t* known = depth_alone && depth_test ? depth_test->known : nullptr;
  std::uint8_t* record = depth_alone && depth_test && !known ? depth_test->record : nullptr;
  DepthOutcome depth_out;
  std::uint8_t alive[kChunk];
  for (int start = 0; start < n; start += kChunk) {
    const int m = std::min(kChunk, n - start);
    const std::uint16_t* in = codes + 4 * static_cast<std::size_t>(start);
    const ListPixels px{pixel + start};
    std::fill_n(alive, m, std::uint8_t{1});
    if (key.alpha_func != 0) alpha_test_fixed(key.alpha_func, in, k.alpha_ref_code, m, alive);  // A_s OP ref
    if (stencil_mask) stencil_test_kept(key, k, b.stencil, px, m, alive);
    if (depth_alone && known) {  // the comparisons known: the buffer is neither read nor written
      for (int j = 0; j < m; ++j) alive[j] &= known[start + j];
    } else if (key.stencil || key.depth) {
      depth_out.cmp = record ? record + start : nullptr;
      if (stencil_mask) depth_only_stage(key.depth_func, key.depth_write, depth + start, b.depth, px, m, alive, depth_out);
      else stencil_depth_stage(key, k, key.depth ? depth + start : nullptr, b, px, m, alive, depth_out);
    }
    if (!plan.write_color) continue;
    if (k.color_max == 255) color_stage_fixed<255>(plan, k, in, b.codes, px, m, alive);
    else color_stage_fixed<0>(plan, k, in, b.codes, px, m, alive);
  }
  if (depth_test) {
    depth_test->recorded = record != nullptr;
    depth_test->would_store = record != nullptr && depth_out.would_store;
    depth_test->stored = depth_out.stored;
  }
}

// ---------------------------------------------------------------------------
// The full path: every stage, every fragment, every channel, read from the raw
// state. The reference the plan is checked against.

namespace {

template <class T>
void full_color_float(const FragmentOpsState& s, const FragmentConstants& k, const FragmentSpan& sp,
                      const FragmentBuffers& b, int i, std::size_t p, Arithmetic arith) {
  T sv[4], dv[4], kv[4];
  for (int q = 0; q < 4; ++q) {
    sv[q] = static_cast<T>(sp.values[4 * static_cast<std::size_t>(i) + q]);
    dv[q] = static_cast<T>(b.values[4 * p + q]);
    kv[q] = static_cast<T>(k.blend_color_value[q]);
  }
  double out[4];
  for (int c = 0; c < 4; ++c) {
    if (s.blend.enabled) {  // the logic op does not apply to float colour
      const T S = blend_factor<T>(s.blend.src, c, sv, dv, kv, T(1));
      const T D = blend_factor<T>(s.blend.dst, c, sv, dv, kv, T(1));
      T r = blend_value<T>(s.blend.equation, sv[c], S, dv[c], D);
      out[c] = static_cast<double>(clamp01(r));
    } else {
      out[c] = store_float_color(sp.values[4 * static_cast<std::size_t>(i) + c], arith);
    }
  }
  for (int c = 0; c < 4; ++c)
    if (s.color_mask[c]) b.values[4 * p + c] = out[c];
}

}  // namespace

void run_fragment_ops_full(const FragmentOpsState& s, const FragmentTarget& t, const FragmentSpan& sp,
                           const FragmentBuffers& b) {
  const FragmentConstants k = fragment_constants(s, t);
  const bool fixed = t.arith == Arithmetic::Fixed;
  if (sp.count <= 0) return;
  check_span(sp, fixed);
  const bool has_stencil = t.stencil_bits > 0, has_depth = t.depth_bits > 0;
  const std::uint32_t M = k.color_max;
  for (int i = 0; i < sp.count; ++i) {
    const std::int64_t x = std::int64_t{sp.x0} + i, y = sp.y;
    // Pixel ownership: the window.
    if (x < 0 || y < 0 || x >= t.width || y >= t.height) continue;
    // Scissor test.
    if (s.scissor.enabled && !(x >= s.scissor.x && x < std::int64_t{s.scissor.x} + s.scissor.width &&
                               y >= s.scissor.y && y < std::int64_t{s.scissor.y} + s.scissor.height))
      continue;
    const std::size_t p = static_cast<std::size_t>(y) * static_cast<std::size_t>(t.width) + static_cast<std::size_t>(x);
    // Alpha test.
    if (s.alpha.enabled) {
      bool pass;
      if (fixed) pass = test_func<std::uint32_t>(s.alpha.func, sp.codes[4 * static_cast<std::size_t>(i) + 3], alpha_ref_code(s.alpha.ref, t.color_bits));
      else {
        double a = sp.values[4 * static_cast<std::size_t>(i) + 3];
        if (t.arith == Arithmetic::Float32) a = static_cast<float>(a);
        pass = test_func<double>(s.alpha.func, a, alpha_ref_value(s.alpha.ref, t.arith));
      }
      if (!pass) continue;
    }
    // Stencil test.
    const bool st = s.stencil.enabled && has_stencil;
    const std::uint32_t smax = k.stencil_max, ref = stencil_ref_clamped(s.stencil.ref, smax);
    const std::uint32_t vm = s.stencil.value_mask & smax, wm = s.stencil_writemask & smax;
    if (st) {
      const std::uint32_t old = b.stencil[p];
      if (!test_func<std::uint32_t>(s.stencil.func, ref & vm, old & vm)) {
        b.stencil[p] = static_cast<std::uint8_t>(stencil_write(s.stencil.sfail, old, ref, smax, wm));
        continue;
      }
    }
    // Depth test.
    if (s.depth.enabled && has_depth) {
      if (sp.depth.size() < static_cast<std::size_t>(sp.count))
        throw std::invalid_argument("fragment span: the depth test is enabled but the span carries no depth");
      const std::uint32_t z = sp.depth[static_cast<std::size_t>(i)];
      if (!test_func<std::uint32_t>(s.depth.func, z, b.depth[p])) {
        if (st) b.stencil[p] = static_cast<std::uint8_t>(stencil_write(s.stencil.dpfail, b.stencil[p], ref, smax, wm));
        continue;
      }
      if (s.depth_mask) b.depth[p] = z;
    }
    if (st) b.stencil[p] = static_cast<std::uint8_t>(stencil_write(s.stencil.dppass, b.stencil[p], ref, smax, wm));
    // Blending or logic op, dithering, masked write.
    if (fixed) {
      std::uint32_t sv[4], dv[4], kv[4], out[4];
      for (int q = 0; q < 4; ++q) {
        sv[q] = sp.codes[4 * static_cast<std::size_t>(i) + q];
        dv[q] = b.codes[4 * p + q];
        kv[q] = k.blend_color_code[q];
      }
      for (int c = 0; c < 4; ++c) {
        std::uint32_t r = sv[c];
        if (s.logic.enabled) r = logic_op(s.logic.op, sv[c], dv[c], M);
        else if (s.blend.enabled)
          r = blend_code(s.blend.equation, sv[c], blend_factor<std::uint32_t>(s.blend.src, c, sv, dv, kv, M), dv[c],
                         blend_factor<std::uint32_t>(s.blend.dst, c, sv, dv, kv, M), M);
        out[c] = dither_code(r, t.color_bits, t.color_bits);
      }
      for (int c = 0; c < 4; ++c)
        if (s.color_mask[c]) b.codes[4 * p + c] = static_cast<std::uint16_t>(out[c]);
    } else if (t.arith == Arithmetic::Float32) {
      full_color_float<float>(s, k, sp, b, i, p, t.arith);
    } else {
      full_color_float<double>(s, k, sp, b, i, p, t.arith);
    }
  }
}

// ---------------------------------------------------------------------------
// describe()

namespace {

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string hex(std::uint32_t v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%x", v);
  return buf;
}

// '@' stands for the channel group's label (RGB, A, ...).
std::string factor_text(GLenum f, int c) {
  switch (f) {
    case gl::ONE: return "";
    case gl::SRC_COLOR: return "@_s";
    case gl::ONE_MINUS_SRC_COLOR: return "(1 - @_s)";
    case gl::DST_COLOR: return "@_d";
    case gl::ONE_MINUS_DST_COLOR: return "(1 - @_d)";
    case gl::SRC_ALPHA: return "A_s";
    case gl::ONE_MINUS_SRC_ALPHA: return "(1 - A_s)";
    case gl::DST_ALPHA: return "A_d";
    case gl::ONE_MINUS_DST_ALPHA: return "(1 - A_d)";
    case gl::CONSTANT_COLOR: return "@_c";
    case gl::ONE_MINUS_CONSTANT_COLOR: return "(1 - @_c)";
    case gl::CONSTANT_ALPHA: return "A_c";
    case gl::ONE_MINUS_CONSTANT_ALPHA: return "(1 - A_c)";
    case gl::SRC_ALPHA_SATURATE: return c == 3 ? "" : "min(A_s, 1 - A_d)";
    default: return "0";
  }
}

std::string term_text(const char* value, GLenum f, int c) {
  const std::string ft = factor_text(f, c);
  return ft.empty() ? std::string(value) : std::string(value) + "*" + ft;
}

std::string channel_template(const FragmentPlanKey& key, int c) {
  const GLenum sf = key.blend_src, df = key.blend_dst;
  switch (key.channel[c]) {
    case ChannelOp::Keep: return "";
    case ChannelOp::Zero: return "0";
    case ChannelOp::Copy: return "@_s";
    case ChannelOp::SrcTerm: return term_text("@_s", sf, c);
    case ChannelOp::DstTerm: return term_text("@_d", df, c);
    case ChannelOp::Add: return "min(1, " + term_text("@_s", sf, c) + " + " + term_text("@_d", df, c) + ")";
    case ChannelOp::Sub: return "max(0, " + term_text("@_s", sf, c) + " - " + term_text("@_d", df, c) + ")";
    case ChannelOp::RevSub: return "max(0, " + term_text("@_d", df, c) + " - " + term_text("@_s", sf, c) + ")";
    case ChannelOp::Min: return "min(@_s, @_d)";
    case ChannelOp::Max: return "max(@_s, @_d)";
    case ChannelOp::Logic: {
      std::string e = logic_op_expression(key.logic_op);
      std::string out;
      for (char ch : e) {
        if (ch == 's') out += "@_s";
        else if (ch == 'd') out += "@_d";
        else out += ch;
      }
      return out + " (" + logic_op_name(key.logic_op) + ")";
    }
  }
  return "";
}

std::string substitute(const std::string& t, const std::string& label) {
  std::string out;
  for (char ch : t) {
    if (ch == '@') out += label;
    else out += ch;
  }
  return out;
}

}  // namespace

std::string describe(const FragmentPlan& plan, const FragmentConstants& k) {
  const FragmentPlanKey& key = plan.key;
  const bool fixed = key.arith == Arithmetic::Fixed;
  std::string out = "per-fragment operations (";
  out += fixed ? std::to_string(k.color_bits) + "-bit colour codes" : key.arith == Arithmetic::Float32 ? "binary32 colour" : "binary64 colour";
  out += "):\n";
  if (key.nothing) {
    out += "  skipped: no fragment can change the framebuffer (every fragment is discarded, or every write is masked)\n";
    return out;
  }
  const WriteRect& r = k.rect;
  if (r.x1 <= r.x0 || r.y1 <= r.y0) out += "  scissor: empty rectangle, no fragment survives\n";
  else out += "  scissor: x " + std::to_string(r.x0) + ".." + std::to_string(r.x1 - 1) + ", y " + std::to_string(r.y0) + ".." +
              std::to_string(r.y1 - 1) + "\n";
  if (key.alpha_func == 0) out += "  alpha test: skipped\n";
  else {
    out += std::string("  alpha test: pass if A_s ") + test_func_symbol(key.alpha_func) + " ";
    out += fixed ? std::to_string(k.alpha_ref_code) + "/" + std::to_string(k.color_max) + " (ref " + num(k.alpha_ref_value) + ")"
                 : num(k.alpha_ref_value);
    out += "\n";
  }
  if (!key.stencil) out += "  stencil test: skipped\n";
  else {
    out += "  stencil test: ";
    if (key.stencil_func == gl::ALWAYS) out += "always passes";
    else if (key.stencil_func == gl::NEVER) out += "never passes";
    else
      out += std::string("pass if (") + std::to_string(k.stencil_ref) + " & " + hex(k.stencil_value_mask) + ") " +
             test_func_symbol(key.stencil_func) + " (S & " + hex(k.stencil_value_mask) + ")";
    std::vector<std::string> ops;  // only the ops that can run
    if (key.stencil_func != gl::ALWAYS) ops.push_back(std::string("fail ") + stencil_op_name(key.sfail));
    if (key.stencil_func != gl::NEVER) {
      if (key.depth) ops.push_back(std::string("depth fail ") + stencil_op_name(key.dpfail));
      ops.push_back(std::string("pass ") + stencil_op_name(key.dppass));
    }
    out += "; ops:";
    for (std::size_t i = 0; i < ops.size(); ++i) out += (i ? ", " : " ") + ops[i];
    out += "; write mask " + hex(k.stencil_writemask) + "\n";
  }
  if (!key.depth) out += "  depth test: skipped\n";
  else out += std::string("  depth test: pass if z ") + test_func_symbol(key.depth_func) + " Z_d; " +
              (key.depth_write ? "writes z" : "no depth write (mask)") + "\n";
  if (!plan.write_color) out += "  colour: not written\n";
  else {
    // Group channels with the same expression: R, G and B always share one.
    std::vector<std::pair<std::string, std::string>> groups;  // label, template
    for (int c = 0; c < 4; ++c) {
      const std::string t = channel_template(key, c);
      if (t.empty()) continue;
      bool merged = false;
      for (auto& g : groups)
        if (g.second == t) { g.first += "RGBA"[c]; merged = true; }
      if (!merged) groups.push_back({std::string(1, "RGBA"[c]), t});
    }
    for (const auto& g : groups) out += "  colour: " + g.first + " = " + substitute(g.second, g.first) + "\n";
    std::string kept;
    for (int c = 0; c < 4; ++c)
      if (key.channel[c] == ChannelOp::Keep) kept += "RGBA"[c];
    if (!kept.empty()) out += "  colour: " + kept + " kept (masked, or the equation leaves the destination)\n";
    const bool uses_constant = (key.blend_src >= gl::CONSTANT_COLOR && key.blend_src <= gl::ONE_MINUS_CONSTANT_ALPHA) ||
                               (key.blend_dst >= gl::CONSTANT_COLOR && key.blend_dst <= gl::ONE_MINUS_CONSTANT_ALPHA);
    if (uses_constant) {
      out += "  blend colour: (" + num(k.blend_color_given[0]) + ", " + num(k.blend_color_given[1]) + ", " +
             num(k.blend_color_given[2]) + ", " + num(k.blend_color_given[3]) + ")";
      if (fixed)
        out += " as codes (" + std::to_string(k.blend_color_code[0]) + ", " + std::to_string(k.blend_color_code[1]) + ", " +
               std::to_string(k.blend_color_code[2]) + ", " + std::to_string(k.blend_color_code[3]) + ")";
      out += "\n";
    }
    out += std::string("  destination colour read: ") + (plan.read_dst_color ? "yes" : "no") + "\n";
    out += fixed ? "  rounding: exact, clamp to [0,1], round half up to " + std::to_string(k.color_bits) + " bits; dither: identity\n"
                 : "  rounding: none (clamp to [0,1] only); dither: identity\n";
  }
  return out;
}

}  // namespace ffsim

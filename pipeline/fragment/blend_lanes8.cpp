// The 8-bit colour stage on interleaved codes (blend_lanes8.h).
#include "pipeline/fragment/blend_lanes8.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "pipeline/fragment/fragment_plan.h"
#include "pipeline/gl/enums.h"

#ifdef __AVX2__
#include <immintrin.h>
#endif

namespace ffsim {

namespace {

// X of a factor X XOR inv (BlendLanes8): per lane, the source or destination
// code, the pixel's source or destination alpha, the constant colour's code, or
// SRC_ALPHA_SATURATE's min(A_s, M − A_d).
enum Select : std::uint8_t { kZero, kSrc, kDst, kSrcAlpha, kDstAlpha, kConstant, kSaturate };
constexpr int kSelects = 7;

struct FactorForm {
  Select x = kZero;
  bool inv = false;             // M − X
  bool constant_alpha = false;  // kConstant: the alpha code in every lane
};

// FixedKernel::factor's cases as X XOR inv.
FactorForm factor_form(GLenum f) {
  switch (f) {
    case gl::ONE: return {kZero, true};
    case gl::SRC_COLOR: return {kSrc};
    case gl::ONE_MINUS_SRC_COLOR: return {kSrc, true};
    case gl::DST_COLOR: return {kDst};
    case gl::ONE_MINUS_DST_COLOR: return {kDst, true};
    case gl::SRC_ALPHA: return {kSrcAlpha};
    case gl::ONE_MINUS_SRC_ALPHA: return {kSrcAlpha, true};
    case gl::DST_ALPHA: return {kDstAlpha};
    case gl::ONE_MINUS_DST_ALPHA: return {kDstAlpha, true};
    case gl::CONSTANT_COLOR: return {kConstant};
    case gl::ONE_MINUS_CONSTANT_COLOR: return {kConstant, true};
    case gl::CONSTANT_ALPHA: return {kConstant, false, true};
    case gl::ONE_MINUS_CONSTANT_ALPHA: return {kConstant, true, true};
    case gl::SRC_ALPHA_SATURATE: return {kSaturate};
    default: return {};  // ZERO, or 0: no channel uses the factor
  }
}

}  // namespace

BlendLanes8 blend_lanes8(const FragmentPlanKey& key) {
  BlendLanes8 b;
#ifdef __AVX2__
  b.usable = key.arith == Arithmetic::Fixed;
#endif
  constexpr std::uint16_t all = 0xFFFF, M = 0x00FF;
  const FactorForm sf = factor_form(key.blend_src), df = factor_form(key.blend_dst);
  b.src_select = sf.x;
  b.dst_select = df.x;
  b.src_constant_alpha = sf.constant_alpha;
  b.dst_constant_alpha = df.constant_alpha;
  for (int c = 0; c < 4; ++c) {
    b.src_inv[c] = sf.inv ? M : 0;
    b.dst_inv[c] = df.inv ? M : 0;
    // SRC_ALPHA_SATURATE is (f, f, f, 1): M for alpha (FixedKernel::factor).
    const bool saturate_alpha = c == 3 && key.blend_src == gl::SRC_ALPHA_SATURATE;
    auto src_term = [&] {
      if (saturate_alpha) b.src_one[c] = M;
      else b.src_use[c] = all;
    };
    switch (key.channel[c]) {
      case ChannelOp::Keep: continue;
      case ChannelOp::Logic: b.usable = false; continue;
      case ChannelOp::Zero: break;  // S = D = 0: finish(0) = 0
      case ChannelOp::Copy: b.src_one[c] = M; break;  // finish(255 s) = s
      case ChannelOp::SrcTerm: src_term(); break;
      case ChannelOp::DstTerm: b.dst_use[c] = all; break;
      case ChannelOp::Add: src_term(); b.dst_use[c] = all; break;
      case ChannelOp::Sub: src_term(); b.dst_use[c] = all; b.sub[c] = all; b.general = true; break;
      case ChannelOp::RevSub: src_term(); b.dst_use[c] = all; b.revsub[c] = all; b.general = true; break;
      case ChannelOp::Min: b.min[c] = all; b.general = true; break;
      case ChannelOp::Max: b.max[c] = all; b.general = true; break;
    }
    b.written[c] = all;
  }
  if (b.dst_select == kSaturate) b.usable = false;  // (a source factor only: never in a valid key)
  return b;
}

#ifdef __AVX2__
namespace {

__m256i lanes(const std::uint16_t (&v)[4]) {
  std::int64_t q;
  std::memcpy(&q, v, sizeof q);
  return _mm256_set1_epi64x(q);
}

// The pattern's vectors and the constant colour's, loaded once per call.
struct Lanes {
  __m256i written, src_inv, dst_inv, src_use, src_one, dst_use, sub, revsub, min, max, constant_src, constant_dst;
  Lanes(const BlendLanes8& b, const std::uint32_t* kc)
      : written(lanes(b.written)), src_inv(lanes(b.src_inv)), dst_inv(lanes(b.dst_inv)), src_use(lanes(b.src_use)),
        src_one(lanes(b.src_one)), dst_use(lanes(b.dst_use)), sub(lanes(b.sub)), revsub(lanes(b.revsub)),
        min(lanes(b.min)), max(lanes(b.max)), constant_src(constant(kc, b.src_constant_alpha)),
        constant_dst(constant(kc, b.dst_constant_alpha)) {}
  static __m256i constant(const std::uint32_t* kc, bool alpha) {
    std::uint16_t v[4];
    for (int c = 0; c < 4; ++c) v[c] = static_cast<std::uint16_t>(kc[alpha ? 3 : c]);
    return lanes(v);
  }
};

// Each pixel's alpha in its four lanes.
__m256i alpha_of(__m256i x) { return _mm256_shufflehi_epi16(_mm256_shufflelo_epi16(x, 0xFF), 0xFF); }

template <int kX>
__m256i select(__m256i s, __m256i d, __m256i constant) {
  if constexpr (kX == kSrc) return s;
  else if constexpr (kX == kDst) return d;
  else if constexpr (kX == kSrcAlpha) return alpha_of(s);
  else if constexpr (kX == kDstAlpha) return alpha_of(d);
  else if constexpr (kX == kConstant) return constant;
  else if constexpr (kX == kSaturate) return _mm256_min_epu16(alpha_of(s), _mm256_xor_si256(alpha_of(d), _mm256_set1_epi16(0xFF)));
  else return _mm256_setzero_si256();
}

// Four fragments' source codes s blended with their pixels' codes d; the
// written channels of the live fragments replaced (live: all ones per pixel).
template <int kS, int kD>
__m256i blend4(bool general, const Lanes& l, __m256i s, __m256i d, __m256i live) {
  const __m256i Sx = _mm256_xor_si256(select<kS>(s, d, l.constant_src), l.src_inv);  // M − x = x XOR 255
  const __m256i S = _mm256_or_si256(_mm256_and_si256(Sx, l.src_use), l.src_one);
  const __m256i D = _mm256_and_si256(_mm256_xor_si256(select<kD>(s, d, l.constant_dst), l.dst_inv), l.dst_use);
  const __m256i P = _mm256_mullo_epi16(s, S), Q = _mm256_mullo_epi16(d, D);  // ≤ 65025: exact in 16 bits
  // s·S + d·D clamped to [0, M²] (saturating at 65535 ≥ M², then the clamp), or
  // the differences clamped at 0.
  __m256i v = _mm256_min_epu16(_mm256_adds_epu16(P, Q), _mm256_set1_epi16(static_cast<std::int16_t>(65025)));
  if (general) {
    v = _mm256_blendv_epi8(v, _mm256_subs_epu16(P, Q), l.sub);
    v = _mm256_blendv_epi8(v, _mm256_subs_epu16(Q, P), l.revsub);
  }
  // FixedKernel<255>::finish: y = v + 127, (y + 1 + (y >> 8)) >> 8; y ≤ 65152, the sum ≤ 65407.
  const __m256i y = _mm256_add_epi16(v, _mm256_set1_epi16(127));
  __m256i out = _mm256_srli_epi16(_mm256_add_epi16(_mm256_add_epi16(y, _mm256_set1_epi16(1)), _mm256_srli_epi16(y, 8)), 8);
  if (general) {
    out = _mm256_blendv_epi8(out, _mm256_min_epu16(s, d), l.min);
    out = _mm256_blendv_epi8(out, _mm256_max_epu16(s, d), l.max);
  }
  return _mm256_blendv_epi8(d, out, _mm256_and_si256(l.written, live));
}

// alive[0..3] (0 or 1) as all ones per live pixel's 64 bits.
__m256i live4(const std::uint8_t* alive) {
  std::int32_t a4;
  std::memcpy(&a4, alive, sizeof a4);
  return _mm256_cmpgt_epi64(_mm256_cvtepu8_epi64(_mm_cvtsi32_si128(a4)), _mm256_setzero_si256());
}

__m256i load(const std::uint16_t* p) { return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)); }

constexpr int kMaxChunk = 256;  // fragments whose destination codes are gathered ahead (fragment_plan.cpp's chunk)

// Where the fragments land: pixel first + j, or pixel[j] when listed.
struct Target {
  std::uint16_t* fb;
  const std::uint32_t* pixel;  // null: a row from `first`
  std::size_t first;
};

template <int kS, int kD>
void run(const BlendLanes8& b, const Lanes& l, const std::uint16_t* in, Target t, int n, const std::uint8_t* alive) {
  const bool general = b.general;
  int j = 0;
  if (!t.pixel) {
    std::uint16_t* row = t.fb + 4 * t.first;
    for (; j + 4 <= n; j += 4) {
      const __m256i r = blend4<kS, kD>(general, l, load(in + 4 * j), load(row + 4 * j), live4(alive + j));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(row + 4 * j), r);
    }
  } else {
    const auto* base = reinterpret_cast<const long long*>(t.fb);
    auto put = [fb = t.fb](std::uint32_t p, __m128i two, bool high) {  // one pixel's 64 bits of `two`
      _mm_storel_epi64(reinterpret_cast<__m128i*>(fb + 4 * static_cast<std::size_t>(p)),
                       high ? _mm_unpackhi_epi64(two, two) : two);
    };
    // The destination codes first, in a loop of gathers alone: the pixels' lines
    // are requested together (computing between the gathers left them waiting one
    // at a time: 1.1x the time of the terrain's frame, docs/performance.md 22.1).
    // Pixel indices are below 2^26 (Framebuffer's limit): 32-bit gather offsets.
    alignas(32) std::uint16_t dst[4 * kMaxChunk];
    const int n4 = std::min(n, kMaxChunk) & ~3;
    for (int i = 0; i < n4; i += 4) {
      const __m128i idx = _mm_loadu_si128(reinterpret_cast<const __m128i*>(t.pixel + i));
      _mm256_store_si256(reinterpret_cast<__m256i*>(dst + 4 * i), _mm256_i32gather_epi64(base, idx, 8));
    }
    for (; j + 4 <= n; j += 4) {
      const __m256i d = j < n4 ? _mm256_load_si256(reinterpret_cast<const __m256i*>(dst + 4 * j))
                               : _mm256_i32gather_epi64(base, _mm_loadu_si128(reinterpret_cast<const __m128i*>(t.pixel + j)), 8);
      const __m256i r = blend4<kS, kD>(general, l, load(in + 4 * j), d, live4(alive + j));
      const __m128i lo = _mm256_castsi256_si128(r), hi = _mm256_extracti128_si256(r, 1);
      put(t.pixel[j], lo, false);
      put(t.pixel[j + 1], lo, true);
      put(t.pixel[j + 2], hi, false);
      put(t.pixel[j + 3], hi, true);
    }
  }
  if (const int m = n - j; m > 0) {  // the last one to three fragments through a padded copy
    auto at = [&](int i) { return t.fb + 4 * (t.pixel ? t.pixel[j + i] : t.first + static_cast<std::size_t>(j + i)); };
    std::uint16_t s[16] = {}, d[16] = {};
    std::uint8_t a[4] = {};
    std::memcpy(s, in + 4 * j, 8 * static_cast<std::size_t>(m));
    for (int i = 0; i < m; ++i) std::memcpy(d + 4 * i, at(i), 8);
    std::memcpy(a, alive + j, static_cast<std::size_t>(m));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(d), blend4<kS, kD>(general, l, load(s), load(d), live4(a)));
    for (int i = 0; i < m; ++i) std::memcpy(at(i), d + 4 * i, 8);
  }
}

// run<kS, kD> for every pair of selections: the factors' choice made once per call.
using RunFn = void (*)(const BlendLanes8&, const Lanes&, const std::uint16_t*, Target, int, const std::uint8_t*);
template <std::size_t... I>
constexpr std::array<RunFn, sizeof...(I)> run_table(std::index_sequence<I...>) {
  return {&run<static_cast<int>(I / kSelects), static_cast<int>(I % kSelects)>...};
}
constexpr auto kRun = run_table(std::make_index_sequence<kSelects * kSelects>{});

void run_any(const BlendLanes8& b, const std::uint32_t* kc, const std::uint16_t* in, Target t, int n,
             const std::uint8_t* alive) {
  if (!b.usable) throw std::logic_error("blend_lanes8: the plan's colour stage is not of this kind");
  kRun[static_cast<std::size_t>(b.src_select * kSelects + b.dst_select)](b, Lanes(b, kc), in, t, n, alive);
}

}  // namespace

void blend_lanes8_row(const BlendLanes8& b, const std::uint32_t* kc, const std::uint16_t* in, std::uint16_t* fb,
                      std::size_t first, int n, const std::uint8_t* alive) {
  run_any(b, kc, in, {fb, nullptr, first}, n, alive);
}

void blend_lanes8_list(const BlendLanes8& b, const std::uint32_t* kc, const std::uint16_t* in, std::uint16_t* fb,
                       const std::uint32_t* pixel, int n, const std::uint8_t* alive) {
  run_any(b, kc, in, {fb, pixel, 0}, n, alive);
}
#else
// Without AVX2 blend_lanes8 is never usable and FixedKernel computes every chunk.
void blend_lanes8_row(const BlendLanes8&, const std::uint32_t*, const std::uint16_t*, std::uint16_t*, std::size_t, int,
                      const std::uint8_t*) {
  throw std::logic_error("blend_lanes8_row: built without AVX2 (BlendLanes8::usable is false)");
}
void blend_lanes8_list(const BlendLanes8&, const std::uint32_t*, const std::uint16_t*, std::uint16_t*,
                       const std::uint32_t*, int, const std::uint8_t*) {
  throw std::logic_error("blend_lanes8_list: built without AVX2 (BlendLanes8::usable is false)");
}
#endif

}  // namespace ffsim

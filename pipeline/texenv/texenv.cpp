#include "pipeline/texenv/texenv.h"

#ifdef __AVX2__
#include <immintrin.h>
#endif

#include <algorithm>
#include <type_traits>

#include "pipeline/number/unorm.h"

namespace ffsim {

namespace {

__extension__ typedef __int128 i128;

i128 iabs(i128 v) { return v < 0 ? -v : v; }
i128 gcd128(i128 a, i128 b) {
  a = iabs(a);
  b = iabs(b);
  while (b != 0) {
    const i128 r = a % b;
    a = b;
    b = r;
  }
  return a;
}

// An exact rational num/den (den > 0), reduced after every operation. The
// texture environment's operands are codes k/(2^n - 1) with n <= 16, and no
// formula multiplies more than three of them or adds more than three products,
// so numerators and denominators stay far below 2^127.
struct Rat {
  i128 n = 0, d = 1;
  Rat() = default;
  Rat(i128 num, i128 den = 1) : n(num), d(den) {
    const i128 g = gcd128(n, d);
    if (g > 1) {
      n /= g;
      d /= g;
    }
  }
  friend Rat operator+(Rat a, Rat b) { return a.d == b.d ? Rat(a.n + b.n, a.d) : Rat(a.n * b.d + b.n * a.d, a.d * b.d); }
  friend Rat operator-(Rat a, Rat b) { return a.d == b.d ? Rat(a.n - b.n, a.d) : Rat(a.n * b.d - b.n * a.d, a.d * b.d); }
  friend Rat operator*(Rat a, Rat b) { return Rat(a.n * b.n, a.d * b.d); }
  friend bool operator<(Rat a, Rat b) { return a.n * b.d < b.n * a.d; }
};

template <class T> T half();
template <> Rat half<Rat>() { return Rat(1, 2); }
template <> double half<double>() { return 0.5; }

template <class T>
T clamp01(T v) {
  if (v < T(0)) return T(0);
  if (T(1) < v) return T(1);
  return v;
}
template <class T>
T min1(T v) {
  return T(1) < v ? T(1) : v;
}

template <class T>
using V4 = std::array<T, 4>;

template <class T>
T scale_of(double s) {
  return T(static_cast<int>(s));  // RGB_SCALE / ALPHA_SCALE are 1, 2 or 4 (validated by glTexEnv)
}

bool has_color(BaseFormat b) { return b != BaseFormat::Alpha; }
bool has_alpha(BaseFormat b) {
  return b == BaseFormat::Alpha || b == BaseFormat::LuminanceAlpha || b == BaseFormat::Intensity ||
         b == BaseFormat::RGBA;
}

// GL121 Table 3.18 / 3.19 and ARB_texture_env_add.
template <class T>
V4<T> classic(const TexEnvState& env, BaseFormat base, const V4<T>& cf, const V4<T>& ct, const V4<T>& cc) {
  V4<T> out = cf;
  const bool hc = has_color(base), ha = has_alpha(base);
  switch (env.mode) {
    case gl::REPLACE:
      if (hc) for (int c = 0; c < 3; ++c) out[c] = ct[c];
      if (ha) out[3] = ct[3];
      break;
    case gl::MODULATE:
      if (hc) for (int c = 0; c < 3; ++c) out[c] = cf[c] * ct[c];
      if (ha) out[3] = cf[3] * ct[3];
      break;
    case gl::DECAL:
      if (base == BaseFormat::RGB) for (int c = 0; c < 3; ++c) out[c] = ct[c];
      if (base == BaseFormat::RGBA) for (int c = 0; c < 3; ++c) out[c] = cf[c] * (T(1) - ct[3]) + ct[c] * ct[3];
      break;
    case gl::BLEND:
      if (hc) for (int c = 0; c < 3; ++c) out[c] = cf[c] * (T(1) - ct[c]) + cc[c] * ct[c];
      if (base == BaseFormat::Intensity) out[3] = cf[3] * (T(1) - ct[3]) + cc[3] * ct[3];
      else if (ha) out[3] = cf[3] * ct[3];
      break;
    case gl::ADD:
      if (hc) for (int c = 0; c < 3; ++c) out[c] = min1(cf[c] + ct[c]);
      if (base == BaseFormat::Intensity) out[3] = min1(cf[3] + ct[3]);
      else if (ha) out[3] = cf[3] * ct[3];
      break;
    default: break;
  }
  return out;
}

template <class T>
const V4<T>& source(GLenum src, const V4<T>& cf, const V4<T>& prim, const V4<T>& ct, const V4<T>& cc) {
  switch (src) {
    case gl::TEXTURE: return ct;
    case gl::CONSTANT: return cc;
    case gl::PRIMARY_COLOR: return prim;
    default: return cf;  // PREVIOUS
  }
}

template <class T>
T operand(GLenum op, const V4<T>& v, int c) {
  switch (op) {
    case gl::ONE_MINUS_SRC_COLOR: return T(1) - v[c];
    case gl::SRC_ALPHA: return v[3];
    case gl::ONE_MINUS_SRC_ALPHA: return T(1) - v[3];
    default: return v[c];  // SRC_COLOR
  }
}

template <class T>
T combine_fn(GLenum f, T a0, T a1, T a2) {
  switch (f) {
    case gl::REPLACE: return a0;
    case gl::ADD: return a0 + a1;
    case gl::ADD_SIGNED: return a0 + a1 - half<T>();
    case gl::INTERPOLATE: return a0 * a2 + a1 * (T(1) - a2);
    case gl::SUBTRACT: return a0 - a1;
    default: return a0 * a1;  // MODULATE
  }
}

// ARB/EXT_texture_env_combine and _dot3: function, then ×scale, then clamp to [0,1].
template <class T>
V4<T> combine(const TexEnvState& env, const V4<T>& cf, const V4<T>& prim, const V4<T>& ct, const V4<T>& cc) {
  V4<T> out{};
  std::array<const V4<T>*, 3> srgb{}, sa{};
  for (int i = 0; i < 3; ++i) {
    srgb[i] = &source(env.source_rgb[i], cf, prim, ct, cc);
    sa[i] = &source(env.source_alpha[i], cf, prim, ct, cc);
  }
  const GLenum frgb = env.combine_rgb;
  const bool dot3_ext = frgb == gl::DOT3_RGB_EXT || frgb == gl::DOT3_RGBA_EXT;
  const bool dot3_rgba = frgb == gl::DOT3_RGBA || frgb == gl::DOT3_RGBA_EXT;
  if (is_dot3(frgb)) {
    // 4·Σ (a0 − ½)(a1 − ½) over R, G, B (TD3 / ETD3).
    T d = T(0);
    for (int c = 0; c < 3; ++c)
      d = d + (operand(env.operand_rgb[0], *srgb[0], c) - half<T>()) * (operand(env.operand_rgb[1], *srgb[1], c) - half<T>());
    d = d * T(4);
    const T rgb = clamp01(dot3_ext ? d : d * scale_of<T>(env.rgb_scale));
    for (int c = 0; c < 3; ++c) out[c] = rgb;
    // DOT3_RGBA: the dot product also goes to alpha, COMBINE_ALPHA ignored; ARB
    // scales it by ALPHA_SCALE (GL 1.3 §3.8.13), EXT applies no scale.
    if (dot3_rgba) out[3] = clamp01(dot3_ext ? d : d * scale_of<T>(env.alpha_scale));
  } else {
    const T s = scale_of<T>(env.rgb_scale);
    for (int c = 0; c < 3; ++c) {
      const T a0 = operand(env.operand_rgb[0], *srgb[0], c);
      const T a1 = operand(env.operand_rgb[1], *srgb[1], c);
      const T a2 = operand(env.operand_rgb[2], *srgb[2], c);
      out[c] = clamp01(combine_fn(frgb, a0, a1, a2) * s);
    }
  }
  if (!dot3_rgba) {
    const T a0 = operand(env.operand_alpha[0], *sa[0], 3);
    const T a1 = operand(env.operand_alpha[1], *sa[1], 3);
    const T a2 = operand(env.operand_alpha[2], *sa[2], 3);
    out[3] = clamp01(combine_fn(env.combine_alpha, a0, a1, a2) * scale_of<T>(env.alpha_scale));
  }
  return out;
}

template <class T>
V4<T> evaluate(const TexEnvState& env, BaseFormat base, const V4<T>& cf, const V4<T>& prim, const V4<T>& ct,
               const V4<T>& cc) {
  return env.mode == gl::COMBINE ? combine(env, cf, prim, ct, cc) : classic(env, base, cf, ct, cc);
}

V4<Rat> rats(const std::array<std::uint32_t, 4>& k, int bits) {
  const i128 m = unorm_max(bits);
  return {Rat(k[0], m), Rat(k[1], m), Rat(k[2], m), Rat(k[3], m)};
}

}  // namespace

int combine_arg_count(GLenum f) {
  if (f == gl::REPLACE) return 1;
  if (f == gl::INTERPOLATE) return 3;
  return 2;
}

bool is_dot3(GLenum f) {
  return f == gl::DOT3_RGB || f == gl::DOT3_RGBA || f == gl::DOT3_RGB_EXT || f == gl::DOT3_RGBA_EXT;
}

TexEnvReads texenv_reads(const TexEnvState& env, BaseFormat base) {
  TexEnvReads r;
  if (env.mode != gl::COMBINE) {
    r.texture = true;
    // Only REPLACE with a format that supplies both colour and alpha ignores Cf.
    r.previous = !(env.mode == gl::REPLACE && has_color(base) && has_alpha(base));
    if (env.mode == gl::DECAL && base != BaseFormat::RGB && base != BaseFormat::RGBA) r.texture = false;
    return r;
  }
  auto note = [&](GLenum src) {
    if (src == gl::TEXTURE) r.texture = true;
    if (src == gl::PREVIOUS) r.previous = true;
    if (src == gl::PRIMARY_COLOR) r.primary = true;
  };
  const int nrgb = is_dot3(env.combine_rgb) ? 2 : combine_arg_count(env.combine_rgb);
  for (int i = 0; i < nrgb; ++i) note(env.source_rgb[i]);
  if (env.combine_rgb != gl::DOT3_RGBA && env.combine_rgb != gl::DOT3_RGBA_EXT)
    for (int i = 0; i < combine_arg_count(env.combine_alpha); ++i) note(env.source_alpha[i]);
  return r;
}

Rgba rgba_from_values(const std::array<double, 4>& v, const ColorFormat& fmt) {
  Rgba out;
  for (int c = 0; c < 4; ++c) {
    const double x = std::clamp(v[c], 0.0, 1.0);
    if (fmt.arith == Arithmetic::Fixed) out.code[c] = unorm_from_double(v[c], fmt.bits);
    else if (fmt.arith == Arithmetic::Float32) out.value[c] = static_cast<double>(static_cast<float>(x));
    else out.value[c] = x;
  }
  return out;
}

Rgba texture_environment(const TexEnvState& env, const Rgba& previous, const Rgba& primary, const Texel& texel,
                         const ColorFormat& fmt) {
  Rgba out;
  if (fmt.fixed()) {
    std::array<std::uint32_t, 4> cc{};
    for (int c = 0; c < 4; ++c) cc[c] = unorm_from_double(env.color[c], fmt.bits);
    const V4<Rat> r = evaluate<Rat>(env, texel.base, rats(previous.code, fmt.bits), rats(primary.code, fmt.bits),
                                    rats(texel.code, texel.bits), rats(cc, fmt.bits));
    const i128 m = unorm_max(fmt.bits);
    for (int c = 0; c < 4; ++c) {
      const Rat v = clamp01(r[c]);
      out.code[c] = static_cast<std::uint32_t>((2 * v.n * m + v.d) / (2 * v.d));  // round half up, once
    }
    return out;
  }
  const V4<double> r = evaluate<double>(env, texel.base, previous.value, primary.value, texel.value, env.color);
  for (int c = 0; c < 4; ++c) {
    const double v = clamp01(r[c]);
    out.value[c] = fmt.arith == Arithmetic::Float32 ? static_cast<double>(static_cast<float>(v)) : v;
  }
  return out;
}

namespace {

enum class SpanOp : std::uint8_t { Keep, Texel, Mul, Decal, Blend, AddSat };

template <std::uint32_t kM>
void env_span_channels(const std::array<SpanOp, 4>& op, const std::array<std::uint32_t, 4>& cc, std::uint32_t m_rt,
                       const std::uint16_t* prev, const std::uint16_t* tex, int n, std::uint16_t* out) {
  using U = std::conditional_t<kM == 255, std::uint32_t, std::uint64_t>;
  const U m = kM ? kM : m_rt;
  // v = x / m^2 exactly; rounded half up once to the colour width: floor(v·m + 1/2).
  auto round2 = [m](U x) { return static_cast<std::uint16_t>((2 * x + m) / (2 * m)); };
  // One operation on all four channels that reads no per-channel constant: one
  // loop over the 4n interleaved codes (the same numbers, channel by channel).
  if (op[0] == op[1] && op[1] == op[2] && op[2] == op[3]) {
    const int n4 = 4 * n;
    switch (op[0]) {
      case SpanOp::Keep:
        if (out != prev) std::copy_n(prev, n4, out);
        return;
      case SpanOp::Texel: std::copy_n(tex, n4, out); return;
      case SpanOp::Mul:
        for (int i = 0; i < n4; ++i) out[i] = round2(U{prev[i]} * tex[i]);
        return;
      case SpanOp::AddSat:
        for (int i = 0; i < n4; ++i) out[i] = static_cast<std::uint16_t>(std::min<U>(U{prev[i]} + tex[i], m));
        return;
      default: break;  // Decal and Blend read alpha or the constant: per channel
    }
  }
  for (int c = 0; c < 4; ++c) {
    const U k = cc[c];
    switch (op[c]) {
      case SpanOp::Keep:
        if (out != prev)
          for (int f = 0; f < n; ++f) out[4 * f + c] = prev[4 * f + c];
        break;
      case SpanOp::Texel:
        for (int f = 0; f < n; ++f) out[4 * f + c] = tex[4 * f + c];
        break;
      case SpanOp::Mul:  // Cf·Ct
        for (int f = 0; f < n; ++f) out[4 * f + c] = round2(U{prev[4 * f + c]} * tex[4 * f + c]);
        break;
      case SpanOp::Decal:  // Cf·(1 − At) + Ct·At
        for (int f = 0; f < n; ++f) {
          const U a = tex[4 * f + 3];
          out[4 * f + c] = round2(U{prev[4 * f + c]} * (m - a) + U{tex[4 * f + c]} * a);
        }
        break;
      case SpanOp::Blend:  // Cf·(1 − Ct) + Cc·Ct
        for (int f = 0; f < n; ++f) {
          const U t = tex[4 * f + c];
          out[4 * f + c] = round2(U{prev[4 * f + c]} * (m - t) + k * t);
        }
        break;
      case SpanOp::AddSat:  // min(1, Cf + Ct), exact on codes of one width
        for (int f = 0; f < n; ++f) out[4 * f + c] = static_cast<std::uint16_t>(std::min<U>(U{prev[4 * f + c]} + tex[4 * f + c], m));
        break;
    }
  }
}

}  // namespace

namespace {

// COMBINE on codes of one width m (combine() above on k/m operands). A function
// value is N/D with D = m (REPLACE, ADD, SUBTRACT), 2m (ADD_SIGNED) or m^2
// (MODULATE, INTERPOLATE, DOT3); after × scale it is clamped to [0, 1] and
// rounded half up: code = floor(N·m/D + 1/2).
// kM: m when fixed at compile time (255: every division below is by a constant,
// which the compiler turns into a multiply), 0: m at run time.
template <std::int64_t kM>
struct CombineInt {
  std::int64_t m_rt;
  std::int64_t max() const { return kM ? kM : m_rt; }
  std::int64_t operand(GLenum op, const std::uint16_t* v, int c) const {
    switch (op) {
      case gl::ONE_MINUS_SRC_COLOR: return max() - v[c];
      case gl::SRC_ALPHA: return v[3];
      case gl::ONE_MINUS_SRC_ALPHA: return max() - v[3];
      default: return v[c];  // SRC_COLOR
    }
  }
  // clamp01(N/D) rounded to a code, for D in {m, 2m, m^2}.
  std::uint16_t finish(std::int64_t N, std::int64_t D) const {
    const std::int64_t m = max();
    if (N <= 0) return 0;
    if (N >= D) return static_cast<std::uint16_t>(m);
    return static_cast<std::uint16_t>((2 * N * m + D) / (2 * D));
  }
  std::uint16_t function(GLenum f, std::int64_t a0, std::int64_t a1, std::int64_t a2, std::int64_t s) const {
    const std::int64_t m = max();
    switch (f) {
      case gl::REPLACE: return finish(s * a0, m);
      case gl::ADD: return finish(s * (a0 + a1), m);
      case gl::ADD_SIGNED: return finish(s * (2 * a0 + 2 * a1 - m), 2 * m);
      case gl::INTERPOLATE: return finish(s * (a0 * a2 + a1 * (m - a2)), m * m);
      case gl::SUBTRACT: return finish(s * (a0 - a1), m);
      default: return finish(s * a0 * a1, m * m);  // MODULATE
    }
  }
};

// DOT3_RGB(A)(_EXT) with 8-bit codes (m = 255), the alpha either the dot product
// (DOT3_RGBA) or REPLACE: combine_span_fixed's numbers without its per-fragment
// switches and branches. Sources and operands are chosen once (a source is a
// pointer and a stride: 4 codes per fragment, 0 for the constant colour), and
// finish(N, m²) is computed branch free:
//   floor((2·clamp(N, 0, m²)·m + m²) / 2m²)
// gives 0 for N <= 0 (m²/2m² < 1), N's rounding for 0 < N < m², and m for
// N >= m² (floor(m + 1/2) = m); finish(N, m) of REPLACE is min(N, m) for
// N >= 0 ((2Nm + m)/2m = N + 1/2). Every value stays below 2^31.
// Returns false (nothing written) for any other combination.
bool combine_dot3_span_8(const TexEnvState& env, const std::uint16_t* previous, const std::uint16_t* primary,
                         const std::uint16_t* texel, int n, std::uint16_t* out) {
  constexpr std::int32_t m = 255, m2 = m * m;
  if (!is_dot3(env.combine_rgb)) return false;
  const bool ext = env.combine_rgb == gl::DOT3_RGB_EXT || env.combine_rgb == gl::DOT3_RGBA_EXT;
  const bool rgba = env.combine_rgb == gl::DOT3_RGBA || env.combine_rgb == gl::DOT3_RGBA_EXT;
  if (!rgba && env.combine_alpha != gl::REPLACE) return false;
  std::uint16_t cc[4];
  for (int c = 0; c < 4; ++c) cc[c] = static_cast<std::uint16_t>(unorm_from_double(env.color[c], 8));
  struct Source {
    const std::uint16_t* base;
    std::size_t stride;
  };
  auto source = [&](GLenum which) -> Source {
    switch (which) {
      case gl::TEXTURE: return {texel, 4};
      case gl::CONSTANT: return {cc, 0};
      case gl::PRIMARY_COLOR: return {primary, 4};
      default: return {previous, 4};  // PREVIOUS (`out` may alias it: each fragment is read before it is written)
    }
  };
  // Operand: the component (c, or alpha) and whether it is inverted (m − v).
  auto alpha_of = [](GLenum op) { return op == gl::SRC_ALPHA || op == gl::ONE_MINUS_SRC_ALPHA; };
  auto inverted = [](GLenum op) { return op == gl::ONE_MINUS_SRC_COLOR || op == gl::ONE_MINUS_SRC_ALPHA; };
  const Source s0 = source(env.source_rgb[0]), s1 = source(env.source_rgb[1]), sa = source(env.source_alpha[0]);
  const bool a0 = alpha_of(env.operand_rgb[0]), a1 = alpha_of(env.operand_rgb[1]);
  const std::int32_t i0 = inverted(env.operand_rgb[0]) ? 1 : 0, i1 = inverted(env.operand_rgb[1]) ? 1 : 0;
  const std::int32_t ia = inverted(env.operand_alpha[0]) ? 1 : 0;  // (the alpha component either way)
  const std::int32_t srgb = static_cast<std::int32_t>(env.rgb_scale), salpha = static_cast<std::int32_t>(env.alpha_scale);
  auto operand = [m](std::int32_t v, std::int32_t inv) { return inv ? m - v : v; };
  auto finish_m2 = [](std::int32_t N) {
    // N clamped to [0, m²] first: the same codes (N <= 0 gives 0; N >= m² gives
    // floor((2m³ + m²) / 2m²) = floor(m + 1/2) = m), and the division by the
    // constant 2m² stays a multiplication (GCC had emitted a div instruction here).
    // 2·c·m + m² <= 2m³ + m² < 2^26: 32-bit lanes, which GCC vectorises.
    const auto c = static_cast<std::uint32_t>(N < 0 ? 0 : N > m2 ? m2 : N);
    constexpr std::uint32_t kTwoM2 = 2 * static_cast<std::uint32_t>(m2);
    return static_cast<std::uint16_t>((2 * c * m + m2) / kTwoM2);
  };
  // One argument the constant colour (a light vector, as in the paper's bump
  // mapping): its three factors (2k − m) once, the other argument from the span.
  const bool const1 = s1.stride == 0, const0 = s0.stride == 0 && !const1;
  const Source sv = const0 ? s1 : s0;  // the argument that varies (or s0)
  const bool av = const0 ? a1 : a0;
  const std::int32_t iv = const0 ? i1 : i0;
  std::int32_t K[3] = {0, 0, 0};
  if (const0 || const1)
    for (int c = 0; c < 3; ++c)
      K[c] = const0 ? 2 * operand(s0.base[a0 ? 3 : c], i0) - m : 2 * operand(s1.base[a1 ? 3 : c], i1) - m;
  // 2·operand(v) − m = ±(2v − m): an inverted operand (m − v) only negates its
  // factor, so the two inversions are one sign on the sum.
  const std::int32_t sign = i0 != i1 ? -1 : 1;
  const std::int32_t scale_rgb = ext ? 1 : srgb, scale_alpha = ext ? 1 : salpha;
  const auto alpha_const =  // (a span source's base is not read here: n may be 0)
      sa.stride == 0 ? static_cast<std::uint16_t>(std::min(salpha * operand(sa.base[3], ia), m)) : std::uint16_t{0};
  // Blocks of fragments: first every read (the sums, and the REPLACE alpha), then
  // every write, whole pixels (`out` may alias a source, PREVIOUS: a block's
  // fragments are all read before any is written, and later blocks read only
  // later fragments). Each loop is free of aliasing, so each vectorises.
  constexpr int kBlock = 256;
  std::int32_t dot[kBlock];
  std::uint16_t alpha[kBlock];
  for (int f0 = 0; f0 < n; f0 += kBlock) {
    const int nb = std::min(kBlock, n - f0);
    const auto at = [f0](const Source& src) { return src.base + src.stride * static_cast<std::size_t>(f0); };
    if (!const0 && !const1 && !a0 && !a1 && s0.stride == 4 && s1.stride == 4) {
      // Both arguments vary, colour operands (the paper's bump map against the
      // interpolated light vector).
      const std::uint16_t* x = at(s0);
      const std::uint16_t* y = at(s1);
      int i = 0;
#ifdef __AVX2__
      // Eight fragments at a time: 2k − m of each code in int16 lanes (|2k − m|
      // <= 255), the alpha factors of y zeroed, one pmaddwd giving per fragment
      // (r·r' + g·g', b·b' + 0), the two halves summed in each 64-bit lane, and
      // the low halves gathered: the same integers as the loop below.
      {
        const __m256i vm = _mm256_set1_epi16(m), rgb = _mm256_set1_epi64x(0x0000FFFFFFFFFFFFll);
        const __m256i low = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7), vsign = _mm256_set1_epi32(sign);
        auto ld = [](const std::uint16_t* p) { return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)); };
        auto four = [&](int j) {  // fragments j .. j + 3: their sums in the low halves of the 64-bit lanes
          const __m256i X = ld(x + 4 * j), Y = ld(y + 4 * j);
          const __m256i u = _mm256_sub_epi16(_mm256_add_epi16(X, X), vm);
          const __m256i v = _mm256_and_si256(_mm256_sub_epi16(_mm256_add_epi16(Y, Y), vm), rgb);
          const __m256i p = _mm256_madd_epi16(u, v);
          return _mm256_add_epi32(p, _mm256_srli_epi64(p, 32));
        };
        for (; i + 8 <= nb; i += 8) {
          const __m256i lo = _mm256_permutevar8x32_epi32(four(i), low), hi = _mm256_permutevar8x32_epi32(four(i + 4), low);
          const __m256i d = _mm256_permute2x128_si256(lo, hi, 0x20);  // fragments i .. i + 7
          _mm256_storeu_si256(reinterpret_cast<__m256i*>(dot + i), _mm256_mullo_epi32(d, vsign));
        }
      }
#endif
      for (; i < nb; ++i) {
        const std::uint16_t* xi = x + 4 * i;
        const std::uint16_t* yi = y + 4 * i;
        dot[i] = sign * ((2 * xi[0] - m) * (2 * yi[0] - m) + (2 * xi[1] - m) * (2 * yi[1] - m) +
                         (2 * xi[2] - m) * (2 * yi[2] - m));
      }
    } else if (const0 || const1) {  // (the same products, the constant side precomputed)
      const std::uint16_t* v = at(sv);
      for (int i = 0; i < nb; ++i) {
        const std::uint16_t* w = v + sv.stride * static_cast<std::size_t>(i);
        std::int32_t d = 0;
        for (int c = 0; c < 3; ++c) d += (2 * operand(w[av ? 3 : c], iv) - m) * K[c];
        dot[i] = d;
      }
    } else {
      const std::uint16_t* x = at(s0);
      const std::uint16_t* y = at(s1);
      for (int i = 0; i < nb; ++i) {
        const std::uint16_t* xi = x + s0.stride * static_cast<std::size_t>(i);
        const std::uint16_t* yi = y + s1.stride * static_cast<std::size_t>(i);
        std::int32_t d = 0;  // Σ (2k0 − m)(2k1 − m), |d| <= 3m²
        for (int c = 0; c < 3; ++c)
          d += (2 * operand(xi[a0 ? 3 : c], i0) - m) * (2 * operand(yi[a1 ? 3 : c], i1) - m);
        dot[i] = d;
      }
    }
    if (rgba) {
      for (int i = 0; i < nb; ++i) alpha[i] = finish_m2(dot[i] * scale_alpha);
    } else if (sa.stride == 0) {
      std::fill_n(alpha, nb, alpha_const);
    } else {  // REPLACE: finish(s·a, m) = min(s·a, m) for s·a >= 0
      const std::uint16_t* a = at(sa);
      for (int i = 0; i < nb; ++i) alpha[i] = static_cast<std::uint16_t>(std::min(salpha * operand(a[4 * i + 3], ia), m));
    }
    std::uint16_t* o = out + 4 * static_cast<std::size_t>(f0);
    int i = 0;
#ifdef __AVX2__
    // Eight fragments at a time: finish_m2 as floor((2c + m) / 2m), the same
    // quotient ((2cm + m²) / 2m² with m divided out), c = clamp(N, 0, m²). In
    // binary32: 2c + m <= 130305 is exact, the quotient q is in [1/2, 255.5],
    // and a non-integral q lies at least 1/510 below the next integer, far more
    // than half an ulp (at most 2^-17), so the rounded quotient truncates to
    // floor(q). Then (v, v, v, alpha) per fragment.
    {
      const __m256i vscale = _mm256_set1_epi32(scale_rgb), zero = _mm256_setzero_si256();
      const __m256i vm2 = _mm256_set1_epi32(m2), vm = _mm256_set1_epi32(m);
      const __m256 two_m = _mm256_set1_ps(2.0f * m);
      // per 64-bit lane holding v | alpha << 16: the codes (v, v, v, alpha)
      const __m256i spread = _mm256_setr_epi8(0, 1, 0, 1, 0, 1, 2, 3, 8, 9, 8, 9, 8, 9, 10, 11, 0, 1, 0, 1, 0, 1, 2, 3, 8,
                                              9, 8, 9, 8, 9, 10, 11);
      for (; i + 8 <= nb; i += 8) {
        const __m256i N = _mm256_mullo_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(dot + i)), vscale);
        const __m256i c = _mm256_min_epi32(_mm256_max_epi32(N, zero), vm2);
        const __m256 num = _mm256_cvtepi32_ps(_mm256_add_epi32(_mm256_add_epi32(c, c), vm));
        const __m256i v = _mm256_cvttps_epi32(_mm256_div_ps(num, two_m));
        const __m256i a = _mm256_cvtepu16_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(alpha + i)));
        const __m256i va = _mm256_or_si256(v, _mm256_slli_epi32(a, 16));  // v | alpha << 16 per fragment
        const __m256i p0 = _mm256_shuffle_epi8(_mm256_cvtepu32_epi64(_mm256_castsi256_si128(va)), spread);
        const __m256i p1 = _mm256_shuffle_epi8(_mm256_cvtepu32_epi64(_mm256_extracti128_si256(va, 1)), spread);
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(o + 4 * static_cast<std::size_t>(i)), p0);
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(o + 4 * static_cast<std::size_t>(i) + 16), p1);
      }
    }
#endif
    for (; i < nb; ++i) {
      const std::uint16_t v = finish_m2(dot[i] * scale_rgb);
      o[4 * i] = v;
      o[4 * i + 1] = v;
      o[4 * i + 2] = v;
      o[4 * i + 3] = alpha[i];
    }
  }
  return true;
}

template <std::int64_t kM>
bool combine_span_fixed(const TexEnvState& env, const std::uint16_t* previous, const std::uint16_t* primary,
                        const std::uint16_t* texel, int n, int bits, std::uint16_t* out) {
  const CombineInt<kM> k{static_cast<std::int64_t>(unorm_max(bits))};
  std::uint16_t cc[4];
  for (int c = 0; c < 4; ++c) cc[c] = static_cast<std::uint16_t>(unorm_from_double(env.color[c], bits));
  const GLenum frgb = env.combine_rgb;
  const bool dot3 = is_dot3(frgb);
  const bool dot3_ext = frgb == gl::DOT3_RGB_EXT || frgb == gl::DOT3_RGBA_EXT;
  const bool dot3_rgba = frgb == gl::DOT3_RGBA || frgb == gl::DOT3_RGBA_EXT;
  const std::int64_t srgb = static_cast<int>(env.rgb_scale), salpha = static_cast<int>(env.alpha_scale);
  auto src = [&](GLenum which, const std::uint16_t* prev, const std::uint16_t* prim, const std::uint16_t* tex) {
    switch (which) {
      case gl::TEXTURE: return tex;
      case gl::CONSTANT: return static_cast<const std::uint16_t*>(cc);
      case gl::PRIMARY_COLOR: return prim;
      default: return prev;  // PREVIOUS
    }
  };
  for (int f = 0; f < n; ++f) {
    const std::size_t o = 4 * static_cast<std::size_t>(f);
    std::uint16_t prev[4];
    for (int c = 0; c < 4; ++c) prev[c] = previous[o + c];  // `out` may alias `previous`
    const std::uint16_t* rgb[3];
    const std::uint16_t* alpha[3];
    for (int i = 0; i < 3; ++i) {
      rgb[i] = src(env.source_rgb[i], prev, primary + o, texel + o);
      alpha[i] = src(env.source_alpha[i], prev, primary + o, texel + o);
    }
    std::uint16_t r[4];
    if (dot3) {
      // 4·Σ (a0 − ½)(a1 − ½) = Σ (2k0 − m)(2k1 − m) / m².
      std::int64_t d = 0;
      for (int c = 0; c < 3; ++c)
        d += (2 * k.operand(env.operand_rgb[0], rgb[0], c) - k.max()) * (2 * k.operand(env.operand_rgb[1], rgb[1], c) - k.max());
      const std::uint16_t v = k.finish(dot3_ext ? d : d * srgb, k.max() * k.max());
      r[0] = r[1] = r[2] = v;
      if (dot3_rgba) r[3] = k.finish(dot3_ext ? d : d * salpha, k.max() * k.max());
    } else {
      for (int c = 0; c < 3; ++c)
        r[c] = k.function(frgb, k.operand(env.operand_rgb[0], rgb[0], c), k.operand(env.operand_rgb[1], rgb[1], c),
                          k.operand(env.operand_rgb[2], rgb[2], c), srgb);
    }
    if (!dot3_rgba)
      r[3] = k.function(env.combine_alpha, k.operand(env.operand_alpha[0], alpha[0], 3),
                        k.operand(env.operand_alpha[1], alpha[1], 3), k.operand(env.operand_alpha[2], alpha[2], 3),
                        salpha);
    for (int c = 0; c < 4; ++c) out[o + c] = r[c];
  }
  return true;
}

}  // namespace

bool texture_environment_span_fixed(const TexEnvState& env, BaseFormat base, int texel_bits,
                                    const std::uint16_t* previous, const std::uint16_t* primary,
                                    const std::uint16_t* texel, int n, const ColorFormat& fmt, std::uint16_t* out) {
  if (!fmt.fixed() || texel_bits != fmt.bits) return false;
  if (env.mode == gl::COMBINE) {
    if (fmt.bits == 8 && combine_dot3_span_8(env, previous, primary, texel, n, out)) return true;
    return fmt.bits == 8 ? combine_span_fixed<255>(env, previous, primary, texel, n, fmt.bits, out)
                         : combine_span_fixed<0>(env, previous, primary, texel, n, fmt.bits, out);
  }
  // The classic() table above, per channel.
  const bool hc = has_color(base), ha = has_alpha(base);
  std::array<SpanOp, 4> op{SpanOp::Keep, SpanOp::Keep, SpanOp::Keep, SpanOp::Keep};
  auto rgb = [&](SpanOp o) { op[0] = op[1] = op[2] = o; };
  switch (env.mode) {
    case gl::REPLACE:
      if (hc) rgb(SpanOp::Texel);
      if (ha) op[3] = SpanOp::Texel;
      break;
    case gl::MODULATE:
      if (hc) rgb(SpanOp::Mul);
      if (ha) op[3] = SpanOp::Mul;
      break;
    case gl::DECAL:
      if (base == BaseFormat::RGB) rgb(SpanOp::Texel);
      if (base == BaseFormat::RGBA) rgb(SpanOp::Decal);
      break;
    case gl::BLEND:
      if (hc) rgb(SpanOp::Blend);
      if (base == BaseFormat::Intensity) op[3] = SpanOp::Blend;
      else if (ha) op[3] = SpanOp::Mul;
      break;
    case gl::ADD:
      if (hc) rgb(SpanOp::AddSat);
      if (base == BaseFormat::Intensity) op[3] = SpanOp::AddSat;
      else if (ha) op[3] = SpanOp::Mul;
      break;
    default: return false;
  }
  std::array<std::uint32_t, 4> cc{};
  for (int c = 0; c < 4; ++c) cc[c] = unorm_from_double(env.color[c], fmt.bits);
  const std::uint32_t m = unorm_max(fmt.bits);
  if (m == 255) env_span_channels<255>(op, cc, m, previous, texel, n, out);
  else env_span_channels<0>(op, cc, m, previous, texel, n, out);
  return true;
}

Rgba color_sum(const Rgba& primary, const Rgba& secondary, const ColorFormat& fmt) {
  Rgba out = primary;
  for (int c = 0; c < 3; ++c) {
    if (fmt.fixed()) {
      out.code[c] = std::min(primary.code[c] + secondary.code[c], unorm_max(fmt.bits));
    } else {
      const double v = std::min(primary.value[c] + secondary.value[c], 1.0);
      out.value[c] = fmt.arith == Arithmetic::Float32 ? static_cast<double>(static_cast<float>(v)) : v;
    }
  }
  return out;
}

}  // namespace ffsim

#include "pipeline/texture/texture_sample.h"

#ifdef __SSE4_1__
#include <immintrin.h>
#endif

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "pipeline/number/unorm.h"

namespace ffsim {

namespace {

bool is_pow2(int n) { return n > 0 && (n & (n - 1)) == 0; }

int floor_log2(int n) {
  int l = 0;
  while ((n >> (l + 1)) > 0) ++l;
  return l;
}

// Stored components of the border colour, in storage order (texture_object.h),
// selected by base format as Table 3.15 selects them from R, G, B, A.
std::array<double, 4> border_components(BaseFormat base, const std::array<double, 4>& bc) {
  switch (base) {
    case BaseFormat::Alpha: return {bc[3], 0, 0, 0};
    case BaseFormat::Luminance:
    case BaseFormat::Intensity: return {bc[0], 0, 0, 0};
    case BaseFormat::LuminanceAlpha: return {bc[0], bc[3], 0, 0};
    case BaseFormat::RGB: return {bc[0], bc[1], bc[2], 0};
    case BaseFormat::RGBA: return bc;
  }
  return bc;
}

// Texel (i, j) of a level in storage components, or the border colour when the
// index lies outside the image including its border (GL121 §3.8.7).
template <class V>
std::array<V, 4> fetch(const TextureImage& im, int dims, int i, int j, const std::array<V, 4>& border) {
  const int b = im.border;
  const int ws = level_width(im), hs = level_height(im, dims);
  const bool inside = i >= -b && i < ws + b && (dims == 1 || (j >= -b && j < hs + b));
  if (!inside) return border;
  const int n = component_count(im.base);
  const std::size_t row = dims == 1 ? 0 : static_cast<std::size_t>(j + b);
  const std::size_t idx = (row * static_cast<std::size_t>(im.width) + static_cast<std::size_t>(i + b)) * n;
  std::array<V, 4> out{};
  for (int c = 0; c < n; ++c) {
    if constexpr (std::is_same_v<V, std::uint32_t>) out[c] = im.codes[idx + c];
    else out[c] = im.values[idx + c];
  }
  return out;
}

template <class C>
C sanitize(C s) {
  return std::isfinite(s) ? s : C(0);  // non-finite coordinates sample at 0 (docs/numerics.md §8.3)
}

// Wrap of one coordinate for NEAREST (eq. 3.17-3.19): the texel index.
template <class C>
int nearest_index(C s, int n, GLenum wrap) {
  s = sanitize(s);
  if (wrap == gl::REPEAT) {
    const C u = (s - std::floor(s)) * static_cast<C>(n);
    const int i = static_cast<int>(std::floor(u));
    return ((i % n) + n) % n;  // s - floor(s) may round up to 1 for tiny negative s
  }
  if (wrap == gl::CLAMP_TO_EDGE) {
    const C lo = C(1) / static_cast<C>(2 * n);
    s = std::clamp(s, lo, C(1) - lo);
  } else {
    s = std::clamp(s, C(0), C(1));
  }
  const int i = static_cast<int>(std::floor(s * static_cast<C>(n)));
  return std::min(i, n - 1);  // s = 1 gives 2^n - 1 (eq. 3.19)
}

template <class C>
struct LinearAxis {
  int i0 = 0, i1 = 0;
  C frac = 0;  // α of eq. 3.20: frac(u - 1/2)
};

template <class C>
LinearAxis<C> linear_axis(C s, int n, GLenum wrap) {
  s = sanitize(s);
  if (wrap == gl::REPEAT) {
    s = s - std::floor(s);
  } else if (wrap == gl::CLAMP_TO_EDGE) {
    const C lo = C(1) / static_cast<C>(2 * n);
    s = std::clamp(s, lo, C(1) - lo);
  } else {
    s = std::clamp(s, C(0), C(1));
  }
  const C x = s * static_cast<C>(n) - C(0.5);
  const C fl = std::floor(x);
  LinearAxis<C> a;
  a.i0 = static_cast<int>(fl);
  a.i1 = a.i0 + 1;
  a.frac = x - fl;  // exact in binary floating point
  if (wrap == gl::REPEAT) {
    a.i0 = ((a.i0 % n) + n) % n;
    a.i1 = ((a.i1 % n) + n) % n;
  } else if (wrap == gl::CLAMP_TO_EDGE) {
    // s in [1/2n, 1-1/2n] puts i0 in [0, n-1]; i1 = n only with weight 0.
    a.i0 = std::clamp(a.i0, 0, n - 1);
    a.i1 = std::clamp(a.i1, 0, n - 1);
  }
  return a;
}

// Fixed profiles: one level, NEAREST or LINEAR, storage components as codes.
template <class C>
std::array<std::uint32_t, 4> level_codes(const TextureObject& tex, const TextureImage& im, int dims, GLenum filter,
                                         C s, C t, int B) {
  const int n = component_count(im.base);
  const std::array<double, 4> bd = border_components(im.base, tex.params.border_color);
  std::array<std::uint32_t, 4> border{};
  for (int c = 0; c < n; ++c) border[c] = unorm_from_double(bd[c], im.bits);
  const int ws = level_width(im), hs = level_height(im, dims);
  if (filter == gl::NEAREST) {
    const int i = nearest_index(s, ws, tex.params.wrap_s);
    const int j = dims == 1 ? 0 : nearest_index(t, hs, tex.params.wrap_t);
    return fetch(im, dims, i, j, border);
  }
  const std::uint64_t one = std::uint64_t{1} << B;
  const LinearAxis<C> ax = linear_axis(s, ws, tex.params.wrap_s);
  const auto a = static_cast<std::uint64_t>(std::floor(std::ldexp(ax.frac, B)));
  std::array<std::uint32_t, 4> out{};
  if (dims == 1) {
    const auto t0 = fetch(im, dims, ax.i0, 0, border), t1 = fetch(im, dims, ax.i1, 0, border);
    for (int c = 0; c < n; ++c) out[c] = static_cast<std::uint32_t>((t0[c] * (one - a) + t1[c] * a + one / 2) >> B);
    return out;
  }
  const LinearAxis<C> ay = linear_axis(t, hs, tex.params.wrap_t);
  const auto b = static_cast<std::uint64_t>(std::floor(std::ldexp(ay.frac, B)));
  const auto t00 = fetch(im, dims, ax.i0, ay.i0, border), t10 = fetch(im, dims, ax.i1, ay.i0, border);
  const auto t01 = fetch(im, dims, ax.i0, ay.i1, border), t11 = fetch(im, dims, ax.i1, ay.i1, border);
  const std::uint64_t w00 = (one - a) * (one - b), w10 = a * (one - b), w01 = (one - a) * b, w11 = a * b;
  const int B2 = 2 * B;
  for (int c = 0; c < n; ++c) {
    const std::uint64_t sum = t00[c] * w00 + t10[c] * w10 + t01[c] * w01 + t11[c] * w11;
    out[c] = static_cast<std::uint32_t>((sum + (std::uint64_t{1} << (B2 - 1))) >> B2);
  }
  return out;
}

// Float profiles: the real formula of eq. 3.20 in C (binary32 or binary64).
template <class C>
std::array<double, 4> level_values(const TextureObject& tex, const TextureImage& im, int dims, GLenum filter, C s,
                                   C t) {
  const int n = component_count(im.base);
  const std::array<double, 4> border = border_components(im.base, tex.params.border_color);
  const int ws = level_width(im), hs = level_height(im, dims);
  if (filter == gl::NEAREST) {
    const int i = nearest_index(s, ws, tex.params.wrap_s);
    const int j = dims == 1 ? 0 : nearest_index(t, hs, tex.params.wrap_t);
    return fetch(im, dims, i, j, border);
  }
  const LinearAxis<C> ax = linear_axis(s, ws, tex.params.wrap_s);
  std::array<double, 4> out{};
  if (dims == 1) {
    const auto t0 = fetch(im, dims, ax.i0, 0, border), t1 = fetch(im, dims, ax.i1, 0, border);
    for (int c = 0; c < n; ++c)
      out[c] = static_cast<double>((C(1) - ax.frac) * static_cast<C>(t0[c]) + ax.frac * static_cast<C>(t1[c]));
    return out;
  }
  const LinearAxis<C> ay = linear_axis(t, hs, tex.params.wrap_t);
  const auto t00 = fetch(im, dims, ax.i0, ay.i0, border), t10 = fetch(im, dims, ax.i1, ay.i0, border);
  const auto t01 = fetch(im, dims, ax.i0, ay.i1, border), t11 = fetch(im, dims, ax.i1, ay.i1, border);
  const C a = ax.frac, b = ay.frac;
  for (int c = 0; c < n; ++c) {
    const C v = (C(1) - a) * (C(1) - b) * static_cast<C>(t00[c]) + a * (C(1) - b) * static_cast<C>(t10[c]) +
                (C(1) - a) * b * static_cast<C>(t01[c]) + a * b * static_cast<C>(t11[c]);
    out[c] = static_cast<double>(v);
  }
  return out;
}

}  // namespace

Texel expand_texel(BaseFormat base, int bits, const std::array<std::uint32_t, 4>& k) {
  const std::uint32_t one = unorm_max(bits);
  Texel t;
  t.base = base;
  t.bits = bits;
  switch (base) {
    case BaseFormat::Alpha: t.code = {0, 0, 0, k[0]}; break;
    case BaseFormat::Luminance: t.code = {k[0], k[0], k[0], one}; break;
    case BaseFormat::LuminanceAlpha: t.code = {k[0], k[0], k[0], k[1]}; break;
    case BaseFormat::Intensity: t.code = {k[0], k[0], k[0], k[0]}; break;
    case BaseFormat::RGB: t.code = {k[0], k[1], k[2], one}; break;
    case BaseFormat::RGBA: t.code = k; break;
  }
  return t;
}

Texel expand_texel(BaseFormat base, const std::array<double, 4>& v) {
  Texel t;
  t.base = base;
  t.bits = 0;
  switch (base) {
    case BaseFormat::Alpha: t.value = {0, 0, 0, v[0]}; break;
    case BaseFormat::Luminance: t.value = {v[0], v[0], v[0], 1}; break;
    case BaseFormat::LuminanceAlpha: t.value = {v[0], v[0], v[0], v[1]}; break;
    case BaseFormat::Intensity: t.value = {v[0], v[0], v[0], v[0]}; break;
    case BaseFormat::RGB: t.value = {v[0], v[1], v[2], 1}; break;
    case BaseFormat::RGBA: t.value = v; break;
  }
  return t;
}

int last_mipmap_level(const TextureObject& tex, int dims) {
  const int b = tex.params.base_level;
  const TextureImage& im = tex.levels[static_cast<std::size_t>(b)];
  const int p = floor_log2(std::max(level_width(im), level_height(im, dims))) + b;
  return std::min(p, tex.params.max_level);
}

bool texture_complete(const TextureObject& tex, int dims, const SampleFormat& fmt) {
  const int b = tex.params.base_level;
  if (b < 0 || b > tex.params.max_level || static_cast<std::size_t>(b) >= tex.levels.size()) return false;
  auto level_ok = [&](const TextureImage& im, int ws, int hs, const TextureImage& base) {
    if (im.empty() || im.base != base.base || im.border != base.border) return false;
    if (level_width(im) != ws || level_height(im, dims) != hs) return false;
    if (dims == 1 && im.height != 1) return false;
    const std::size_t need = static_cast<std::size_t>(im.width) * im.height * component_count(im.base);
    if (fmt.arith == Arithmetic::Fixed) return im.codes.size() >= need && im.bits >= 1 && im.bits <= 16;
    return im.values.size() >= need;
  };
  const TextureImage& base = tex.levels[static_cast<std::size_t>(b)];
  const int ws = level_width(base), hs = level_height(base, dims);
  if (!is_pow2(ws) || !is_pow2(hs) || !level_ok(base, ws, hs, base)) return false;
  if (!is_mipmap_filter(tex.params.min_filter)) return true;
  const int q = last_mipmap_level(tex, dims);
  for (int k = b + 1; k <= q; ++k) {
    if (static_cast<std::size_t>(k) >= tex.levels.size()) return false;
    if (!level_ok(tex.levels[static_cast<std::size_t>(k)], std::max(1, ws >> (k - b)), std::max(1, hs >> (k - b)),
                  base))
      return false;
  }
  return true;
}

std::string describe_footprint(const TextureObject& tex, int level, int dims, GLenum filter, double s, double t,
                               const SampleFormat& fmt) {
  const TextureImage& im = tex.levels[static_cast<std::size_t>(level)];
  const int n = component_count(im.base);
  const int ws = level_width(im), hs = level_height(im, dims);
  const bool fixed = fmt.arith == Arithmetic::Fixed;
  const std::array<double, 4> bd = border_components(im.base, tex.params.border_color);
  std::array<std::uint32_t, 4> bcode{};
  for (int c = 0; c < n; ++c) bcode[c] = unorm_from_double(bd[c], im.bits);
  auto texel = [&](int i, int j) {
    std::string r("[");
    r.append(std::to_string(i));
    if (dims == 2) r.append(",").append(std::to_string(j));
    r.append("] (");
    for (int c = 0; c < n; ++c) {
      if (c) r += ", ";
      if (fixed) r += std::to_string(fetch(im, dims, i, j, bcode)[c]);
      else {
        const std::array<double, 4> v = fetch(im, dims, i, j, bd);
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.6g", v[c]);
        r += buf;
      }
    }
    return r.append(")");
  };
  const auto sf = static_cast<float>(s), tf = static_cast<float>(t);  // as sample_level rounds them
  std::string out("level ");
  out.append(std::to_string(level));
  if (filter == gl::NEAREST) {
    const int i = nearest_index(fixed ? sf : s, ws, tex.params.wrap_s);
    const int j = dims == 1 ? 0 : nearest_index(fixed ? tf : t, hs, tex.params.wrap_t);
    return out.append(" NEAREST texel ").append(texel(i, j));
  }
  const LinearAxis<double> ax = linear_axis<double>(fixed ? sf : s, ws, tex.params.wrap_s);
  const LinearAxis<double> ay = dims == 1 ? LinearAxis<double>{} : linear_axis<double>(fixed ? tf : t, hs, tex.params.wrap_t);
  auto weight = [&](double frac) {
    if (!fixed) return std::to_string(frac);
    const int B = fmt.weight_bits;
    std::string w = std::to_string(static_cast<long long>(std::floor(std::ldexp(frac, B))));
    return w.append("/").append(std::to_string(1LL << B));
  };
  out.append(" LINEAR alpha ").append(weight(ax.frac));
  if (dims == 2) out.append(" beta ").append(weight(ay.frac));
  out.append(" texels ").append(texel(ax.i0, ay.i0)).append(" ").append(texel(ax.i1, ay.i0));
  if (dims == 2) out.append(" ").append(texel(ax.i0, ay.i1)).append(" ").append(texel(ax.i1, ay.i1));
  return out;
}

Texel sample_level(const TextureObject& tex, int level, int dims, GLenum filter, double s, double t,
                   const SampleFormat& fmt) {
  const TextureImage& im = tex.levels[static_cast<std::size_t>(level)];
  const auto sf = static_cast<float>(s), tf = static_cast<float>(t);
  if (fmt.arith == Arithmetic::Fixed)
    return expand_texel(im.base, im.bits, level_codes<float>(tex, im, dims, filter, sf, tf, fmt.weight_bits));
  if (fmt.arith == Arithmetic::Float32) return expand_texel(im.base, level_values<float>(tex, im, dims, filter, sf, tf));
  return expand_texel(im.base, level_values<double>(tex, im, dims, filter, s, t));
}

// ---- span fast path --------------------------------------------------------

bool sample_span_supported(const TextureObject& tex, int dims, const SampleFormat& fmt) {
  const TextureParams& p = tex.params;
  if (!(fmt.arith == Arithmetic::Fixed && dims == 2 && p.min_filter == p.mag_filter &&
        (p.mag_filter == gl::NEAREST || p.mag_filter == gl::LINEAR)))
    return false;
  // Power-of-two sides (every complete texture has them): REPEAT's mod is a mask.
  const TextureImage& im = tex.levels[static_cast<std::size_t>(p.base_level)];
  return is_pow2(level_width(im)) && is_pow2(level_height(im, dims));
}

namespace {

// std::floor for binary32 without a library call, exact for every float: values
// of magnitude >= 2^23 (and ±inf, NaN) are integral already; below, truncation
// through int32 is exact, minus one for a negative non-integer; an integral x
// (±0 included) is returned as is, keeping the sign of zero like floor.
inline float floor_f(float x) {
  if (!(std::fabs(x) < 8388608.0f)) return x;
  const auto t = static_cast<float>(static_cast<std::int32_t>(x));
  if (t == x) return x;
  return t > x ? t - 1.0f : t;
}

// nearest_index<float> / linear_axis<float> for a power-of-two n with floor_f,
// and i & (n − 1) for REPEAT's ((i % n) + n) % n (equal for a power of two n in
// two's complement). The same operations otherwise, in the same order.
inline int nearest_index_pow2(float s, int n, GLenum wrap) {
  s = sanitize(s);
  if (wrap == gl::REPEAT) {
    const float u = (s - floor_f(s)) * static_cast<float>(n);
    return static_cast<int>(floor_f(u)) & (n - 1);
  }
  if (wrap == gl::CLAMP_TO_EDGE) {
    const float lo = 1.0f / static_cast<float>(2 * n);
    s = std::clamp(s, lo, 1.0f - lo);
  } else {
    s = std::clamp(s, 0.0f, 1.0f);
  }
  const int i = static_cast<int>(floor_f(s * static_cast<float>(n)));
  return std::min(i, n - 1);
}

inline LinearAxis<float> linear_axis_pow2(float s, int n, GLenum wrap) {
  s = sanitize(s);
  if (wrap == gl::REPEAT) {
    s = s - floor_f(s);
  } else if (wrap == gl::CLAMP_TO_EDGE) {
    const float lo = 1.0f / static_cast<float>(2 * n);
    s = std::clamp(s, lo, 1.0f - lo);
  } else {
    s = std::clamp(s, 0.0f, 1.0f);
  }
  const float x = s * static_cast<float>(n) - 0.5f;
  const float fl = floor_f(x);
  LinearAxis<float> a;
  a.i0 = static_cast<int>(fl);
  a.i1 = a.i0 + 1;
  a.frac = x - fl;
  if (wrap == gl::REPEAT) {
    a.i0 &= n - 1;
    a.i1 &= n - 1;
  } else if (wrap == gl::CLAMP_TO_EDGE) {
    a.i0 = std::clamp(a.i0, 0, n - 1);
    a.i1 = std::clamp(a.i1, 0, n - 1);
  }
  return a;
}

// What sample_level computes per fragment, with everything that does not depend
// on (s, t) computed once. kDirect: every index the filter produces lies inside
// the image (NEAREST always; LINEAR unless a wrap is CLAMP), so fetch's
// inside-or-border test is skipped.
struct SpanLevel {
  const TextureObject* tex;
  const TextureImage* im;
  int ws, hs, ncomp, B;
  std::array<std::uint32_t, 4> border{};
  std::array<int, 4> expand{};  // register component c = comps[expand[c]]; 4: 0, 5: one
  std::uint32_t one_code;
};

// U: the accumulator of the weighted sum; std::uint32_t when it cannot overflow
// (texel bits + 2B <= 31), else std::uint64_t as in level_codes. Same value.
// NC: stored components per texel (0: L.ncomp at run time).
template <bool kLinear, bool kDirect, class U, int NC>
void span_level(const SpanLevel& L, const float* s, const float* t, int n, std::uint16_t* out) {
  const TextureImage& im = *L.im;
  const TextureParams& p = L.tex->params;
  const int nc = NC ? NC : L.ncomp, b = im.border;
  const std::uint16_t* codes = im.codes.data();
  const std::size_t W = static_cast<std::size_t>(im.width);
  auto at = [&](int i, int j) {  // kDirect: the texel's stored components in place
    return codes + ((static_cast<std::size_t>(j + b) * W) + static_cast<std::size_t>(i + b)) * static_cast<std::size_t>(nc);
  };
  const U one = U{1} << L.B;
  const int B2 = 2 * L.B;
  const U half = U{1} << (B2 - 1);
  const float two_b = std::ldexp(1.0f, L.B);
  std::uint32_t k[4] = {0, 0, 0, 0};
  // A row of a screen-aligned quad has one t: its axis is then computed once.
  bool t_const = true;
  for (int f = 1; f < n && t_const; ++f) t_const = t[f] == t[0];
  LinearAxis<float> ay;
  for (int f = 0; f < n; ++f) {
    const float sf = s[f], tf = t[f];  // binary32, as sample_level rounds them
    if constexpr (!kLinear) {
      const std::uint16_t* q = at(nearest_index_pow2(sf, L.ws, p.wrap_s), nearest_index_pow2(tf, L.hs, p.wrap_t));
      for (int c = 0; c < nc; ++c) k[c] = q[c];
    } else {
      const LinearAxis<float> ax = linear_axis_pow2(sf, L.ws, p.wrap_s);
      if (!t_const || f == 0) ay = linear_axis_pow2(tf, L.hs, p.wrap_t);
      // floor(ldexp(α, B)): α·2^B is exact in binary32 (a power-of-two scale of
      // α in [0, 1)), and truncation is floor for a non-negative value.
      const auto a = static_cast<U>(ax.frac * two_b);
      const auto bb = static_cast<U>(ay.frac * two_b);
      const U w00 = (one - a) * (one - bb), w10 = a * (one - bb), w01 = (one - a) * bb, w11 = a * bb;
      if constexpr (kDirect) {
        const std::uint16_t *t00 = at(ax.i0, ay.i0), *t10 = at(ax.i1, ay.i0);
        const std::uint16_t *t01 = at(ax.i0, ay.i1), *t11 = at(ax.i1, ay.i1);
        for (int c = 0; c < nc; ++c) {
          const U sum = U{t00[c]} * w00 + U{t10[c]} * w10 + U{t01[c]} * w01 + U{t11[c]} * w11;
          k[c] = static_cast<std::uint32_t>((sum + half) >> B2);
        }
      } else {
        const auto t00 = fetch(im, 2, ax.i0, ay.i0, L.border), t10 = fetch(im, 2, ax.i1, ay.i0, L.border);
        const auto t01 = fetch(im, 2, ax.i0, ay.i1, L.border), t11 = fetch(im, 2, ax.i1, ay.i1, L.border);
        for (int c = 0; c < nc; ++c) {
          const U sum = t00[c] * w00 + t10[c] * w10 + t01[c] * w01 + t11[c] * w11;
          k[c] = static_cast<std::uint32_t>((sum + half) >> B2);
        }
      }
    }
    std::uint16_t* o = out + 4 * static_cast<std::size_t>(f);
    for (int c = 0; c < 4; ++c) {
      const int e = L.expand[c];
      o[c] = static_cast<std::uint16_t>(e < 4 ? k[e] : e == 5 ? L.one_code : 0u);
    }
  }
}

// LINEAR with REPEAT on both axes, every index inside the image, the weighted
// sum in 32 bits (texel bits + 2B <= 31): span_level<true, true, uint32_t, NC>'s
// numbers in two passes, so the compiler can vectorise the first.
//  1. per fragment, the x axis exactly as linear_axis_pow2(REPEAT): non-finite ->
//     0, s − floor(s), ·n − 1/2, floor, the fraction's B-bit weight, the indices
//     masked by n − 1 (floor is exact, so std::floor and floor_f agree);
//  2. per fragment, the four texels and the sum rounded once, as span_level.
// A span whose x and y weights are all 0 (texel-aligned sampling) reads one
// texel: (k·2^2B + 2^(2B−1)) >> 2B = k.
constexpr int kAxisChunk = 64;

void repeat_axis(const float* s, int n, int size, float two_b, std::int32_t* i0, std::int32_t* i1,
                 std::uint32_t* w) {
  const auto nf = static_cast<float>(size);
  const std::int32_t mask = size - 1;
  int f = 0;
#ifdef __AVX2__
  // Eight fragments at a time, the same IEEE operations in lanes (GCC does not
  // vectorise the loop below itself under -ftrapping-math): floor_ps is exact,
  // mul and sub stay separate (no FMA), cvttps truncates like the casts (fl and
  // the weight are integral or in range).
  {
    const __m256 vnf = _mm256_set1_ps(nf), vhalf = _mm256_set1_ps(0.5f), vtwo_b = _mm256_set1_ps(two_b);
    const __m256i vexp = _mm256_set1_epi32(0x7f800000), vmask = _mm256_set1_epi32(mask), vone = _mm256_set1_epi32(1);
    for (; f + 8 <= n; f += 8) {
      __m256 x = _mm256_loadu_ps(s + f);
      const __m256i inf_or_nan = _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_castps_si256(x), vexp), vexp);
      x = _mm256_andnot_ps(_mm256_castsi256_ps(inf_or_nan), x);  // non-finite -> +0
      x = _mm256_sub_ps(x, _mm256_floor_ps(x));
      x = _mm256_sub_ps(_mm256_mul_ps(x, vnf), vhalf);
      const __m256 fl = _mm256_floor_ps(x);
      const __m256i i = _mm256_cvttps_epi32(fl);
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(i0 + f), _mm256_and_si256(i, vmask));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(i1 + f), _mm256_and_si256(_mm256_add_epi32(i, vone), vmask));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(w + f), _mm256_cvttps_epi32(_mm256_mul_ps(_mm256_sub_ps(x, fl), vtwo_b)));
    }
  }
#endif
  for (; f < n; ++f) {
    float x = s[f];
    // isfinite(x) ? x : 0, from the exponent bits (no floating compare: a select)
    x = (std::bit_cast<std::uint32_t>(x) & 0x7f800000u) != 0x7f800000u ? x : 0.0f;
    x = x - std::floor(x);
    x = x * nf - 0.5f;
    const float fl = std::floor(x);
    const auto i = static_cast<std::int32_t>(fl);
    i0[f] = i & mask;
    i1[f] = (i + 1) & mask;
    // (x − fl)·2^B is in [0, 2^B), B <= 16: through int32 (vectorisable), the same value.
    w[f] = static_cast<std::uint32_t>(static_cast<std::int32_t>((x - fl) * two_b));
  }
}

#ifdef __AVX2__
// span_linear_repeat's RGBA and RGB sums for texels of at most 15 bits and
// weights of at most 14 (every code and weight fits int16), the same integers
// regrouped (a, b the B-bit weights, 1 = 2^B):
//   Σ t·w = (1 − b)·h0 + b·h1,  h0 = t00·(1 − a) + t10·a,  h1 = t01·(1 − a) + t11·a
//         = h0·2^B + (h1 − h0)·b,
// exact in 32-bit lanes: the sum is below 2^31 (texel bits + 2B <= 31) and the
// wrap-around of (h1 − h0)·b cancels in the addition. Where x1 = x0 + 1 (no wrap
// around the row) t10 follows t00 in memory, so one 16-byte load at t00 holds
// both, and one pmaddwd per row gives two fragments' h0 (h1) for four
// components. Eight fragments at a time; eight with a wrapped pair, and the
// tail, take the sum as span_level writes it. off: the four texels' code
// offsets (t00, t10, t01, t11); codes holds 8 codes from each t00 and t01.
template <int NC>
void linear_repeat_pairs(const std::uint16_t* codes, const std::uint32_t* const (&off)[4], const std::int32_t* x0,
                         const std::int32_t* x1, const std::uint32_t* wx, const std::uint32_t* wy, int m, int B,
                         std::uint32_t one_code, std::uint16_t* o) {
  const std::uint32_t one = 1u << B;
  const int B2 = 2 * B;
  const std::uint32_t half = 1u << (B2 - 1);
  const std::uint32_t *o00 = off[0], *o10 = off[1], *o01 = off[2], *o11 = off[3];
  auto sum = [&](int f) {  // span_level's sum, one fragment
    const std::uint32_t a = wx[f], bb = wy[f];
    const std::uint32_t w00 = (one - a) * (one - bb), w10 = a * (one - bb), w01 = (one - a) * bb, w11 = a * bb;
    const std::uint16_t *t00 = codes + o00[f], *t10 = codes + o10[f], *t01 = codes + o01[f], *t11 = codes + o11[f];
    std::uint16_t* q = o + 4 * static_cast<std::size_t>(f);
    for (int c = 0; c < NC; ++c)
      q[c] = static_cast<std::uint16_t>((t00[c] * w00 + t10[c] * w10 + t01[c] * w01 + t11[c] * w11 + half) >> B2);
    if constexpr (NC == 3) q[3] = static_cast<std::uint16_t>(one_code);
  };
  // Per 128-bit lane (one fragment), t00's and t10's codes as int16 pairs per
  // component, (t00.c, t10.c); RGB: the alpha pair 0.
  const __m256i interleave =
      NC == 4 ? _mm256_setr_epi8(0, 1, 8, 9, 2, 3, 10, 11, 4, 5, 12, 13, 6, 7, 14, 15, 0, 1, 8, 9, 2, 3, 10, 11, 4, 5, 12,
                                 13, 6, 7, 14, 15)
              : _mm256_setr_epi8(0, 1, 6, 7, 2, 3, 8, 9, 4, 5, 10, 11, -1, -1, -1, -1, 0, 1, 6, 7, 2, 3, 8, 9, 4, 5, 10,
                                 11, -1, -1, -1, -1);
  const __m128i sB = _mm_cvtsi32_si128(B), s2B = _mm_cvtsi32_si128(B2);
  const __m256i vhalf = _mm256_set1_epi32(static_cast<int>(half)), vone = _mm256_set1_epi32(static_cast<int>(one));
  const __m256i one_codes = _mm256_set1_epi16(static_cast<std::int16_t>(one_code)), vi1 = _mm256_set1_epi32(1);
  auto rows = [&](const std::uint32_t* of, int f) {  // fragments f, f + 1: one lane each
    return _mm256_shuffle_epi8(_mm256_loadu2_m128i(reinterpret_cast<const __m128i*>(codes + of[f + 1]),
                                                   reinterpret_cast<const __m128i*>(codes + of[f])),
                               interleave);
  };
  auto ld = [](const void* p) { return _mm256_loadu_si256(static_cast<const __m256i*>(p)); };
  int f = 0;
  for (; f + 8 <= m; f += 8) {
    const __m256i adjacent = _mm256_cmpeq_epi32(ld(x1 + f), _mm256_add_epi32(ld(x0 + f), vi1));
    if (_mm256_movemask_epi8(adjacent) != -1) {  // a pair wraps around the row
      for (int i = f; i < f + 8; ++i) sum(i);
      continue;
    }
    const __m256i a = ld(wx + f), wb = ld(wy + f);
    const __m256i wa = _mm256_or_si256(_mm256_sub_epi32(vone, a), _mm256_slli_epi32(a, 16));  // (1 − a) | a << 16
    __m256i r[4];
    for (int p = 0; p < 4; ++p) {
      const __m256i pick = _mm256_setr_epi32(2 * p, 2 * p, 2 * p, 2 * p, 2 * p + 1, 2 * p + 1, 2 * p + 1, 2 * p + 1);
      const __m256i wap = _mm256_permutevar8x32_epi32(wa, pick), wbp = _mm256_permutevar8x32_epi32(wb, pick);
      const __m256i h0 = _mm256_madd_epi16(rows(o00, f + 2 * p), wap);
      const __m256i h1 = _mm256_madd_epi16(rows(o01, f + 2 * p), wap);
      const __m256i s = _mm256_add_epi32(_mm256_sll_epi32(h0, sB), _mm256_mullo_epi32(_mm256_sub_epi32(h1, h0), wbp));
      r[p] = _mm256_srl_epi32(_mm256_add_epi32(s, vhalf), s2B);
    }
    for (int q = 0; q < 2; ++q) {
      // codes < 2^16 (packus keeps them); lanes (f, f + 2 | f + 1, f + 3) to (f, f + 1, f + 2, f + 3)
      __m256i packed = _mm256_permute4x64_epi64(_mm256_packus_epi32(r[2 * q], r[2 * q + 1]), 0xD8);
      if constexpr (NC == 3) packed = _mm256_blend_epi16(packed, one_codes, 0x88);  // RGB: (R, G, B, 1)
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(o + 4 * static_cast<std::size_t>(f + 4 * q)), packed);
    }
  }
  for (; f < m; ++f) sum(f);
}
#endif

template <int NC>
void span_linear_repeat(const SpanLevel& L, const float* s, const float* t, int n, std::uint16_t* out) {
  const TextureImage& im = *L.im;
  const int nc = NC ? NC : L.ncomp, b = im.border;
  const std::uint16_t* codes = im.codes.data();
  const std::size_t W = static_cast<std::size_t>(im.width);
  const std::uint32_t one = 1u << L.B;
  const int B2 = 2 * L.B;
  const std::uint32_t half = 1u << (B2 - 1);
  const float two_b = std::ldexp(1.0f, L.B);
  // Texel codes and weights fit int16: linear_repeat_pairs.
  [[maybe_unused]] const bool pairs16 = im.bits <= 15 && L.B <= 14;
  // One t for the span (bit for bit; no early exit, so the loop vectorises):
  // its axis is then computed once. (±0 differ in bits: computed per fragment.)
  std::uint32_t t_varies = 0;
  const auto t0 = std::bit_cast<std::uint32_t>(t[0]);
  for (int f = 1; f < n; ++f) t_varies |= std::bit_cast<std::uint32_t>(t[f]) ^ t0;
  const bool t_const = t_varies == 0;
  alignas(32) std::int32_t x0[kAxisChunk], x1[kAxisChunk], y0[kAxisChunk], y1[kAxisChunk];
  alignas(32) std::uint32_t wx[kAxisChunk], wy[kAxisChunk];
  auto texel = [&](std::int32_t i, std::int32_t j) {
    return codes + ((static_cast<std::size_t>(j + b) * W) + static_cast<std::size_t>(i + b)) * static_cast<std::size_t>(nc);
  };
  auto store = [&](std::uint16_t* o, const std::uint32_t* k) {
    if constexpr (NC == 4) {  // RGBA: expand_texel is the identity
      for (int c = 0; c < 4; ++c) o[c] = static_cast<std::uint16_t>(k[c]);
    } else if constexpr (NC == 3) {  // RGB: (R, G, B, 1)
      for (int c = 0; c < 3; ++c) o[c] = static_cast<std::uint16_t>(k[c]);
      o[3] = static_cast<std::uint16_t>(L.one_code);
    } else {
      for (int c = 0; c < 4; ++c) {
        const int e = L.expand[c];
        o[c] = static_cast<std::uint16_t>(e < 4 ? k[e] : e == 5 ? L.one_code : 0u);
      }
    }
  };
  bool y_filled = !t_const;
  auto fill_y = [&] {
    if (y_filled) return;
    std::fill_n(y0 + 1, kAxisChunk - 1, y0[0]);
    std::fill_n(y1 + 1, kAxisChunk - 1, y1[0]);
    std::fill_n(wy + 1, kAxisChunk - 1, wy[0]);
    y_filled = true;
  };
  for (int first = 0; first < n; first += kAxisChunk) {
    const int m = std::min(kAxisChunk, n - first);
    repeat_axis(s + first, m, L.ws, two_b, x0, x1, wx);
    // One t: its axis once, in lane 0; the other lanes are filled only where a
    // loop below reads them per fragment (once per call: they never change).
    if (!t_const) repeat_axis(t + first, m, L.hs, two_b, y0, y1, wy);
    else if (first == 0) repeat_axis(t, 1, L.hs, two_b, y0, y1, wy);
    std::uint32_t any = t_const ? wy[0] : 0;
    for (int f = 0; f < m; ++f) any |= wx[f];
    if (!t_const)
      for (int f = 0; f < m; ++f) any |= wy[f];
    std::uint16_t* o = out + 4 * static_cast<std::size_t>(first);
    std::uint32_t k[4] = {0, 0, 0, 0};
    if (any == 0) {  // every weight (1, 0, 0, 0): the texel at (i0, j0)
      if constexpr (NC == 4) {
        // One row of texels in order (a screen-aligned quad at one pixel per
        // texel): x0[f] = (x0[0] + f) mod w_s. RGBA texels are stored as the four
        // codes the fragment takes, so the run is copied a row segment at a time.
        std::uint32_t off_row = 0;
        for (int f = 0; f < m; ++f) off_row |= static_cast<std::uint32_t>(x0[f] ^ ((x0[0] + f) & (L.ws - 1)));
        if (!t_const)
          for (int f = 0; f < m; ++f) off_row |= static_cast<std::uint32_t>(y0[f] ^ y0[0]);
        if (off_row == 0) {
          const std::uint16_t* row = texel(0, y0[0]);
          for (int f = 0, i = x0[0]; f < m; i = 0) {
            const int len = std::min(m - f, L.ws - i);
            std::memcpy(o + 4 * static_cast<std::size_t>(f), row + 4 * static_cast<std::size_t>(i),
                        4 * sizeof(std::uint16_t) * static_cast<std::size_t>(len));
            f += len;
          }
          continue;
        }
      }
      fill_y();
      for (int f = 0; f < m; ++f, o += 4) {
        const std::uint16_t* q = texel(x0[f], y0[f]);
        for (int c = 0; c < nc; ++c) k[c] = q[c];
        store(o, k);
      }
      continue;
    }
    fill_y();
    if constexpr (NC == 1) {
      // One stored component (ALPHA, LUMINANCE, INTENSITY: the imaging path's
      // maps): the four texels and the rounded sum per fragment in one loop, then
      // the register components as (k & mask) | constant per channel, expand's
      // table without a branch (k: 0xFFFF mask; 1: the constant one_code; 0: 0).
      alignas(32) std::uint32_t k1[kAxisChunk];
      const auto Wb = static_cast<std::uint32_t>(W), ub = static_cast<std::uint32_t>(b);
      int f0 = 0;
#ifdef __AVX2__
      // Eight fragments at a time: the texels by 32-bit gathers at their code's
      // byte offset (the low 16 bits; the high half, the next code, is masked
      // off), unless a gather would read past the image (its last texel).
      {
        const __m256i vWb = _mm256_set1_epi32(static_cast<int>(Wb)), vub = _mm256_set1_epi32(static_cast<int>(ub));
        const __m256i vone = _mm256_set1_epi32(static_cast<int>(one)), vhalf = _mm256_set1_epi32(static_cast<int>(half));
        const __m256i low16 = _mm256_set1_epi32(0xFFFF);
        const __m128i shift = _mm_cvtsi32_si128(B2);
        const auto limit = static_cast<std::uint32_t>(im.codes.size()) - 1;  // the last code: a gather there reads past
        auto ld = [](const std::int32_t* p, int f) { return _mm256_load_si256(reinterpret_cast<const __m256i*>(p + f)); };
        auto gather_pair = [&](__m256i idx) {  // codes idx and idx + 1
          return _mm256_i32gather_epi32(reinterpret_cast<const int*>(codes), idx, 2);
        };
        auto gather = [&](__m256i idx) { return _mm256_and_si256(gather_pair(idx), low16); };
        const __m128i sB = _mm_cvtsi32_si128(L.B);
        const __m256i vi1 = _mm256_set1_epi32(1);
        for (; f0 + 8 <= m; f0 += 8) {
          const __m256i r0 = _mm256_add_epi32(_mm256_mullo_epi32(_mm256_add_epi32(ld(y0, f0), vub), vWb), vub);
          const __m256i r1 = _mm256_add_epi32(_mm256_mullo_epi32(_mm256_add_epi32(ld(y1, f0), vub), vWb), vub);
          const __m256i i00 = _mm256_add_epi32(r0, ld(x0, f0)), i10 = _mm256_add_epi32(r0, ld(x1, f0));
          const __m256i i01 = _mm256_add_epi32(r1, ld(x0, f0)), i11 = _mm256_add_epi32(r1, ld(x1, f0));
          const __m256i hi = _mm256_max_epu32(_mm256_max_epu32(i00, i10), _mm256_max_epu32(i01, i11));
          if (!_mm256_testz_si256(_mm256_cmpeq_epi32(_mm256_max_epu32(hi, _mm256_set1_epi32(static_cast<int>(limit))), hi),
                                  _mm256_set1_epi32(-1)))
            break;  // some index >= limit: the scalar loop from here
          const __m256i a = _mm256_load_si256(reinterpret_cast<const __m256i*>(wx + f0));
          const __m256i bb = _mm256_load_si256(reinterpret_cast<const __m256i*>(wy + f0));
          const __m256i na = _mm256_sub_epi32(vone, a), nb = _mm256_sub_epi32(vone, bb);
          __m256i sum;
          if (pairs16 && _mm256_movemask_epi8(_mm256_cmpeq_epi32(ld(x1, f0), _mm256_add_epi32(ld(x0, f0), vi1))) == -1) {
            // x1 = x0 + 1 in every lane: the 32-bit gather at t00 is t00 | t10 << 16
            // (at t01, t01 | t11 << 16), and linear_repeat_pairs's regrouped sum
            // takes one pmaddwd per row, h0·2^B + (h1 − h0)·b.
            const __m256i wa = _mm256_or_si256(na, _mm256_slli_epi32(a, 16));  // (1 − a) | a << 16
            const __m256i h0 = _mm256_madd_epi16(gather_pair(i00), wa), h1 = _mm256_madd_epi16(gather_pair(i01), wa);
            sum = _mm256_add_epi32(_mm256_sll_epi32(h0, sB), _mm256_mullo_epi32(_mm256_sub_epi32(h1, h0), bb));
          } else {
            sum = _mm256_mullo_epi32(gather(i00), _mm256_mullo_epi32(na, nb));
            sum = _mm256_add_epi32(sum, _mm256_mullo_epi32(gather(i10), _mm256_mullo_epi32(a, nb)));
            sum = _mm256_add_epi32(sum, _mm256_mullo_epi32(gather(i01), _mm256_mullo_epi32(na, bb)));
            sum = _mm256_add_epi32(sum, _mm256_mullo_epi32(gather(i11), _mm256_mullo_epi32(a, bb)));
          }
          _mm256_store_si256(reinterpret_cast<__m256i*>(k1 + f0), _mm256_srl_epi32(_mm256_add_epi32(sum, vhalf), shift));
        }
      }
#endif
      for (int f = f0; f < m; ++f) {
        const std::uint32_t a = wx[f], bb = wy[f];
        const std::uint32_t r0 = (static_cast<std::uint32_t>(y0[f]) + ub) * Wb + ub;
        const std::uint32_t r1 = (static_cast<std::uint32_t>(y1[f]) + ub) * Wb + ub;
        const std::uint32_t t00 = codes[r0 + static_cast<std::uint32_t>(x0[f])];
        const std::uint32_t t10 = codes[r0 + static_cast<std::uint32_t>(x1[f])];
        const std::uint32_t t01 = codes[r1 + static_cast<std::uint32_t>(x0[f])];
        const std::uint32_t t11 = codes[r1 + static_cast<std::uint32_t>(x1[f])];
        k1[f] = (t00 * ((one - a) * (one - bb)) + t10 * (a * (one - bb)) + t01 * ((one - a) * bb) + t11 * (a * bb) +
                 half) >> B2;
      }
      std::uint16_t mask[4], constant[4];
      for (int c = 0; c < 4; ++c) {
        const int e = L.expand[static_cast<std::size_t>(c)];
        mask[c] = e < 4 ? 0xFFFF : 0;
        constant[c] = static_cast<std::uint16_t>(e == 5 ? L.one_code : 0u);
      }
      for (int f = 0; f < m; ++f)
        for (int c = 0; c < 4; ++c)
          o[4 * f + c] = static_cast<std::uint16_t>((static_cast<std::uint16_t>(k1[f]) & mask[c]) | constant[c]);
      continue;
    }
#ifdef __AVX2__
    if constexpr (NC == 4 || NC == 3) {
      // The texel offsets of every fragment first (a loop the compiler
      // vectorises); then linear_repeat_pairs where its codes fit int16 and its
      // 16-byte loads stay inside the image. Otherwise two fragments per 256-bit
      // register (four 32-bit lanes each), the same integers as below: the four
      // weights of every fragment, then per pair four loads, four products and
      // one rounding; the codes packed back to 16 bits (< 2^16). RGB: a texel is
      // loaded as four codes, the fourth (the next texel's R) lands in the alpha
      // lane, which is then set to 1; unless a load would read past the image
      // (its last texel), then the chunk takes the loop below.
      alignas(32) std::uint32_t w00[kAxisChunk], w10[kAxisChunk], w01[kAxisChunk], w11[kAxisChunk];
      alignas(32) std::uint32_t o00[kAxisChunk], o10[kAxisChunk], o01[kAxisChunk], o11[kAxisChunk];
      const auto Wb = static_cast<std::uint32_t>(W), ub = static_cast<std::uint32_t>(b);
      std::uint32_t last = 0;  // the largest offset
      for (int f = 0; f < m; ++f) {
        const std::uint32_t r0 = (static_cast<std::uint32_t>(y0[f]) + ub) * Wb + ub;
        const std::uint32_t r1 = (static_cast<std::uint32_t>(y1[f]) + ub) * Wb + ub;
        o00[f] = NC * (r0 + static_cast<std::uint32_t>(x0[f]));
        o10[f] = NC * (r0 + static_cast<std::uint32_t>(x1[f]));
        o01[f] = NC * (r1 + static_cast<std::uint32_t>(x0[f]));
        o11[f] = NC * (r1 + static_cast<std::uint32_t>(x1[f]));
        last = std::max({last, o00[f], o10[f], o01[f], o11[f]});
      }
      if (pairs16 && static_cast<std::size_t>(last) + 8 <= im.codes.size()) {
        const std::uint32_t* const off[4] = {o00, o10, o01, o11};
        linear_repeat_pairs<NC>(codes, off, x0, x1, wx, wy, m, L.B, L.one_code, o);
        continue;
      }
      for (int f = 0; f < m; ++f) {
        const std::uint32_t a = wx[f], bb = wy[f];
        w00[f] = (one - a) * (one - bb);
        w10[f] = a * (one - bb);
        w01[f] = (one - a) * bb;
        w11[f] = a * bb;
      }
      if (NC == 4 || static_cast<std::size_t>(last) + 4 <= im.codes.size()) {
        const __m256i vhalf = _mm256_set1_epi32(static_cast<int>(half));
        const __m128i shift = _mm_cvtsi32_si128(B2);
        auto pair = [&](const std::uint32_t* off, int f) {  // texels of fragments f, f + 1 as 8 lanes
          const __m128i lo = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(codes + off[f]));
          const __m128i both = _mm_castpd_si128(
              _mm_loadh_pd(_mm_castsi128_pd(lo), reinterpret_cast<const double*>(codes + off[f + 1])));
          return _mm256_cvtepu16_epi32(both);
        };
        auto weight = [](const std::uint32_t* w, int f) {  // w[f] in lanes 0-3, w[f + 1] in lanes 4-7
          return _mm256_set_m128i(_mm_set1_epi32(static_cast<int>(w[f + 1])), _mm_set1_epi32(static_cast<int>(w[f])));
        };
        int f = 0;
        for (; f + 2 <= m; f += 2, o += 8) {
          __m256i sum = _mm256_mullo_epi32(pair(o00, f), weight(w00, f));
          sum = _mm256_add_epi32(sum, _mm256_mullo_epi32(pair(o10, f), weight(w10, f)));
          sum = _mm256_add_epi32(sum, _mm256_mullo_epi32(pair(o01, f), weight(w01, f)));
          sum = _mm256_add_epi32(sum, _mm256_mullo_epi32(pair(o11, f), weight(w11, f)));
          const __m256i r = _mm256_srl_epi32(_mm256_add_epi32(sum, vhalf), shift);
          const __m256i packed = _mm256_packus_epi32(r, r);  // per 128-bit lane: the fragment's codes twice
          __m128i codes2 = _mm256_castsi256_si128(_mm256_permute4x64_epi64(packed, 0x08));  // qwords 0 and 2
          if constexpr (NC == 3) {  // RGB: (R, G, B, 1)
            codes2 = _mm_insert_epi16(codes2, static_cast<int>(L.one_code), 3);
            codes2 = _mm_insert_epi16(codes2, static_cast<int>(L.one_code), 7);
          }
          _mm_storeu_si128(reinterpret_cast<__m128i*>(o), codes2);
        }
        for (; f < m; ++f, o += 4) {
          const std::uint16_t *t00 = codes + o00[f], *t10 = codes + o10[f], *t01 = codes + o01[f], *t11 = codes + o11[f];
          for (int c = 0; c < NC; ++c)
            k[c] = (t00[c] * w00[f] + t10[c] * w10[f] + t01[c] * w01[f] + t11[c] * w11[f] + half) >> B2;
          store(o, k);
        }
        continue;
      }
    }
#endif
#ifdef __SSE4_1__
    if constexpr (NC == 4 || NC == 3) {  // the components in one 128-bit register, the same integers
      const __m128i vhalf = _mm_set1_epi32(static_cast<int>(half));
      const __m128i shift = _mm_cvtsi32_si128(B2);
      auto load = [](const std::uint16_t* q) {
        if constexpr (NC == 4) {
          return _mm_cvtepu16_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(q)));
        } else {  // R, G, B only (a fourth code would read past the image's last texel); lane 3 is 0
          std::uint32_t rg;
          std::memcpy(&rg, q, sizeof rg);
          return _mm_cvtepu16_epi32(_mm_insert_epi16(_mm_cvtsi32_si128(static_cast<int>(rg)), q[2], 2));
        }
      };
      for (int f = 0; f < m; ++f, o += 4) {
        const std::uint32_t a = wx[f], bb = wy[f];
        const auto w00 = static_cast<int>((one - a) * (one - bb)), w10 = static_cast<int>(a * (one - bb));
        const auto w01 = static_cast<int>((one - a) * bb), w11 = static_cast<int>(a * bb);
        __m128i sum = _mm_mullo_epi32(load(texel(x0[f], y0[f])), _mm_set1_epi32(w00));
        sum = _mm_add_epi32(sum, _mm_mullo_epi32(load(texel(x1[f], y0[f])), _mm_set1_epi32(w10)));
        sum = _mm_add_epi32(sum, _mm_mullo_epi32(load(texel(x0[f], y1[f])), _mm_set1_epi32(w01)));
        sum = _mm_add_epi32(sum, _mm_mullo_epi32(load(texel(x1[f], y1[f])), _mm_set1_epi32(w11)));
        // (sum + half) >> 2B < 2^16: packus keeps it unchanged.
        const __m128i r = _mm_srl_epi32(_mm_add_epi32(sum, vhalf), shift);
        __m128i codes = _mm_packus_epi32(r, r);
        if constexpr (NC == 3) codes = _mm_insert_epi16(codes, static_cast<int>(L.one_code), 3);  // RGB: (R, G, B, 1)
        _mm_storel_epi64(reinterpret_cast<__m128i*>(o), codes);
      }
      continue;
    }
#endif
    for (int f = 0; f < m; ++f, o += 4) {
      const std::uint32_t a = wx[f], bb = wy[f];
      const std::uint32_t w00 = (one - a) * (one - bb), w10 = a * (one - bb), w01 = (one - a) * bb, w11 = a * bb;
      const std::uint16_t *t00 = texel(x0[f], y0[f]), *t10 = texel(x1[f], y0[f]);
      const std::uint16_t *t01 = texel(x0[f], y1[f]), *t11 = texel(x1[f], y1[f]);
      for (int c = 0; c < nc; ++c) {
        const std::uint32_t sum = t00[c] * w00 + t10[c] * w10 + t01[c] * w01 + t11[c] * w11;
        k[c] = (sum + half) >> B2;
      }
      store(o, k);
    }
  }
}

}  // namespace

void sample_span_fixed(const TextureObject& tex, int dims, const float* s, const float* t, int n,
                       const SampleFormat& fmt, std::uint16_t* out) {
  SpanLevel L;
  L.tex = &tex;
  L.im = &tex.levels[static_cast<std::size_t>(tex.params.base_level)];
  const TextureImage& im = *L.im;
  L.ws = level_width(im);
  L.hs = level_height(im, dims);
  L.ncomp = component_count(im.base);
  L.B = fmt.weight_bits;
  L.one_code = unorm_max(im.bits);
  // expand_texel's table as indices into the stored components.
  switch (im.base) {
    case BaseFormat::Alpha: L.expand = {4, 4, 4, 0}; break;
    case BaseFormat::Luminance: L.expand = {0, 0, 0, 5}; break;
    case BaseFormat::LuminanceAlpha: L.expand = {0, 0, 0, 1}; break;
    case BaseFormat::Intensity: L.expand = {0, 0, 0, 0}; break;
    case BaseFormat::RGB: L.expand = {0, 1, 2, 5}; break;
    case BaseFormat::RGBA: L.expand = {0, 1, 2, 3}; break;
  }
  const bool linear = tex.params.mag_filter == gl::LINEAR;
  const bool direct = !linear || (tex.params.wrap_s != gl::CLAMP && tex.params.wrap_t != gl::CLAMP);
  const bool narrow = im.bits + 2 * L.B <= 31;
  if (!direct) {  // only CLAMP with LINEAR can reach the border colour
    const std::array<double, 4> bd = border_components(im.base, tex.params.border_color);
    for (int c = 0; c < L.ncomp; ++c) L.border[c] = unorm_from_double(bd[c], im.bits);
  }
  const bool repeat = tex.params.wrap_s == gl::REPEAT && tex.params.wrap_t == gl::REPEAT;
  if (linear && repeat && narrow && L.ncomp == 4) span_linear_repeat<4>(L, s, t, n, out);
  else if (linear && repeat && narrow && L.ncomp == 3) span_linear_repeat<3>(L, s, t, n, out);
  else if (linear && repeat && narrow && L.ncomp == 1) span_linear_repeat<1>(L, s, t, n, out);
  else if (linear && repeat && narrow) span_linear_repeat<0>(L, s, t, n, out);
  else if (!linear) span_level<false, true, std::uint64_t, 0>(L, s, t, n, out);
  else if (direct && narrow && L.ncomp == 4) span_level<true, true, std::uint32_t, 4>(L, s, t, n, out);
  else if (direct && narrow && L.ncomp == 3) span_level<true, true, std::uint32_t, 3>(L, s, t, n, out);
  else if (direct && narrow) span_level<true, true, std::uint32_t, 0>(L, s, t, n, out);
  else if (direct) span_level<true, true, std::uint64_t, 0>(L, s, t, n, out);
  else span_level<true, false, std::uint64_t, 0>(L, s, t, n, out);
}

Texel sample_texture(const TextureObject& tex, int dims, double s, double t, double lambda_in,
                     const SampleFormat& fmt) {
  const TextureParams& p = tex.params;
  // λ in binary32 (binary64 for the ideal profile); NaN (0/0 derivatives) -> 0.
  double lambda = std::isnan(lambda_in) ? 0.0 : lambda_in;
  lambda = std::clamp(lambda, p.min_lod, p.max_lod);
  if (fmt.arith != Arithmetic::Float64) lambda = static_cast<float>(lambda);
  const double c = (p.mag_filter == gl::LINEAR &&
                   (p.min_filter == gl::NEAREST_MIPMAP_NEAREST || p.min_filter == gl::NEAREST_MIPMAP_LINEAR))
                      ? 0.5
                      : 0.0;
  const int b = p.base_level;
  if (lambda <= c) return sample_level(tex, b, dims, p.mag_filter, s, t, fmt);
  if (!is_mipmap_filter(p.min_filter)) return sample_level(tex, b, dims, p.min_filter, s, t, fmt);
  const int q = last_mipmap_level(tex, dims);
  const GLenum f =
      (p.min_filter == gl::NEAREST_MIPMAP_NEAREST || p.min_filter == gl::NEAREST_MIPMAP_LINEAR) ? gl::NEAREST
                                                                                                 : gl::LINEAR;
  const double bl = b + lambda;  // exact: b is a small integer
  if (p.min_filter == gl::NEAREST_MIPMAP_NEAREST || p.min_filter == gl::LINEAR_MIPMAP_NEAREST) {
    int d = q;  // eq. 3.21
    if (lambda <= 0.5) d = b;
    else if (bl <= q + 0.5) d = static_cast<int>(std::ceil(bl + 0.5)) - 1;
    return sample_level(tex, d, dims, f, s, t, fmt);
  }
  if (bl >= q) return sample_level(tex, q, dims, f, s, t, fmt);  // eq. 3.22, d1 = d2 = q
  const int d1 = static_cast<int>(std::floor(bl)), d2 = d1 + 1;
  const double fr = lambda - std::floor(lambda);  // frac(λ), exact
  const Texel t1 = sample_level(tex, d1, dims, f, s, t, fmt), t2 = sample_level(tex, d2, dims, f, s, t, fmt);
  Texel out = t1;
  if (fmt.arith == Arithmetic::Fixed) {
    const int B = fmt.weight_bits;
    const std::uint64_t one = std::uint64_t{1} << B;
    const auto w = static_cast<std::uint64_t>(std::floor(std::ldexp(fr, B)));
    for (int c = 0; c < 4; ++c) {
      const std::uint64_t k2 = unorm_convert(t2.code[c], t2.bits, t1.bits);
      out.code[c] = static_cast<std::uint32_t>((t1.code[c] * (one - w) + k2 * w + one / 2) >> B);
    }
  } else if (fmt.arith == Arithmetic::Float32) {
    for (int c = 0; c < 4; ++c)
      out.value[c] = static_cast<double>((1.0f - static_cast<float>(fr)) * static_cast<float>(t1.value[c]) +
                                         static_cast<float>(fr) * static_cast<float>(t2.value[c]));
  } else {
    for (int c = 0; c < 4; ++c) out.value[c] = (1.0 - fr) * t1.value[c] + fr * t2.value[c];
  }
  return out;
}

}  // namespace ffsim

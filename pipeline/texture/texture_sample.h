// Texture sampling (GL121 §3.8.5-3.8.7): wrap modes, NEAREST / LINEAR filters,
// the four mipmap filters, 1D and 2D, at the profile's precision.
//
// Output: the filtered texel of one texture unit, expanded to R, G, B, A by its
// base format the way ARB_texture_env_combine (Table 3.23) and
// NV_register_combiners (Table NV_register_combiners.2) read it:
//   ALPHA (0,0,0,At)  LUMINANCE (L,L,L,1)  LUMINANCE_ALPHA (L,L,L,At)
//   INTENSITY (I,I,I,I)  RGB (R,G,B,1)  RGBA (R,G,B,A).
// The classic texture functions (Table 3.18) additionally need the base format,
// which the texel carries.
//
// Numerics (docs/numerics.md §8.3-8.5): coordinates in binary32; fixed profiles
// quantise the LINEAR weights to `bilinear_weight_bits` fractional bits (floor),
// sum the integer products exactly and round half up once to the texel width;
// float profiles use the real weights.
#pragma once
#include <array>
#include <string>
#include <cstdint>

#include "pipeline/number/profile.h"
#include "pipeline/texture/texture_object.h"

namespace ffsim {

struct Texel {
  BaseFormat base = BaseFormat::RGBA;
  int bits = 8;                         // fixed profiles: width of `code`
  std::array<std::uint32_t, 4> code{};  // fixed profiles: R, G, B, A codes at `bits`
  std::array<double, 4> value{};        // float profiles: R, G, B, A in [0,1]
};

// How sampling computes: the profile's arithmetic and weight precision.
struct SampleFormat {
  Arithmetic arith = Arithmetic::Fixed;
  int weight_bits = 8;  // fixed profiles: fractional bits of filter weights
  static SampleFormat from_profile(const Profile& p) { return {p.arithmetic, p.bilinear_weight_bits}; }
};

// Sizes of a level without its border (w_s, h_s of GL121 §3.8.1).
inline int level_width(const TextureImage& im) { return im.width - 2 * im.border; }
inline int level_height(const TextureImage& im, int dims) { return dims == 1 ? 1 : im.height - 2 * im.border; }

// The last level a minification filter can use (q of GL121 §3.8.7): base level +
// log2 of the larger side, capped by MAX_LEVEL.
int last_mipmap_level(const TextureObject& tex, int dims);

// Texture completeness (GL121 §3.8.9): the base level exists with power-of-two
// sides; for a mipmap minification filter every level base..q exists with the
// halved sizes, the same base format and border. An incomplete texture makes its
// unit behave as if texturing were disabled (§3.8.13). Also checks that the
// level holds the data vector the profile samples (codes or values) at full size.
bool texture_complete(const TextureObject& tex, int dims, const SampleFormat& fmt);

// Whether the minification filter needs mipmaps.
constexpr bool is_mipmap_filter(GLenum f) {
  return f == gl::NEAREST_MIPMAP_NEAREST || f == gl::LINEAR_MIPMAP_NEAREST || f == gl::NEAREST_MIPMAP_LINEAR ||
         f == gl::LINEAR_MIPMAP_LINEAR;
}

// One filter on one level (no LOD logic): `filter` is NEAREST or LINEAR. Used by
// sample_texture and directly by unit tests.
// Coordinates are rounded to binary32 first in the fixed and float32 profiles
// (the hardware's texture coordinate format); the ideal profile keeps binary64.
Texel sample_level(const TextureObject& tex, int level, int dims, GLenum filter, double s, double t,
                   const SampleFormat& fmt);

// For single-pixel tracing: the footprint one filter reads on one level, in
// storage components (codes for fixed profiles): the wrapped texel indices, the
// weights (B-bit integers over 2^B in fixed profiles) and the texels.
std::string describe_footprint(const TextureObject& tex, int level, int dims, GLenum filter, double s, double t,
                               const SampleFormat& fmt);

// The complete lookup of GL121 §3.8.5-3.8.7 for a complete texture: λ clamped to
// [MIN_LOD, MAX_LOD], magnification vs minification switch (c = 0.5 or 0), level
// selection, and the mipmap LINEAR blend between levels. `s`, `t` are s/q, t/q.
// λ is rounded to binary32 except in the ideal profile.
Texel sample_texture(const TextureObject& tex, int dims, double s, double t, double lambda, const SampleFormat& fmt);

// ---- span fast path (docs/performance.md) ---------------------------------
// Whether sample_span_fixed applies: a fixed profile, a 2D texture whose
// result cannot depend on λ (MIN_FILTER == MAG_FILTER, NEAREST or LINEAR), so
// every fragment samples BASE_LEVEL with that filter.
bool sample_span_supported(const TextureObject& tex, int dims, const SampleFormat& fmt);
// For every i < n: the register-layout codes of
// sample_texture(tex, dims, s[i], t[i], λ, fmt) (any λ), 4 per fragment, at the
// base level's bits, into out[4i..4i+3]. Same operations, in the same order, as
// sample_level, which rounds its binary64 s and t to binary32 first: s and t
// here are those binary32 values (the same weights and rounding follow); only
// the per-fragment work that does not depend on the coordinates is hoisted.
void sample_span_fixed(const TextureObject& tex, int dims, const float* s, const float* t, int n,
                       const SampleFormat& fmt, std::uint16_t* out);

// The base-format expansion above applied to stored components (`comps` in the
// storage order of texture_object.h): exposed for tests and for the combiners.
Texel expand_texel(BaseFormat base, int bits, const std::array<std::uint32_t, 4>& comps);
Texel expand_texel(BaseFormat base, const std::array<double, 4>& comps);

}  // namespace ffsim

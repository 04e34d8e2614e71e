// Texture environments (GL121 §3.8.9 Tables 3.18-3.19; ARB_texture_env_add;
// ARB/EXT_texture_env_combine; ARB/EXT_texture_env_dot3) and the colour sum
// (GL 1.4 §3.9 / EXT_secondary_color).
//
// Numerics (docs/numerics.md §8.6-8.7): fixed profiles evaluate each unit's
// formula exactly on the rational operands k/(2^n - 1) (texels at the texture
// width, colours at the colour width, TEXTURE_ENV_COLOR rounded to the colour
// width), apply the scale and the spec's clamp, and round once, half up, to the
// colour width. Float profiles evaluate the same formula in binary64 and round
// the unit's result to binary32 in the float32 profile.
#pragma once
#include <array>
#include <cstdint>

#include "pipeline/gl/enums.h"
#include "pipeline/number/profile.h"
#include "pipeline/texture/texture_sample.h"

namespace ffsim {

// The representation of fragment colours between shading stages.
struct ColorFormat {
  Arithmetic arith = Arithmetic::Fixed;
  int bits = 8;  // fixed profiles: colour code width (= framebuffer colour bits)
  bool fixed() const { return arith == Arithmetic::Fixed; }
  static ColorFormat from_profile(const Profile& p) { return {p.arithmetic, p.color_bits}; }
};

// A fragment colour: codes at ColorFormat::bits (fixed) or values (float).
struct Rgba {
  std::array<std::uint32_t, 4> code{};
  std::array<double, 4> value{};
  bool operator==(const Rgba&) const = default;
};

// The colour from real values: clamp01, then §1.2 rounding (fixed), binary32
// rounding (float32) or as is (float64).
Rgba rgba_from_values(const std::array<double, 4>& v, const ColorFormat& fmt);

// Texture environment state of one unit (GL121 Table 6.17, TEC/TD3 state tables),
// with the initial values.
struct TexEnvState {
  GLenum mode = gl::MODULATE;                       // TEXTURE_ENV_MODE
  std::array<double, 4> color{0, 0, 0, 0};          // TEXTURE_ENV_COLOR, clamped to [0,1] when set
  GLenum combine_rgb = gl::MODULATE;                // COMBINE_RGB
  GLenum combine_alpha = gl::MODULATE;              // COMBINE_ALPHA
  std::array<GLenum, 3> source_rgb{gl::TEXTURE, gl::PREVIOUS, gl::CONSTANT};
  std::array<GLenum, 3> source_alpha{gl::TEXTURE, gl::PREVIOUS, gl::CONSTANT};
  std::array<GLenum, 3> operand_rgb{gl::SRC_COLOR, gl::SRC_COLOR, gl::SRC_ALPHA};
  std::array<GLenum, 3> operand_alpha{gl::SRC_ALPHA, gl::SRC_ALPHA, gl::SRC_ALPHA};
  double rgb_scale = 1, alpha_scale = 1;            // 1, 2 or 4
  bool operator==(const TexEnvState&) const = default;
};

// Number of arguments a COMBINE function reads (REPLACE 1, INTERPOLATE 3, else 2).
int combine_arg_count(GLenum function);
bool is_dot3(GLenum function);

// What one unit's environment reads, for the shading plan.
struct TexEnvReads {
  bool texture = false;   // the unit's filtered texel
  bool previous = false;  // Cf/Af: the previous unit's result (the primary colour on unit 0)
  bool primary = false;   // PRIMARY_COLOR (COMBINE only)
};
TexEnvReads texenv_reads(const TexEnvState& env, BaseFormat base);

// One unit: `previous` is Cf (the primary colour for unit 0), `primary` the
// fragment's primary colour (COMBINE source PRIMARY_COLOR), `texel` the unit's
// filtered texel. DECAL with a format other than RGB/RGBA (undefined in the spec)
// passes `previous` through.
Rgba texture_environment(const TexEnvState& env, const Rgba& previous, const Rgba& primary, const Texel& texel,
                         const ColorFormat& fmt);

// Span fast path (fixed profiles, docs/performance.md): one unit's environment
// over n fragments whose previous colours, primary colours and expanded texels
// are codes, 4 per fragment, when the texel width equals the colour width. Every
// operand is then k/m with one m, so the exact rational of texture_environment,
// scaled, clamped and rounded half up once, is an integer formula:
// a·b -> floor((2ab + m) / 2m), min(1, a + b) -> min(a + b, m), DOT3 ->
// floor((2·Σ(2a − m)(2b − m) + m) / 2m) clamped, ... `out` may be `previous`.
// Returns false and writes nothing when no such kernel applies (other widths):
// the caller runs texture_environment.
bool texture_environment_span_fixed(const TexEnvState& env, BaseFormat base, int texel_bits,
                                    const std::uint16_t* previous, const std::uint16_t* primary,
                                    const std::uint16_t* texel, int n, const ColorFormat& fmt, std::uint16_t* out);

// Colour sum (GL 1.4 §3.9): R, G, B of primary + secondary clamped to 1; A of the
// primary. Exact on codes of the same width.
Rgba color_sum(const Rgba& primary, const Rgba& secondary, const ColorFormat& fmt);

}  // namespace ffsim

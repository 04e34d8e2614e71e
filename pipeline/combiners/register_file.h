// The combiner register set (RC Table NV_register_combiners.1) and how a
// fragment's values enter it.
//
//   ZERO                 0
//   CONSTANT_COLOR0/1    ccc0 / ccc1 (global, or the stage's own with RC2 PER_STAGE_CONSTANTS)
//   FOG                  RGB = fog colour, A = fog factor (1 when fog is disabled)
//   PRIMARY_COLOR_NV     primary colour
//   SECONDARY_COLOR_NV   secondary colour; A is undefined on NV1x -> 0 (choice #24),
//                        or the secondary alpha when CombinerConfig::rc2_secondary_alpha
//   SPARE0_NV            A = texture 0 alpha when unit 0 is enabled; RGB undefined -> 0
//   SPARE1_NV            undefined -> 0
//   TEXTURE<i>_ARB       filtered texel of unit i (RC Table .2 component layout),
//                        undefined when unit i is disabled -> 0
//
// Fixed profiles: colours, fog colour, fog factor and constants are codes at the
// profile's colour width (constants and fog colour are rounded to it on entry,
// choice #36: 0.5 -> 128 at 8 bits), texels are codes at the texture width; each
// enters a register as snorm_from_unorm (c = k when the widths agree, e.g. 8-bit
// codes into 9-bit registers).
#pragma once
#include <array>
#include <cstdint>

#include "pipeline/gl/enums.h"
#include "pipeline/texture/texture_object.h"

namespace ffsim::combiners {

enum Reg : std::uint8_t {
  kZero,
  kConstantColor0,
  kConstantColor1,
  kFog,
  kPrimaryColor,
  kSecondaryColor,
  kSpare0,
  kSpare1,
  kTexture0,
  kTexture1,
  kTexture2,
  kTexture3,
  kRegisterCount,
  // Final-combiner pseudo-registers (never stored in the register set).
  kETimesF = kRegisterCount,
  kSpare0PlusSecondary,
};

// Register index of a register name (or final-combiner pseudo-register); -1 if none.
int register_index(GLenum reg);
GLenum register_enum(int index);
// Short name for equations: zero, const0, const1, fog, primary, secondary, spare0,
// spare1, tex0..tex3, (e*f), (spare0+secondary).
const char* register_short_name(int index);

template <class T>
struct RegisterSet {
  T v[kRegisterCount][4];
};

// Per-fragment inputs of the combiners, as spans (struct of arrays). Colours and
// texels are RGBA, 4 values per fragment; the fog factor is 1 value per fragment.
// A nullptr means "absent": secondary colour (0,0,0,0), fog factor (fog disabled:
// FOG alpha = 1), texture unit (disabled: register undefined -> 0). Inputs the plan
// does not read (CombinerPlan::*_needed) are never touched and may be nullptr;
// the primary colour must be given when plan.primary_needed.
//
// Fixed profiles: unsigned codes (colours and fog factor at Profile::color_bits,
// texels at Profile::texture_bits). Float profiles: values in [0,1].
template <class V>
struct CombinerInputs {
  int count = 0;
  const V* primary = nullptr;
  const V* secondary = nullptr;
  const V* fog_factor = nullptr;
  std::array<const V*, 4> texture{};  // TEXTURE0_ARB .. TEXTURE3_ARB
};
using CombinerInputsFixed = CombinerInputs<std::uint16_t>;
using CombinerInputsFloat = CombinerInputs<double>;

// RC Table NV_register_combiners.2: the register's RGBA from a filtered texel with
// base format `base` whose stored components are `comp` (in the order of
// BaseFormat's comment) and whose 1.0 is `one`.
template <class V>
std::array<V, 4> texture_register_rgba(BaseFormat base, const V* comp, V one) {
  switch (base) {
    case BaseFormat::Alpha: return {V(0), V(0), V(0), comp[0]};
    case BaseFormat::Luminance: return {comp[0], comp[0], comp[0], one};
    case BaseFormat::LuminanceAlpha: return {comp[0], comp[0], comp[0], comp[1]};
    case BaseFormat::Intensity: return {comp[0], comp[0], comp[0], comp[0]};
    case BaseFormat::RGB: return {comp[0], comp[1], comp[2], one};
    case BaseFormat::RGBA: return {comp[0], comp[1], comp[2], comp[3]};
  }
  return {V(0), V(0), V(0), V(0)};
}

}  // namespace ffsim::combiners

// The fixed colour stage for 8-bit colour (M = 255) on interleaved codes: four
// pixels' R, G, B, A codes in the sixteen 16-bit lanes of an AVX2 register, every
// written channel blended at once (GL 1.2.1 §4.1.7, EXT_blend_color,
// EXT_blend_minmax, EXT_blend_subtract; docs/performance.md 22.1).
//
// The same numbers as fragment_plan.cpp's FixedKernel<255> (and blend.h's
// blend_code): each product of two codes is at most 255² = 65025 and fits a
// 16-bit lane; the sum of the two terms saturates (adds_epu16) and is clamped to
// M² as FixedKernel clamps it, a difference saturates at 0 (subs_epu16); then
// FixedKernel::finish's floor((v + 127) / 255) by shifts, which stays below 2^16
// for every v ≤ 65025. A factor M − x is x XOR 255 for a code x ≤ 255.
#pragma once
#include <cstddef>
#include <cstdint>

namespace ffsim {

struct FragmentPlanKey;

// What each lane of the four-pixel pattern computes, from a plan key (built once
// with the plan). usable is false when a channel uses a logic op (left to
// FixedKernel), for float colour, and in a build without AVX2; the key does not
// know M, so the caller takes this path only for M = 255 (color_stage_fixed<255>).
struct BlendLanes8 {
  bool usable = false;
  bool general = false;  // some lane subtracts or takes MIN / MAX (else every lane is s·S + d·D)
  // The factors as X XOR inv (inv 0 or 255 per lane), X selected by these
  // (blend_lanes8.cpp Select); constant: X is the constant colour's code.
  std::uint8_t src_select = 0, dst_select = 0;
  bool src_constant_alpha = false, dst_constant_alpha = false;  // CONSTANT_ALPHA: the code of alpha in every lane
  // One 16-bit value per channel (R, G, B, A), repeated for each pixel of the
  // register: 0xFFFF where the property holds, else 0, unless stated otherwise.
  std::uint16_t written[4]{};            // the channel is written (ChannelOp other than Keep)
  std::uint16_t src_inv[4]{}, dst_inv[4]{};  // 0x00FF: the factor is M − X
  std::uint16_t src_use[4]{};            // S is the source factor's value
  std::uint16_t src_one[4]{};            // 0x00FF: S is M (Copy, and SRC_ALPHA_SATURATE's alpha)
  std::uint16_t dst_use[4]{};            // D is the destination factor's value
  std::uint16_t sub[4]{}, revsub[4]{}, min[4]{}, max[4]{};  // the lane's equation (else s·S + d·D)
};

BlendLanes8 blend_lanes8(const FragmentPlanKey& key);

// Fragment j's codes in[4j .. 4j+3] blended into pixel first + j (rows) or
// pixel[j] (listed; distinct pixels) of `fb`, where alive[j]; n ≥ 0; kc: the
// constant colour's four codes. Requires b.usable.
void blend_lanes8_row(const BlendLanes8& b, const std::uint32_t* kc, const std::uint16_t* in, std::uint16_t* fb,
                      std::size_t first, int n, const std::uint8_t* alive);
void blend_lanes8_list(const BlendLanes8& b, const std::uint32_t* kc, const std::uint16_t* in, std::uint16_t* fb,
                       const std::uint32_t* pixel, int n, const std::uint8_t* alive);

}  // namespace ffsim

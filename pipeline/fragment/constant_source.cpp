#include "pipeline/fragment/constant_source.h"

#include <optional>

#include "pipeline/fragment/blend.h"

namespace ffsim {

namespace {

// Factor f's code for channel c when it does not read the destination (else
// none): blend_factor's value, which then cannot depend on the destination.
std::optional<std::uint32_t> factor_without_destination(GLenum f, int c, const std::uint32_t* s,
                                                        const std::uint32_t* k, std::uint32_t M) {
  switch (f) {
    case gl::DST_COLOR:
    case gl::ONE_MINUS_DST_COLOR:
    case gl::DST_ALPHA:
    case gl::ONE_MINUS_DST_ALPHA: return std::nullopt;
    case gl::SRC_ALPHA_SATURATE:  // (f, f, f, 1), f = min(A_s, 1 − A_d)
      if (c != 3) return std::nullopt;
      break;
    default: break;
  }
  static constexpr std::uint32_t kNoDestination[4] = {0, 0, 0, 0};  // (never read: see above)
  return blend_factor<std::uint32_t>(f, c, s, kNoDestination, k, M);
}

}  // namespace

bool colour_stage_keeps(const FragmentPlanKey& key, const FragmentConstants& k,
                        const std::array<std::uint32_t, 4>& source) {
  if (key.nothing) return true;
  if (key.arith != Arithmetic::Fixed) return false;
  const std::uint32_t M = k.color_max;
  for (int c = 0; c < 4; ++c) {
    const std::uint32_t s = source[static_cast<std::size_t>(c)];
    if (s > M) return false;  // (not a code of this buffer)
    switch (key.channel[static_cast<std::size_t>(c)]) {
      case ChannelOp::Keep: continue;
      case ChannelOp::Min:  // min(s, d) = d for every d
        if (s != M) return false;
        continue;
      case ChannelOp::Max:  // max(s, d) = d for every d
        if (s != 0) return false;
        continue;
      case ChannelOp::DstTerm:  // (the source factor is ZERO)
      case ChannelOp::Add:
      case ChannelOp::RevSub: {
        const auto S = factor_without_destination(key.blend_src, c, source.data(), k.blend_color_code.data(), M);
        const bool no_source_term = s == 0 || key.channel[static_cast<std::size_t>(c)] == ChannelOp::DstTerm || (S && *S == 0);
        const auto D = factor_without_destination(key.blend_dst, c, source.data(), k.blend_color_code.data(), M);
        if (!no_source_term || !D || *D != M) return false;
        continue;
      }
      default: return false;  // Zero, Copy, SrcTerm, Sub, Logic
    }
  }
  return true;
}

}  // namespace ffsim

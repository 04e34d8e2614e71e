// Texture uploads of one-byte client data (UNSIGNED_BYTE, BYTE) through a
// transfer plan that works component by component, by table (docs/performance.md
// 14.1). Each stored component of a texel is then a function of one client byte
// (or a constant): the unpacking of Table 2.6, the plan's stages and the final
// conversion of §3.8.1 applied to one component. The 256 values of that function
// are computed once per upload by running the same unpack_rgba, run_plan and
// store_texels on a 256-texel image whose texel v has every client element equal
// to the byte v; the upload then looks each texel's codes up. The same bits as
// the generic path by construction (tests/pipeline/test_byte_texels.cpp compares
// them over random plans, formats and data).
#pragma once
#include <array>
#include <cstdint>

#include "pipeline/number/profile.h"
#include "pipeline/pixel_transfer/pixel_state.h"
#include "pipeline/pixel_transfer/transfer_plan.h"
#include "pipeline/texture/texture_object.h"

namespace ffsim::pixel {

// True when every stage of the plan maps each RGBA component to itself alone:
// scale and bias, the colour maps, the colour tables (a component indexes the
// table with its own value) and the post-colour-matrix scale, bias and table
// with an identity matrix. Not: the colour matrix, a convolution.
bool plan_is_componentwise(const TransferPlan& plan);

// The tables of one upload: for stored component k of `dst`'s format, the code
// of client byte v (element[k] >= 0, the element of the client group that feeds
// it) or a constant code (element[k] = -1: table[k][0]).
struct ByteTexelTables {
  int components = 0;  // stored components per texel
  std::array<int, 4> element{-1, -1, -1, -1};
  int group_bytes = 0;  // client elements per group (one byte each)
  std::array<std::array<std::uint16_t, 256>, 4> code{};
};

// The tables for data of (format, type: UNSIGNED_BYTE or BYTE) into a level of
// dst's internal format, base and bits under a fixed profile p, through `plan`
// (plan_is_componentwise). T: the arithmetic of the generic path (float or double).
template <class T>
ByteTexelTables byte_texel_tables(GLenum format, GLenum type, const TransferPlan& plan, const TransferInputs& in,
                                  const TextureImage& dst, const Profile& p);

// The width x height client image at `data` (laid out by the unpack modes) into
// dst at storage position (x0, y0), as store_texels(run_plan(unpack_rgba(...)))
// would write it.
void store_byte_texels(const ByteTexelTables& tab, const void* data, int width, int height,
                       const PixelStoreModes& modes, TextureImage& dst, int x0, int y0);

}  // namespace ffsim::pixel

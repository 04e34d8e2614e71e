#include "pipeline/pixel_transfer/byte_texels.h"

#include <vector>

#include "pipeline/pixel_transfer/final_conversion.h"
#include "pipeline/pixel_transfer/formats.h"
#include "pipeline/pixel_transfer/unpack.h"

namespace ffsim::pixel {

bool plan_is_componentwise(const TransferPlan& plan) {
  for (const Stage s : plan.stages)
    switch (s) {
      case Stage::ScaleBias:
      case Stage::MapColor:
      case Stage::ColorTable:
      case Stage::PostColorMatrixScaleBias:
      case Stage::PostColorMatrixColorTable: continue;
      default: return false;  // the colour matrix mixes components; a convolution mixes texels
    }
  return true;
}

template <class T>
ByteTexelTables byte_texel_tables(GLenum format, GLenum type, const TransferPlan& plan, const TransferInputs& in,
                                  const TextureImage& dst, const Profile& p) {
  ByteTexelTables tab;
  const int n = color_format_components(format);
  tab.group_bytes = n;
  tab.components = component_count(dst.base);
  // Texel v: every element the byte v, one row of 256 groups (no padding at any
  // alignment: 256·n bytes).
  std::vector<unsigned char> bytes(static_cast<std::size_t>(256 * n));
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>(i / static_cast<std::size_t>(n));
  const RgbaImage<T> img = run_plan(plan, in, unpack_rgba<T>(bytes.data(), 256, 1, format, type, PixelStoreModes{}));
  TextureImage row = dst;  // the same internal format, base and bits
  row.width = 256;
  row.height = 1;
  row.border = 0;
  row.codes.assign(static_cast<std::size_t>(256 * tab.components), 0);
  row.values.clear();
  store_texels(img, row, 0, 0, p);
  for (int k = 0; k < tab.components; ++k) {
    tab.element[static_cast<std::size_t>(k)] = format_element_for(format, rgba_component_for(dst.base, k));
    for (int v = 0; v < 256; ++v)
      tab.code[static_cast<std::size_t>(k)][static_cast<std::size_t>(v)] = row.codes[static_cast<std::size_t>(v * tab.components + k)];
  }
  return tab;
}

void store_byte_texels(const ByteTexelTables& tab, const void* data, int width, int height,
                       const PixelStoreModes& modes, TextureImage& dst, int x0, int y0) {
  const ClientLayout L = client_layout(modes, width, height, tab.group_bytes, 1);
  const auto* base = static_cast<const unsigned char*>(data);
  const int nc = tab.components;
  // Every stored component the code of its own client element, in order, by an
  // identity table (an 8-bit level from UNSIGNED_BYTE data through an identity
  // transfer: c/255 stores as c): a row's codes are its bytes, widened.
  bool widen = tab.group_bytes == nc;
  for (std::size_t k = 0; k < static_cast<std::size_t>(nc) && widen; ++k) {
    widen = tab.element[k] == static_cast<int>(k);
    for (int v = 0; v < 256 && widen; ++v) widen = tab.code[k][static_cast<std::size_t>(v)] == v;
  }
  const std::size_t row_codes = static_cast<std::size_t>(width) * static_cast<std::size_t>(nc);
  for (int y = 0; y < height; ++y) {
    const unsigned char* g = base + L.offset(0, y);
    std::uint16_t* out = dst.codes.data() + (static_cast<std::size_t>(y0 + y) * static_cast<std::size_t>(dst.width) +
                                             static_cast<std::size_t>(x0)) * static_cast<std::size_t>(nc);
    if (widen) {
      for (std::size_t i = 0; i < row_codes; ++i) out[i] = g[i];
      continue;
    }
    for (int k = 0; k < nc; ++k) {
      const auto& code = tab.code[static_cast<std::size_t>(k)];
      const int e = tab.element[static_cast<std::size_t>(k)];
      if (e < 0) {  // a constant component
        for (int x = 0; x < width; ++x) out[static_cast<std::size_t>(x * nc + k)] = code[0];
        continue;
      }
      const unsigned char* src = g + e;
      const int step = tab.group_bytes;
      for (int x = 0; x < width; ++x) out[static_cast<std::size_t>(x * nc + k)] = code[src[x * step]];
    }
  }
}

template ByteTexelTables byte_texel_tables<float>(GLenum, GLenum, const TransferPlan&, const TransferInputs&,
                                                  const TextureImage&, const Profile&);
template ByteTexelTables byte_texel_tables<double>(GLenum, GLenum, const TransferPlan&, const TransferInputs&,
                                                   const TextureImage&, const Profile&);

}  // namespace ffsim::pixel

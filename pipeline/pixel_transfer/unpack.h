// Unpacking client images into RGBA groups and packing groups back (GL121
// §3.6.4 "Unpacking", "Conversion to floating-point", "Conversion to RGB",
// "Final Expansion to RGBA"; §4.3.2 "Final Conversion", Table 4.7 for packing),
// with the pixel store modes ALIGNMENT, ROW_LENGTH, SKIP_PIXELS, SKIP_ROWS and
// SWAP_BYTES.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "pipeline/gl/enums.h"
#include "pipeline/pixel_transfer/pixel_image.h"
#include "pipeline/pixel_transfer/pixel_state.h"

namespace ffsim::pixel {

// Where the groups of a width x height image of `components` elements of
// `elem_size` bytes lie in client memory (GL121 §3.6.4, eq. 3.11 and the skip
// rules): byte offset of group (col, row).
struct ClientLayout {
  std::size_t row_stride = 0;  // bytes from one row to the next
  std::size_t first = 0;       // byte offset of group (0, 0)
  int group_bytes = 0;
  int elem_size = 0;
  std::size_t offset(int col, int row) const {
    return first + static_cast<std::size_t>(row) * row_stride + static_cast<std::size_t>(col) * group_bytes;
  }
  // Bytes the client array must hold (offset of the last byte + 1).
  std::size_t extent(int width, int height) const;
};
ClientLayout client_layout(const PixelStoreModes& modes, int width, int height, int components, int elem_size);

// Colour data -> RGBA groups (format: a colour format of formats.h; type: an
// element type of formats.h). Integer elements become c/(2^b-1) (unsigned) or
// (2c+1)/(2^b-1) (signed), Table 2.6, computed in T; FLOAT elements are taken as
// binary32 values converted to T. Missing R, G, B are 0 and missing A is 1;
// LUMINANCE copies L to R, G, B.
template <class T>
RgbaImage<T> unpack_rgba(const void* data, int width, int height, GLenum format, GLenum type,
                         const PixelStoreModes& modes);

// The client element (0-based, within a group of `format`) that fills RGBA
// component `rgba` when unpacking (LUMINANCE's element fills R, G and B), or -1
// when none does (the component is then the constant 0, or 1 for A).
int format_element_for(GLenum format, int rgba);

// One-component data (STENCIL_INDEX, DEPTH_COMPONENT). Stencil: integer values
// (FLOAT elements rounded half up, negative -> 0 after rounding); depth: [0,1]
// conversion as for colour elements.
std::vector<std::int64_t> unpack_indices(const void* data, int width, int height, GLenum type,
                                         const PixelStoreModes& modes);
template <class T>
std::vector<T> unpack_depth(const void* data, int width, int height, GLenum type, const PixelStoreModes& modes);

// RGBA groups -> client data for glReadPixels (GL121 §4.3.2): LUMINANCE is
// R + G + B; each component is clamped to [0,1] and converted by Table 4.7 with
// round half up on the exact value (docs/numerics.md §7).
template <class T>
void pack_rgba(const RgbaImage<T>& img, GLenum format, GLenum type, const PixelStoreModes& modes, void* data);
// Integer (stencil) values and [0,1] (depth) values into client data.
void pack_indices(const std::vector<std::uint32_t>& v, int width, int height, GLenum type,
                  const PixelStoreModes& modes, void* data);
void pack_depth(const std::vector<double>& v, int width, int height, GLenum type, const PixelStoreModes& modes,
                void* data);

// Exact conversions of f in [0,1] (clamped first; NaN -> 0) to the unsigned
// (round(f*(2^b-1))) and signed (round(((2^b-1)f - 1)/2)) integers of Table 4.7,
// b = 8, 16 or 32, rounding half up on the exact value.
std::uint32_t pack_unsigned(double f, int bits);
std::int32_t pack_signed(double f, int bits);

}  // namespace ffsim::pixel

// Client pixel formats and types (GL121 Tables 3.5, 3.6) and internal formats
// (Tables 3.15, 3.16) as the pixel path accepts them.
#pragma once
#include <array>
#include <optional>

#include "pipeline/gl/enums.h"
#include "pipeline/texture/texture_object.h"

namespace ffsim::pixel {

// Colour formats of client data: RED, GREEN, BLUE, ALPHA, RGB, RGBA, LUMINANCE,
// LUMINANCE_ALPHA, BGR, BGRA. Returns the number of elements per group, 0 if the
// enum is not one of them.
int color_format_components(GLenum format);
// Element types ffsim unpacks and packs: UNSIGNED_BYTE, BYTE, UNSIGNED_SHORT,
// SHORT, UNSIGNED_INT, INT, FLOAT. Size in bytes, 0 otherwise.
int type_size(GLenum type);
// GL 1.2 pixel types that exist but ffsim does not take (BITMAP and the packed
// UNSIGNED_BYTE_3_3_2 ... UNSIGNED_INT_2_10_10_10_REV types).
bool is_unsupported_gl_type(GLenum type);

// An internal format (texture, colour table or convolution filter): base format
// and, for sized formats, the component widths requested (GL121 Table 3.16).
// TextureImage has one width per image, so mixed-width sized formats (RGB5_A1,
// RGB10_A2, R3_G3_B2, LUMINANCE6_ALPHA2, LUMINANCE12_ALPHA4) are stored at the
// least common multiple of their widths: each component is rounded at its own
// width and then represented exactly at the storage width (k * (2^L-1)/(2^n-1) is
// an integer when n divides L), e.g. RGB5_A1 stores alpha 0/1 as 0/31 in 5 bits.
struct InternalFormat {
  BaseFormat base = BaseFormat::RGBA;
  int sized_bits = 0;  // storage width; 0: unsized (the profile's texture_bits apply)
  std::array<int, 4> component_bits{0, 0, 0, 0};  // per stored component; 0: sized_bits
};
// Texture internal formats: 1, 2, 3, 4, the six base formats and the sized ones.
std::optional<InternalFormat> texture_internal_format(GLenum internal_format);
// Colour-table and convolution-filter internal formats: the base and sized
// formats (not the legacy 1..4).
std::optional<InternalFormat> table_internal_format(GLenum internal_format);

}  // namespace ffsim::pixel

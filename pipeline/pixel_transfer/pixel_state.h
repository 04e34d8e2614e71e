// GL state of the pixel path (GL121 §3.6 with the imaging subset): pixel store
// modes, pixel transfer modes, pixel maps, colour tables, convolution filters and
// pixel zoom. Plain data; the stages in this directory are functions of it.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "pipeline/gl/enums.h"
#include "pipeline/texture/texture_object.h"

namespace ffsim::pixel {

// Implementation limits (docs/numerics.md §7).
inline constexpr int kMaxPixelMapTable = 256;        // MAX_PIXEL_MAP_TABLE (GL121 minimum 32; Mesa 256)
inline constexpr int kMaxColorTableWidth = 4096;     // largest colour-table width accepted
inline constexpr int kMaxConvolutionWidth = 9;       // MAX_CONVOLUTION_WIDTH (minimum 3; Mesa 9)
inline constexpr int kMaxConvolutionHeight = 9;      // MAX_CONVOLUTION_HEIGHT
inline constexpr int kMaxTextureSize = 2048;         // MAX_TEXTURE_SIZE of the pixel path (GeForce 256: 2048)

// glPixelStore (GL121 Table 3.1 unpack, Table 4.5 pack); initial values.
struct PixelStoreModes {
  bool swap_bytes = false;
  bool lsb_first = false;  // only meaningful for BITMAP data, which ffsim does not take
  int row_length = 0;
  int skip_rows = 0;
  int skip_pixels = 0;
  int alignment = 4;
};
struct PixelStoreState {
  PixelStoreModes unpack;
  PixelStoreModes pack;
};

// glPixelTransfer and glPixelMap (GL121 Table 3.2, 3.3; imaging subset). Values
// are kept in binary64 as given; the stages round them to the evaluation precision.
struct PixelTransferState {
  bool map_color = false;
  bool map_stencil = false;
  int index_shift = 0;
  int index_offset = 0;
  std::array<double, 4> scale{1, 1, 1, 1};  // RED_SCALE .. ALPHA_SCALE
  std::array<double, 4> bias{0, 0, 0, 0};   // RED_BIAS .. ALPHA_BIAS
  double depth_scale = 1, depth_bias = 0;
  std::array<double, 4> post_convolution_scale{1, 1, 1, 1};
  std::array<double, 4> post_convolution_bias{0, 0, 0, 0};
  std::array<double, 4> post_color_matrix_scale{1, 1, 1, 1};
  std::array<double, 4> post_color_matrix_bias{0, 0, 0, 0};
  // PIXEL_MAP_R_TO_R, G_TO_G, B_TO_B, A_TO_A: initial size 1, entry 0 (Table 3.3).
  std::array<std::vector<double>, 4> color_maps{std::vector<double>{0.0}, std::vector<double>{0.0},
                                                std::vector<double>{0.0}, std::vector<double>{0.0}};
  std::vector<std::uint32_t> stencil_map{0};  // PIXEL_MAP_S_TO_S
};

// The three colour tables of the imaging subset, in pipeline order.
enum class TableSlot { Color = 0, PostConvolution = 1, PostColorMatrix = 2 };

struct ColorTable {
  bool enabled = false;
  GLenum internal_format = gl::RGBA;
  BaseFormat base = BaseFormat::RGBA;
  int width = 0;  // 0: the table does nothing
  // component_count(base) values per entry, in TextureImage order (A; L; L,A; I;
  // R,G,B; R,G,B,A), each clamp01(c * scale + bias) at the evaluation precision.
  std::vector<double> entries;
  std::array<double, 4> scale{1, 1, 1, 1};  // COLOR_TABLE_SCALE
  std::array<double, 4> bias{0, 0, 0, 0};   // COLOR_TABLE_BIAS
};

enum class BorderMode { Reduce, ConstantBorder, ReplicateBorder };

// A convolution filter (CONVOLUTION_1D, CONVOLUTION_2D or SEPARABLE_2D).
struct ConvolutionFilter {
  bool enabled = false;
  GLenum internal_format = gl::RGBA;
  BaseFormat base = BaseFormat::RGBA;
  int width = 0;   // 0 until specified
  int height = 0;  // 1 for CONVOLUTION_1D
  // Taps expanded to R, G, B, A slots (L -> R,G,B; I -> R,G,B,A), 4 per tap,
  // row-major from row 0; unused slots are 0. For SEPARABLE_2D: `row` has width
  // taps, `column` has height taps, `taps` is unused.
  std::vector<double> taps, row, column;
  BorderMode border_mode = BorderMode::Reduce;
  std::array<double, 4> border_color{0, 0, 0, 0};  // CONVOLUTION_BORDER_COLOR, not clamped
  std::array<double, 4> filter_scale{1, 1, 1, 1};  // CONVOLUTION_FILTER_SCALE
  std::array<double, 4> filter_bias{0, 0, 0, 0};   // CONVOLUTION_FILTER_BIAS
};

struct ImagingState {
  std::array<ColorTable, 3> tables;  // indexed by TableSlot
  ConvolutionFilter conv1d, conv2d, separable2d;
  ColorTable& table(TableSlot s) { return tables[static_cast<int>(s)]; }
  const ColorTable& table(TableSlot s) const { return tables[static_cast<int>(s)]; }
};

// Which components a base format carries in R, G, B, A terms (GL121 Table 3.15
// for textures and colour tables, Table 3.14 for convolution filters):
// ALPHA: A; LUMINANCE: R,G,B (from L); LUMINANCE_ALPHA: R,G,B,A; INTENSITY:
// R,G,B,A (from I); RGB: R,G,B; RGBA: R,G,B,A.
constexpr std::array<bool, 4> replaced_components(BaseFormat f) {
  switch (f) {
    case BaseFormat::Alpha: return {false, false, false, true};
    case BaseFormat::Luminance: return {true, true, true, false};
    case BaseFormat::LuminanceAlpha: return {true, true, true, true};
    case BaseFormat::Intensity: return {true, true, true, true};
    case BaseFormat::RGB: return {true, true, true, false};
    case BaseFormat::RGBA: return {true, true, true, true};
  }
  return {true, true, true, true};
}

// For RGBA component c (0..3), the index of the stored component of base format
// f that supplies it, or -1 when f leaves c alone.
constexpr int source_component(BaseFormat f, int c) {
  switch (f) {
    case BaseFormat::Alpha: return c == 3 ? 0 : -1;
    case BaseFormat::Luminance: return c < 3 ? 0 : -1;
    case BaseFormat::LuminanceAlpha: return c < 3 ? 0 : 1;
    case BaseFormat::Intensity: return 0;
    case BaseFormat::RGB: return c < 3 ? c : -1;
    case BaseFormat::RGBA: return c;
  }
  return -1;
}

// For stored component k of base format f, the RGBA component it is taken from
// when an RGBA group is converted to f (GL121 §3.8.1 Table 3.15): L and I from R.
constexpr int rgba_component_for(BaseFormat f, int k) {
  switch (f) {
    case BaseFormat::Alpha: return 3;
    case BaseFormat::Luminance: return 0;
    case BaseFormat::LuminanceAlpha: return k == 0 ? 0 : 3;
    case BaseFormat::Intensity: return 0;
    case BaseFormat::RGB: return k;
    case BaseFormat::RGBA: return k;
  }
  return k;
}

}  // namespace ffsim::pixel

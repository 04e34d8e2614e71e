// Pixel-path state: glPixelStore, glPixelTransfer, glPixelMap, glPixelZoom,
// colour tables and convolution filters (GL121 §3.6.1-3.6.3 with the imaging
// subset), the pixel-path enables, and the helpers shared by the pixel
// rectangle and texture image calls (reading the framebuffer, running the plan).
#include <algorithm>
#include <cmath>

#include "pipeline/gl/enum_names.h"
#include "pipeline/pixel_transfer/color_table.h"
#include "pipeline/pixel_transfer/convolution.h"
#include "pipeline/pixel_transfer/formats.h"
#include "pipeline/pixel_transfer/unpack.h"
#include "sim/context.h"

namespace ffsim {

using pixel::RgbaImage;

namespace {
bool is_pow2(long long v) { return v > 0 && (v & (v - 1)) == 0; }
// Integer pixel-transfer parameters given as reals: rounded half up, limited to
// [-limit, limit] (INDEX_SHIFT: 31, INDEX_OFFSET: 2e9), NaN -> 0.
int round_int(double v, double limit) {
  const double r = std::floor(v + 0.5);
  return std::isnan(r) ? 0 : static_cast<int>(std::clamp(r, -limit, limit));
}
}  // namespace

// ---- enables ---------------------------------------------------------------

bool Context::pixel_capability(GLenum cap, bool on) {
  switch (cap) {
    case gl::COLOR_TABLE: imaging_.table(pixel::TableSlot::Color).enabled = on; return true;
    case gl::POST_CONVOLUTION_COLOR_TABLE: imaging_.table(pixel::TableSlot::PostConvolution).enabled = on; return true;
    case gl::POST_COLOR_MATRIX_COLOR_TABLE: imaging_.table(pixel::TableSlot::PostColorMatrix).enabled = on; return true;
    case gl::CONVOLUTION_1D: imaging_.conv1d.enabled = on; return true;
    case gl::CONVOLUTION_2D: imaging_.conv2d.enabled = on; return true;
    case gl::SEPARABLE_2D: imaging_.separable2d.enabled = on; return true;
    default: return false;
  }
}

int Context::pixel_is_enabled(GLenum cap) const {
  switch (cap) {
    case gl::COLOR_TABLE: return imaging_.table(pixel::TableSlot::Color).enabled;
    case gl::POST_CONVOLUTION_COLOR_TABLE: return imaging_.table(pixel::TableSlot::PostConvolution).enabled;
    case gl::POST_COLOR_MATRIX_COLOR_TABLE: return imaging_.table(pixel::TableSlot::PostColorMatrix).enabled;
    case gl::CONVOLUTION_1D: return imaging_.conv1d.enabled;
    case gl::CONVOLUTION_2D: return imaging_.conv2d.enabled;
    case gl::SEPARABLE_2D: return imaging_.separable2d.enabled;
    default: return -1;
  }
}

// ---- glPixelStore (§3.6.1, Table 3.1; §4.3.2 Table 4.5) ----------------------

void Context::pixelStorei(GLenum pname, std::int64_t param) {
  if (reject_in_begin("glPixelStorei")) return;
  static const char* fn = "glPixelStore";
  pixel::PixelStoreModes* m = nullptr;
  switch (pname) {
    case gl::UNPACK_SWAP_BYTES: case gl::UNPACK_LSB_FIRST: case gl::UNPACK_ROW_LENGTH:
    case gl::UNPACK_SKIP_ROWS: case gl::UNPACK_SKIP_PIXELS: case gl::UNPACK_ALIGNMENT:
      m = &pixel_store_.unpack; break;
    case gl::PACK_SWAP_BYTES: case gl::PACK_LSB_FIRST: case gl::PACK_ROW_LENGTH:
    case gl::PACK_SKIP_ROWS: case gl::PACK_SKIP_PIXELS: case gl::PACK_ALIGNMENT:
      m = &pixel_store_.pack; break;
    default:
      error(gl::INVALID_ENUM, fn, gl::enum_name(pname) + " is not a pixel store parameter");
      return;
  }
  const GLenum base = m == &pixel_store_.unpack ? gl::UNPACK_SWAP_BYTES : gl::PACK_SWAP_BYTES;
  const GLenum k = pname - base;  // 0 swap, 1 lsb, 2 row length, 3 skip rows, 4 skip pixels, 5 alignment
  if (k >= 2 && k <= 4 && (param < 0 || param > 1000000000)) {
    error(gl::INVALID_VALUE, fn, gl::enum_name(pname) + " must not be negative (got " + std::to_string(param) + ")");
    return;
  }
  switch (k) {
    case 0: m->swap_bytes = param != 0; break;
    case 1: m->lsb_first = param != 0; break;
    case 2: m->row_length = static_cast<int>(param); break;
    case 3: m->skip_rows = static_cast<int>(param); break;
    case 4: m->skip_pixels = static_cast<int>(param); break;
    default:
      if (param != 1 && param != 2 && param != 4 && param != 8) {
        error(gl::INVALID_VALUE, fn, gl::enum_name(pname) + " must be 1, 2, 4 or 8 (got " + std::to_string(param) + ")");
        return;
      }
      m->alignment = static_cast<int>(param);
  }
}

void Context::pixelStoref(GLenum pname, double param) {
  if (reject_in_begin("glPixelStoref")) return;
  // §3.6.1: boolean parameters are false iff param is 0; integer ones are rounded.
  if (pname == gl::UNPACK_SWAP_BYTES || pname == gl::UNPACK_LSB_FIRST || pname == gl::PACK_SWAP_BYTES ||
      pname == gl::PACK_LSB_FIRST) {
    pixelStorei(pname, param != 0.0 ? 1 : 0);
    return;
  }
  const double r = std::floor(param + 0.5);
  pixelStorei(pname, std::isfinite(r) ? static_cast<std::int64_t>(std::clamp(r, -2e9, 2e9)) : -1);
}

// ---- glPixelTransfer (§3.6.3, Table 3.2; imaging subset) ---------------------

void Context::pixelTransferf(GLenum pname, double v) {
  if (reject_in_begin("glPixelTransferf")) return;
  pixel::PixelTransferState& t = pixel_transfer_;
  switch (pname) {
    case gl::MAP_COLOR: t.map_color = v != 0.0; return;
    case gl::MAP_STENCIL: t.map_stencil = v != 0.0; return;
    case gl::INDEX_SHIFT: t.index_shift = round_int(v, 31); return;
    case gl::INDEX_OFFSET: t.index_offset = round_int(v, 2e9); return;
    case gl::RED_SCALE: t.scale[0] = v; return;
    case gl::GREEN_SCALE: t.scale[1] = v; return;
    case gl::BLUE_SCALE: t.scale[2] = v; return;
    case gl::ALPHA_SCALE: t.scale[3] = v; return;
    case gl::RED_BIAS: t.bias[0] = v; return;
    case gl::GREEN_BIAS: t.bias[1] = v; return;
    case gl::BLUE_BIAS: t.bias[2] = v; return;
    case gl::ALPHA_BIAS: t.bias[3] = v; return;
    case gl::DEPTH_SCALE: t.depth_scale = v; return;
    case gl::DEPTH_BIAS: t.depth_bias = v; return;
    default: break;
  }
  if (pname >= gl::POST_CONVOLUTION_RED_SCALE && pname <= gl::POST_CONVOLUTION_ALPHA_SCALE) {
    t.post_convolution_scale[pname - gl::POST_CONVOLUTION_RED_SCALE] = v;
  } else if (pname >= gl::POST_CONVOLUTION_RED_BIAS && pname <= gl::POST_CONVOLUTION_ALPHA_BIAS) {
    t.post_convolution_bias[pname - gl::POST_CONVOLUTION_RED_BIAS] = v;
  } else if (pname >= gl::POST_COLOR_MATRIX_RED_SCALE && pname <= gl::POST_COLOR_MATRIX_ALPHA_SCALE) {
    t.post_color_matrix_scale[pname - gl::POST_COLOR_MATRIX_RED_SCALE] = v;
  } else if (pname >= gl::POST_COLOR_MATRIX_RED_BIAS && pname <= gl::POST_COLOR_MATRIX_ALPHA_BIAS) {
    t.post_color_matrix_bias[pname - gl::POST_COLOR_MATRIX_RED_BIAS] = v;
  } else {
    error(gl::INVALID_ENUM, "glPixelTransfer", gl::enum_name(pname) + " is not a pixel transfer parameter");
  }
}

void Context::pixelTransferi(GLenum pname, std::int64_t param) {
  if (reject_in_begin("glPixelTransferi")) return;
  pixelTransferf(pname, static_cast<double>(param));
}

// ---- glPixelMap (§3.6.3, Table 3.3) -------------------------------------------

void Context::pixelMapfv(GLenum map, int mapsize, const double* values) {
  if (reject_in_begin("glPixelMapfv")) return;
  static const char* fn = "glPixelMapfv";
  const bool color = map >= gl::PIXEL_MAP_R_TO_R && map <= gl::PIXEL_MAP_A_TO_A;
  const bool index = map == gl::PIXEL_MAP_S_TO_S || map == gl::PIXEL_MAP_I_TO_I ||
                     (map >= gl::PIXEL_MAP_I_TO_R && map <= gl::PIXEL_MAP_I_TO_A);
  if (!color && !index) {
    error(gl::INVALID_ENUM, fn, gl::enum_name(map) + " is not a pixel map");
    return;
  }
  if (mapsize < 1 || mapsize > pixel::kMaxPixelMapTable) {
    error(gl::INVALID_VALUE, fn, "mapsize must be 1.." + std::to_string(pixel::kMaxPixelMapTable) + " (got " +
                                     std::to_string(mapsize) + ")");
    return;
  }
  if (index && !is_pow2(mapsize)) {
    error(gl::INVALID_VALUE, fn, "mapsize of " + gl::enum_name(map) + " must be a power of two (got " +
                                     std::to_string(mapsize) + ")");
    return;
  }
  if (color) {
    // Colour map entries are clamped to [0,1] when specified (M6 main/pixel.c store_pixelmap).
    std::vector<double> e(static_cast<std::size_t>(mapsize));
    for (int i = 0; i < mapsize; ++i) e[i] = pixel::clamp01(values[i]);
    pixel_transfer_.color_maps[map - gl::PIXEL_MAP_R_TO_R] = std::move(e);
  } else if (map == gl::PIXEL_MAP_S_TO_S) {
    std::vector<std::uint32_t> e(static_cast<std::size_t>(mapsize));
    for (int i = 0; i < mapsize; ++i) {
      const double r = std::floor(values[i] + 0.5);  // index entries rounded to integers
      e[i] = !(r > 0) ? 0u : (r > 4294967295.0 ? 0xFFFFFFFFu : static_cast<std::uint32_t>(r));
    }
    pixel_transfer_.stencil_map = std::move(e);
  } else {
    error(gl::INVALID_OPERATION, fn, gl::enum_name(map) + " maps colour indices; ffsim has no colour-index data path");
  }
}

void Context::pixelZoom(double xfactor, double yfactor) {
  if (reject_in_begin("glPixelZoom")) return;
  pixel_zoom_ = {xfactor, yfactor};
}

// ---- colour tables (§3.6.3 "Color Table Specification") ---------------------

namespace {
int table_slot(GLenum target) {
  switch (target) {
    case gl::COLOR_TABLE: return 0;
    case gl::POST_CONVOLUTION_COLOR_TABLE: return 1;
    case gl::POST_COLOR_MATRIX_COLOR_TABLE: return 2;
    default: return -1;
  }
}
}  // namespace

template <class T>
void Context::color_table(const char* fn, GLenum target, GLenum internalformat, int width, GLenum format,
                          GLenum type, const void* data, const int* copy_xy) {
  const int slot = table_slot(target);
  if (slot < 0) {
    error(gl::INVALID_ENUM, fn, gl::enum_name(target) + " is not a colour table target");
    return;
  }
  const auto f = pixel::table_internal_format(internalformat);
  if (!f) {
    error(gl::INVALID_ENUM, fn, gl::enum_name(internalformat) + " is not a colour table internal format");
    return;
  }
  if (width < 0 || (width != 0 && !is_pow2(width))) {
    error(gl::INVALID_VALUE, fn, "width must be 0 or a power of two (got " + std::to_string(width) + ")");
    return;
  }
  if (!copy_xy) {
    if (pixel::color_format_components(format) == 0) {
      error(gl::INVALID_ENUM, fn, gl::enum_name(format) + " is not a colour format");
      return;
    }
    if (pixel::type_size(type) == 0) {
      error(gl::INVALID_ENUM, fn, gl::enum_name(type) + " is not a pixel type ffsim takes");
      return;
    }
  }
  if (width > pixel::kMaxColorTableWidth) {
    error(gl::TABLE_TOO_LARGE, fn, "width " + std::to_string(width) + " exceeds " +
                                       std::to_string(pixel::kMaxColorTableWidth));
    return;
  }
  if (!copy_xy && width > 0 && !data) {
    error(gl::INVALID_VALUE, fn, "no table data");
    return;
  }
  pixel::ColorTable& t = imaging_.tables[slot];
  RgbaImage<T> groups = copy_xy ? read_color_rect<T>(copy_xy[0], copy_xy[1], width, 1)
                                : pixel::unpack_rgba<T>(data, width, 1, format, type, pixel_store_.unpack);
  // CopyColorTable reads the framebuffer as CopyPixels would and, like
  // ColorTable, stops after the expansion to RGBA: no transfer operations are
  // applied to table data (GL121 §3.6.3; docs/numerics.md §7).
  t.internal_format = internalformat;
  t.base = f->base;
  t.width = width;
  pixel::set_table_entries(t, groups);
}

void Context::colorTable(GLenum target, GLenum internalformat, int width, GLenum format, GLenum type,
                         const void* data) {
  if (reject_in_begin("glColorTable")) return;
  if (profile_.arithmetic == Arithmetic::Float64)
    color_table<double>("glColorTable", target, internalformat, width, format, type, data, nullptr);
  else
    color_table<float>("glColorTable", target, internalformat, width, format, type, data, nullptr);
}

void Context::copyColorTable(GLenum target, GLenum internalformat, int x, int y, int width) {
  if (reject_in_begin("glCopyColorTable")) return;
  const int xy[2] = {x, y};
  if (profile_.arithmetic == Arithmetic::Float64)
    color_table<double>("glCopyColorTable", target, internalformat, width, 0, 0, nullptr, xy);
  else
    color_table<float>("glCopyColorTable", target, internalformat, width, 0, 0, nullptr, xy);
}

void Context::colorTableParameterfv(GLenum target, GLenum pname, const double params[4]) {
  if (reject_in_begin("glColorTableParameterfv")) return;
  static const char* fn = "glColorTableParameterfv";
  const int slot = table_slot(target);
  if (slot < 0) {
    error(gl::INVALID_ENUM, fn, gl::enum_name(target) + " is not a colour table target");
    return;
  }
  pixel::ColorTable& t = imaging_.tables[slot];
  if (pname == gl::COLOR_TABLE_SCALE) t.scale = {params[0], params[1], params[2], params[3]};
  else if (pname == gl::COLOR_TABLE_BIAS) t.bias = {params[0], params[1], params[2], params[3]};
  else error(gl::INVALID_ENUM, fn, gl::enum_name(pname) + " is not COLOR_TABLE_SCALE or COLOR_TABLE_BIAS");
}

// ---- convolution filters (§3.6.3 "Convolution Filter Specification") --------

pixel::ConvolutionFilter* Context::convolution_target(GLenum target) {
  switch (target) {
    case gl::CONVOLUTION_1D: return &imaging_.conv1d;
    case gl::CONVOLUTION_2D: return &imaging_.conv2d;
    case gl::SEPARABLE_2D: return &imaging_.separable2d;
    default: return nullptr;
  }
}

template <class T>
void Context::convolution_filter(const char* fn, pixel::FilterKind kind, GLenum target, GLenum internalformat,
                                 int width, int height, GLenum format, GLenum type, const void* data,
                                 const void* column) {
  const GLenum want = kind == pixel::FilterKind::OneD   ? gl::CONVOLUTION_1D
                      : kind == pixel::FilterKind::TwoD ? gl::CONVOLUTION_2D
                                                        : gl::SEPARABLE_2D;
  if (target != want) {
    error(gl::INVALID_ENUM, fn, "target must be " + gl::enum_name(want) + " (got " + gl::enum_name(target) + ")");
    return;
  }
  const auto f = pixel::table_internal_format(internalformat);
  if (!f) {
    error(gl::INVALID_ENUM, fn, gl::enum_name(internalformat) + " is not a convolution filter internal format");
    return;
  }
  if (width < 0 || width > pixel::kMaxConvolutionWidth) {
    error(gl::INVALID_VALUE, fn, "width must be 0.." + std::to_string(pixel::kMaxConvolutionWidth) + " (got " +
                                     std::to_string(width) + ")");
    return;
  }
  if (height < 0 || height > pixel::kMaxConvolutionHeight) {
    error(gl::INVALID_VALUE, fn, "height must be 0.." + std::to_string(pixel::kMaxConvolutionHeight) + " (got " +
                                     std::to_string(height) + ")");
    return;
  }
  if (pixel::color_format_components(format) == 0) {
    error(gl::INVALID_ENUM, fn, gl::enum_name(format) + " is not a colour format");
    return;
  }
  if (pixel::type_size(type) == 0) {
    error(gl::INVALID_ENUM, fn, gl::enum_name(type) + " is not a pixel type ffsim takes");
    return;
  }
  if ((width > 0 && height > 0 && !data) || (kind == pixel::FilterKind::Separable && height > 0 && !column)) {
    error(gl::INVALID_VALUE, fn, "no filter data");
    return;
  }
  pixel::ConvolutionFilter& cf = *convolution_target(target);
  cf.internal_format = internalformat;
  cf.base = f->base;
  cf.width = width;
  cf.height = kind == pixel::FilterKind::OneD ? 1 : height;
  const auto round = [&](std::vector<double> v) {
    for (double& x : v) x = pixel::to_precision(x, pixel::precision_for(profile_.arithmetic));
    return v;
  };
  if (kind == pixel::FilterKind::Separable) {
    cf.row = round(pixel::make_filter_taps(pixel::unpack_rgba<T>(data, width, 1, format, type, pixel_store_.unpack), cf));
    cf.column =
        round(pixel::make_filter_taps(pixel::unpack_rgba<T>(column, height, 1, format, type, pixel_store_.unpack), cf));
  } else {
    cf.taps = round(
        pixel::make_filter_taps(pixel::unpack_rgba<T>(data, width, cf.height, format, type, pixel_store_.unpack), cf));
  }
  if (width == 0 || cf.height == 0) cf.width = 0;  // an empty filter convolves nothing
}

void Context::convolutionFilter1D(GLenum target, GLenum internalformat, int width, GLenum format, GLenum type,
                                  const void* data) {
  if (reject_in_begin("glConvolutionFilter1D")) return;
  if (profile_.arithmetic == Arithmetic::Float64)
    convolution_filter<double>("glConvolutionFilter1D", pixel::FilterKind::OneD, target, internalformat, width, 1,
                               format, type, data, nullptr);
  else
    convolution_filter<float>("glConvolutionFilter1D", pixel::FilterKind::OneD, target, internalformat, width, 1,
                              format, type, data, nullptr);
}

void Context::convolutionFilter2D(GLenum target, GLenum internalformat, int width, int height, GLenum format,
                                  GLenum type, const void* data) {
  if (reject_in_begin("glConvolutionFilter2D")) return;
  if (profile_.arithmetic == Arithmetic::Float64)
    convolution_filter<double>("glConvolutionFilter2D", pixel::FilterKind::TwoD, target, internalformat, width,
                               height, format, type, data, nullptr);
  else
    convolution_filter<float>("glConvolutionFilter2D", pixel::FilterKind::TwoD, target, internalformat, width,
                              height, format, type, data, nullptr);
}

void Context::separableFilter2D(GLenum target, GLenum internalformat, int width, int height, GLenum format,
                                GLenum type, const void* row, const void* column) {
  if (reject_in_begin("glSeparableFilter2D")) return;
  if (profile_.arithmetic == Arithmetic::Float64)
    convolution_filter<double>("glSeparableFilter2D", pixel::FilterKind::Separable, target, internalformat, width,
                               height, format, type, row, column);
  else
    convolution_filter<float>("glSeparableFilter2D", pixel::FilterKind::Separable, target, internalformat, width,
                              height, format, type, row, column);
}

void Context::convolutionParameteri(GLenum target, GLenum pname, std::int64_t param) {
  if (reject_in_begin("glConvolutionParameteri")) return;
  static const char* fn = "glConvolutionParameteri";
  pixel::ConvolutionFilter* f = convolution_target(target);
  if (!f) {
    error(gl::INVALID_ENUM, fn, gl::enum_name(target) + " is not a convolution target");
    return;
  }
  if (pname != gl::CONVOLUTION_BORDER_MODE) {
    error(gl::INVALID_ENUM, fn, gl::enum_name(pname) + " is not CONVOLUTION_BORDER_MODE");
    return;
  }
  switch (static_cast<GLenum>(param)) {
    case gl::REDUCE: f->border_mode = pixel::BorderMode::Reduce; return;
    case gl::CONSTANT_BORDER: f->border_mode = pixel::BorderMode::ConstantBorder; return;
    case gl::REPLICATE_BORDER: f->border_mode = pixel::BorderMode::ReplicateBorder; return;
    default:
      error(gl::INVALID_ENUM, fn, gl::enum_name(static_cast<GLenum>(param)) + " is not a convolution border mode");
  }
}

void Context::convolutionParameterfv(GLenum target, GLenum pname, const double params[4]) {
  if (reject_in_begin("glConvolutionParameterfv")) return;
  static const char* fn = "glConvolutionParameterfv";
  pixel::ConvolutionFilter* f = convolution_target(target);
  if (!f) {
    error(gl::INVALID_ENUM, fn, gl::enum_name(target) + " is not a convolution target");
    return;
  }
  const std::array<double, 4> v{params[0], params[1], params[2], params[3]};
  switch (pname) {
    case gl::CONVOLUTION_BORDER_MODE: {
      const double r = params[0];
      convolutionParameteri(target, pname, std::isfinite(r) ? static_cast<std::int64_t>(r) : 0);
      return;
    }
    case gl::CONVOLUTION_BORDER_COLOR: f->border_color = v; return;
    case gl::CONVOLUTION_FILTER_SCALE: f->filter_scale = v; return;
    case gl::CONVOLUTION_FILTER_BIAS: f->filter_bias = v; return;
    default: error(gl::INVALID_ENUM, fn, gl::enum_name(pname) + " is not a convolution parameter");
  }
}

// ---- shared helpers ------------------------------------------------------------

pixel::TransferInputs Context::transfer_inputs() const {
  pixel::Matrix4 m{};
  const glm::dmat4& c = color_matrix_.top();
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row) m[4 * col + row] = c[col][row];
  return pixel::TransferInputs{pixel_transfer_, imaging_, m};
}

pixel::TransferPlan Context::transfer_plan(pixel::ImageDims dims) const {
  return pixel::plan_transfer(transfer_inputs(), dims);
}

std::size_t Context::pixel_client_bytes(bool pack, int width, int height, GLenum format, GLenum type) const {
  const int n = format == gl::STENCIL_INDEX || format == gl::DEPTH_COMPONENT ? 1 : pixel::color_format_components(format);
  const int s = pixel::type_size(type);
  if (n == 0 || s == 0 || width <= 0 || height <= 0) return 0;
  const pixel::PixelStoreModes& m = pack ? pixel_store_.pack : pixel_store_.unpack;
  return pixel::client_layout(m, width, height, n, s).extent(width, height);
}

template <class T>
RgbaImage<T> Context::read_color_rect(int x, int y, int w, int h) const {
  RgbaImage<T> img(std::max(w, 0), std::max(h, 0));
  const bool fl = fb_.format().float_color();
  const T maxc = static_cast<T>(fb_.color_max());
  for (int j = 0; j < img.height; ++j)
    for (int i = 0; i < img.width; ++i) {
      const int fx = x + i, fy = y + j;
      if (fx < 0 || fy < 0 || fx >= fb_.width() || fy >= fb_.height()) continue;
      const std::size_t s = 4 * fb_.index(fx, fy);
      T* o = img.at(i, j);
      for (int c = 0; c < 4; ++c)  // m-bit code k -> k / (2^m - 1) in T (spec-notes §2.11)
        o[c] = fl ? static_cast<T>(fb_.values()[s + c]) : static_cast<T>(fb_.codes()[s + c]) / maxc;
    }
  return img;
}

template <class T>
RgbaImage<T> Context::transfer(RgbaImage<T> img, pixel::ImageDims dims) const {
  const pixel::TransferInputs in = transfer_inputs();
  return pixel::run_plan(pixel::plan_transfer(in, dims), in, std::move(img));
}

template RgbaImage<float> Context::read_color_rect<float>(int, int, int, int) const;
template RgbaImage<double> Context::read_color_rect<double>(int, int, int, int) const;
template RgbaImage<float> Context::transfer<float>(RgbaImage<float>, pixel::ImageDims) const;
template RgbaImage<double> Context::transfer<double>(RgbaImage<double>, pixel::ImageDims) const;

}  // namespace ffsim

// Pixel rectangles: glDrawPixels, glReadPixels, glCopyPixels (GL121 §3.6.4,
// §4.3.2, §4.3.3). Colour goes through the transfer plan, then final conversion
// and fragment generation at the raster position with pixel zoom; the fragments
// go to pixel_fragments (texturing with the raster texture coordinates and the
// per-fragment operations, owned by other areas). Stencil rectangles are written
// directly through the scissor box and the stencil write mask (§4.3.1, §3.6.4).
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "pipeline/gl/enum_names.h"
#include "pipeline/number/unorm.h"
#include "pipeline/pixel_transfer/final_conversion.h"
#include "pipeline/pixel_transfer/formats.h"
#include "pipeline/pixel_transfer/transfer_plan.h"
#include "pipeline/pixel_transfer/unpack.h"
#include "sim/context.h"
#include "sim/worker_pool.h"

namespace ffsim {

using pixel::RgbaImage;

namespace {
// Rectangles beyond the framebuffer's pixel limit are refused with OUT_OF_MEMORY
// (GL121 §2.5) instead of allocating gigabytes for a mistyped size.
bool too_large(int width, int height) {
  return static_cast<long long>(width) * height > kMaxFramebufferPixels;
}

// The checks DrawPixels and ReadPixels share: the buffer a STENCIL_INDEX or
// DEPTH_COMPONENT rectangle needs exists (INVALID_OPERATION), and the size is
// within the limit (OUT_OF_MEMORY). Raises the error and returns false otherwise.
bool rectangle_buffers_ok(Context& c, const char* fn, GLenum format, int width, int height) {
  if (format == gl::STENCIL_INDEX && !c.framebuffer().has_stencil())
    return c.error(gl::INVALID_OPERATION, fn, "STENCIL_INDEX with no stencil buffer");
  if (format == gl::DEPTH_COMPONENT && !c.framebuffer().has_depth())
    return c.error(gl::INVALID_OPERATION, fn, "DEPTH_COMPONENT with no depth buffer");
  if (too_large(width, height))
    return c.error(gl::OUT_OF_MEMORY, fn,
                   "a " + std::to_string(width) + "x" + std::to_string(height) + " rectangle is too large");
  return true;
}
}  // namespace

void Context::group_extent(int n, int m, int& x0, int& x1, int& y0, int& y1) const {
  // GL121 §3.6.4 "Conversion to Fragments": group (n, m) covers the rectangle with
  // corners (xrp + zx n, yrp + zy m) and (xrp + zx (n+1), yrp + zy (m+1)); a pixel
  // belongs to it when its centre lies inside or on the bottom/left edge:
  // x + 1/2 in [lo, hi)  <=>  x in [ceil(lo - 1/2), ceil(hi - 1/2)).
  const double zx = pixel_zoom_[0], zy = pixel_zoom_[1];
  const double xa = raster_pos_.x + zx * n, xb = raster_pos_.x + zx * (n + 1);
  const double ya = raster_pos_.y + zy * m, yb = raster_pos_.y + zy * (m + 1);
  const auto lo = [](double a, double b) { return std::ceil(std::min(a, b) - 0.5); };
  const auto hi = [](double a, double b) { return std::ceil(std::max(a, b) - 0.5); };
  const auto to_int = [](double v) { return std::isnan(v) ? 0 : static_cast<int>(std::clamp(v, -1e9, 1e9)); };
  x0 = to_int(lo(xa, xb));
  x1 = to_int(hi(xa, xb));
  y0 = to_int(lo(ya, yb));
  y1 = to_int(hi(ya, yb));
}

namespace {
// Iterate the columns of an image in increasing window x (negative zoom reverses).
template <class F>
void for_columns(int width, double zx, F f) {
  if (zx >= 0)
    for (int n = 0; n < width; ++n) f(n);
  else
    for (int n = width - 1; n >= 0; --n) f(n);
}
}  // namespace

template <class T>
void Context::emit_color_rect(const RgbaImage<T>& img) {
  if (!raster_pos_.valid || img.empty()) return;  // §3.6.4: invalid raster position -> nothing
  const bool fixed = profile_.is_fixed();
  const int bits = fb_.format().color_bits;
  const bool has_depth = fb_.has_depth();
  const std::uint32_t z = has_depth ? pixel::pack_unsigned(raster_pos_.z, fb_.format().depth_bits) : 0;
  // A group's columns depend on n only and its rows on m only (group_extent):
  // the columns, clipped to the window, are computed once for every row.
  std::vector<std::array<int, 2>> cols(static_cast<std::size_t>(img.width));
  for (int n = 0; n < img.width; ++n) {
    int gx0, gx1, gy0, gy1;
    group_extent(n, 0, gx0, gx1, gy0, gy1);
    cols[static_cast<std::size_t>(n)] = {std::max(gx0, 0), std::min(gx1, fb_.width())};  // pixel ownership
  }
  FragmentSpan span;  // reused from row to row
  std::vector<std::uint16_t> row_codes;
  std::vector<double> row_values;
  for (int m = 0; m < img.height; ++m) {
    int x0, x1, y0, y1;
    group_extent(0, m, x0, x1, y0, y1);
    const int ya = std::max(y0, 0), yb = std::min(y1, fb_.height());
    if (ya >= yb) continue;
    // The row's colours converted once (every window row of the group repeats them).
    if (fixed) {
      row_codes.resize(4 * static_cast<std::size_t>(img.width));
      for (int n = 0; n < img.width; ++n)
        for (int k = 0; k < 4; ++k) row_codes[4 * static_cast<std::size_t>(n) + k] = pixel::final_code(img.at(n, m)[k], bits);
    } else {
      row_values.resize(4 * static_cast<std::size_t>(img.width));
      for (int n = 0; n < img.width; ++n)
        for (int k = 0; k < 4; ++k) row_values[4 * static_cast<std::size_t>(n) + k] = pixel::final_value(img.at(n, m)[k], profile_.arithmetic);
    }
    for (int y = ya; y < yb; ++y) {
      span.y = y;
      span.count = 0;
      span.codes.clear();
      span.values.clear();
      span.depth.clear();
      bool started = false;
      for_columns(img.width, pixel_zoom_[0], [&](int n) {
        const auto [xa, xe] = cols[static_cast<std::size_t>(n)];
        for (int x = xa; x < xe; ++x) {
          if (!started) {
            span.x0 = x;
            started = true;
          }
          const std::size_t o = 4 * static_cast<std::size_t>(n);
          if (fixed) span.codes.insert(span.codes.end(), row_codes.begin() + static_cast<std::ptrdiff_t>(o), row_codes.begin() + static_cast<std::ptrdiff_t>(o + 4));
          else span.values.insert(span.values.end(), row_values.begin() + static_cast<std::ptrdiff_t>(o), row_values.begin() + static_cast<std::ptrdiff_t>(o + 4));
          if (has_depth) span.depth.push_back(z);
          ++span.count;
        }
      });
      if (span.count > 0) pixel_fragments(span);
    }
  }
}

// emit_color_rect's fragments for a fixed profile whose final codes are known
// (CopyPixels' identity transfer), without the per-pixel vector growth: the
// window row's fragments are counted once and laid out by index. The reference
// (set_fast_paths(false)) keeps emit_color_rect; tests/sim/test_fast_copy_pixels.cpp
// compares the two.
template <class RowCodes>
void Context::emit_color_code_rows(int width, int height, RowCodes row_codes_of) {
  if (!raster_pos_.valid || width <= 0 || height <= 0) return;  // §3.6.4: invalid raster position -> nothing
  const bool has_depth = fb_.has_depth();
  const std::uint32_t z = has_depth ? pixel::pack_unsigned(raster_pos_.z, fb_.format().depth_bits) : 0;
  // A group's columns depend on n only and its rows on m only (group_extent):
  // the columns, clipped to the window, are computed once for every row, and so
  // is the number of fragments of a window row.
  std::vector<std::array<int, 2>> cols(static_cast<std::size_t>(width));
  int row_fragments = 0;
  for (int n = 0; n < width; ++n) {
    int gx0, gx1, gy0, gy1;
    group_extent(n, 0, gx0, gx1, gy0, gy1);
    auto& c = cols[static_cast<std::size_t>(n)];
    c = {std::max(gx0, 0), std::min(gx1, fb_.width())};  // pixel ownership
    row_fragments += std::max(0, c[1] - c[0]);
  }
  if (row_fragments == 0) return;
  // One window column per image column, in order (zoom 1, as CopyPixels onto the
  // window usually is): a row's fragments are the row's codes from the first
  // column that lands in the window, copied at once.
  int first = -1;
  bool one_to_one = pixel_zoom_[0] >= 0;
  for (int n = 0, next = -1; n < width && one_to_one; ++n) {
    const auto [xa, xe] = cols[static_cast<std::size_t>(n)];
    if (xa >= xe) continue;
    if (first < 0) first = n;
    one_to_one = xe - xa == 1 && (next < 0 || xa == next) && n - first == xa - cols[static_cast<std::size_t>(first)][0];
    next = xe;
  }
  // Threads (docs/performance.md 19.6): when each image row lands on exactly one
  // window row, all of them distinct, and nothing shades the fragments, the rows
  // go to the fragment operations in bands on the pool. A pixel receives one
  // fragment, from one row, whatever the thread: the same buffers as in order.
  if (threads_ > 1 && !probe_.enabled() && !on_explain_ && one_to_one && !shading_active(shading_plan(shading_state()))) {
    std::vector<std::array<int, 2>> rows;  // (image row m, its window row), rows monotone
    bool single = true;
    for (int m = 0, dir = 0; m < height && single; ++m) {
      int x0, x1, y0, y1;
      group_extent(0, m, x0, x1, y0, y1);
      const int ya = std::max(y0, 0), yb = std::min(y1, fb_.height());
      if (ya >= yb) continue;
      const int d = rows.empty() ? dir : (ya > rows.back()[1] ? 1 : ya < rows.back()[1] ? -1 : 0);
      single = yb - ya == 1 && (rows.empty() || (d != 0 && (dir == 0 || d == dir)));
      dir = d;
      rows.push_back({m, ya});
    }
    if (single && rows.size() >= 2 && static_cast<std::int64_t>(rows.size()) * row_fragments >= split_fragments_) {
      code_rows_in_bands(rows, width, cols[static_cast<std::size_t>(first)][0], first, row_fragments, z, row_codes_of);
      return;
    }
  }
  FragmentSpan span;  // reused from row to row
  std::vector<std::uint16_t> row_codes(4 * static_cast<std::size_t>(width));
  span.count = row_fragments;
  span.codes.resize(4 * static_cast<std::size_t>(row_fragments));
  if (has_depth) span.depth.assign(static_cast<std::size_t>(row_fragments), z);
  for (int m = 0; m < height; ++m) {
    int x0, x1, y0, y1;
    group_extent(0, m, x0, x1, y0, y1);
    const int ya = std::max(y0, 0), yb = std::min(y1, fb_.height());
    if (ya >= yb) continue;
    row_codes_of(m, row_codes.data());  // once for every window row of the group
    for (int y = ya; y < yb; ++y) {
      // Laid out again for every window row, in increasing window x:
      // pixel_fragments textures the span's colours in place.
      if (one_to_one) {
        span.x0 = cols[static_cast<std::size_t>(first)][0];
        std::copy_n(row_codes.data() + 4 * static_cast<std::size_t>(first), 4 * static_cast<std::size_t>(row_fragments),
                    span.codes.data());
        span.y = y;
        pixel_fragments(span);
        continue;
      }
      std::size_t f = 0;
      bool started = false;
      for_columns(width, pixel_zoom_[0], [&](int n) {
        const auto [xa, xe] = cols[static_cast<std::size_t>(n)];
        if (xa >= xe) return;
        if (!started) {
          span.x0 = xa;
          started = true;
        }
        for (int x = xa; x < xe; ++x, ++f) std::copy_n(row_codes.data() + 4 * static_cast<std::size_t>(n), 4, span.codes.data() + 4 * f);
      });
      span.y = y;
      pixel_fragments(span);
    }
  }
}

template <class RowCodes>
void Context::code_rows_in_bands(const std::vector<std::array<int, 2>>& rows, int width, int x0, int first,
                                 int row_fragments, std::uint32_t z, RowCodes& row_codes_of) {
  // write_fragments' work for every row (its plan update once), the rows cut
  // into bands; counters summed after the run, also when a band throws.
  update_fragment_plan();
  const FragmentBuffers b = fragment_buffers();
  const int bands = static_cast<int>(std::min<std::size_t>(4 * static_cast<std::size_t>(threads_), rows.size()));
  ready_bands(bands);
  struct Sum {
    Context& c;
    ~Sum() { c.sum_band_counts(); }
  } sum{*this};
  ++split_pixel_rects_;
  const bool has_depth = fb_.has_depth();
  run_split(bands, [&](int k) {
    FragmentSpan& span = band_spans_[static_cast<std::size_t>(k)].span;
    span.count = row_fragments;
    span.x0 = x0;
    span.codes.resize(4 * static_cast<std::size_t>(row_fragments));
    span.values.clear();
    if (has_depth) span.depth.assign(static_cast<std::size_t>(row_fragments), z);
    else span.depth.clear();
    std::vector<std::uint16_t> row_codes(4 * static_cast<std::size_t>(width));
    const std::size_t i0 = rows.size() * static_cast<std::size_t>(k) / static_cast<std::size_t>(bands);
    const std::size_t i1 = rows.size() * static_cast<std::size_t>(k + 1) / static_cast<std::size_t>(bands);
    for (std::size_t i = i0; i < i1; ++i) {
      row_codes_of(rows[i][0], row_codes.data());
      std::copy_n(row_codes.data() + 4 * static_cast<std::size_t>(first), 4 * static_cast<std::size_t>(row_fragments),
                  span.codes.data());
      span.y = rows[i][1];
      band_counts_[static_cast<std::size_t>(k)].fragments += static_cast<std::uint64_t>(row_fragments);
      if (run_fragment_plan(*fragment_current_plan_, fragment_current_constants_, span, b, fb_.width())) fb_.depth_changed();
    }
  });
}

void Context::write_stencil_rect(int, int, int w, int h, const std::vector<std::int64_t>& idx) {
  // Index arithmetic (§3.6.5 "Arithmetic on Indices"): shift, offset, MAP_STENCIL,
  // then the value is masked to the s stencil bits and written through the
  // scissor box and StencilMask (§4.3.1); no other fragment operation applies.
  if (!raster_pos_.valid || !fb_.has_stencil()) return;
  const std::uint32_t smax = fb_.stencil_max();
  const std::uint32_t wmask = masks_.stencil & smax;
  const Rect r = write_rect();
  const pixel::PixelTransferState& t = pixel_transfer_;
  for (int m = 0; m < h; ++m)
    for (int n = 0; n < w; ++n) {
      std::int64_t v = idx[static_cast<std::size_t>(m) * w + n];
      v = t.index_shift >= 0 ? v * (std::int64_t{1} << t.index_shift) : v >> -t.index_shift;
      v += t.index_offset;
      if (t.map_stencil) v = t.stencil_map[static_cast<std::size_t>(v & static_cast<std::int64_t>(t.stencil_map.size() - 1))];
      const std::uint32_t s = static_cast<std::uint32_t>(v) & smax;
      int x0, x1, y0, y1;
      group_extent(n, m, x0, x1, y0, y1);
      for (int y = std::max(y0, r.y); y < std::min(y1, r.y + r.height); ++y)
        for (int x = std::max(x0, r.x); x < std::min(x1, r.x + r.width); ++x) {
          std::uint8_t& d = fb_.stencil()[fb_.index(x, y)];
          d = static_cast<std::uint8_t>((d & ~wmask) | (s & wmask));
        }
    }
}

void Context::write_depth_fragments(int w, int h, const std::vector<double>& zv) {
  // DEPTH_COMPONENT rectangles: the depth values replace z; colour comes from the
  // current raster colour (§3.6.4); the fragments take the usual per-fragment path.
  if (!raster_pos_.valid) return;
  const bool fixed = profile_.is_fixed();
  const int bits = fb_.format().color_bits;
  const int dbits = fb_.format().depth_bits;
  for (int m = 0; m < h; ++m) {
    int x0, x1, y0, y1;
    group_extent(0, m, x0, x1, y0, y1);
    for (int y = std::max(y0, 0); y < std::min(y1, fb_.height()); ++y) {
      FragmentSpan span;
      span.y = y;
      bool started = false;
      for_columns(w, pixel_zoom_[0], [&](int n) {
        int gx0, gx1, gy0, gy1;
        group_extent(n, m, gx0, gx1, gy0, gy1);
        for (int x = std::max(gx0, 0); x < std::min(gx1, fb_.width()); ++x) {
          if (!started) {
            span.x0 = x;
            started = true;
          }
          for (int k = 0; k < 4; ++k) {
            const double c = raster_pos_.color[k];
            if (fixed) span.codes.push_back(static_cast<std::uint16_t>(unorm_from_double(c, bits)));
            else span.values.push_back(pixel::final_value(c, profile_.arithmetic));
          }
          span.depth.push_back(pixel::pack_unsigned(zv[static_cast<std::size_t>(m) * w + n], dbits));
          ++span.count;
        }
      });
      if (span.count > 0) pixel_fragments(span);
    }
  }
}

namespace {
// Depth scale and bias (§3.6.5), then the clamp to [0,1] of final conversion.
// Always binary64: binary32 has 24 significant bits, so k / (2^24 - 1) of a 24-bit
// depth code would not convert back to k (docs/numerics.md §7.6).
std::vector<double> depth_transfer(const std::vector<double>& d, const pixel::PixelTransferState& t) {
  std::vector<double> out(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) {
    const double prod = d[i] * t.depth_scale;
    out[i] = pixel::clamp01(prod + t.depth_bias);
  }
  return out;
}
// Depth codes of a framebuffer rectangle as k / (2^d - 1) in binary64; outside the window 0.
std::vector<double> read_depth_rect(const Framebuffer& fb, int x, int y, int width, int height) {
  std::vector<double> d(static_cast<std::size_t>(width) * height, 0.0);
  const double dmax = static_cast<double>(fb.depth_max());
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const int fx = x + i, fy = y + j;
      if (fx >= 0 && fy >= 0 && fx < fb.width() && fy < fb.height())
        d[static_cast<std::size_t>(j) * width + i] = static_cast<double>(fb.depth()[fb.index(fx, fy)]) / dmax;
    }
  return d;
}
}  // namespace

template <class T>
void Context::draw_pixels(int width, int height, GLenum format, GLenum type, const void* data) {
  const auto& up = pixel_store_.unpack;
  if (format == gl::STENCIL_INDEX) {
    write_stencil_rect(0, 0, width, height, pixel::unpack_indices(data, width, height, type, up));
  } else if (format == gl::DEPTH_COMPONENT) {
    write_depth_fragments(width, height,
                          depth_transfer(pixel::unpack_depth<double>(data, width, height, type, up), pixel_transfer_));
  } else {
    emit_color_rect(transfer(pixel::unpack_rgba<T>(data, width, height, format, type, up), pixel::ImageDims::TwoD));
  }
}

void Context::drawPixels(int width, int height, GLenum format, GLenum type, const void* data) {
  if (reject_in_begin("glDrawPixels")) return;
  static const char* fn = "glDrawPixels";
  if (width < 0 || height < 0) {
    error(gl::INVALID_VALUE, fn, "width and height must not be negative");
    return;
  }
  if (pixel::color_format_components(format) == 0 && format != gl::STENCIL_INDEX && format != gl::DEPTH_COMPONENT) {
    error(gl::INVALID_ENUM, fn, gl::enum_name(format) + (format == gl::COLOR_INDEX
                                                            ? std::string(" is not supported by ffsim (no colour-index path)")
                                                            : std::string(" is not a pixel format")));
    return;
  }
  if (pixel::type_size(type) == 0) {
    error(gl::INVALID_ENUM, fn, gl::enum_name(type) + (pixel::is_unsupported_gl_type(type)
                                                          ? std::string(" (packed or bitmap) is not supported by ffsim")
                                                          : std::string(" is not a pixel type")));
    return;
  }
  if (!rectangle_buffers_ok(*this, fn, format, width, height)) return;
  if (width == 0 || height == 0) return;
  if (!data) {
    error(gl::INVALID_VALUE, fn, "no pixel data");
    return;
  }
  if (profile_.arithmetic == Arithmetic::Float64) draw_pixels<double>(width, height, format, type, data);
  else draw_pixels<float>(width, height, format, type, data);
}

template <class T>
void Context::read_pixels(int x, int y, int width, int height, GLenum format, GLenum type, void* data) {
  const auto& pk = pixel_store_.pack;
  const auto inside = [&](int fx, int fy) { return fx >= 0 && fy >= 0 && fx < fb_.width() && fy < fb_.height(); };
  if (format == gl::STENCIL_INDEX) {
    const pixel::PixelTransferState& t = pixel_transfer_;
    std::vector<std::uint32_t> v(static_cast<std::size_t>(width) * height, 0);
    for (int j = 0; j < height; ++j)
      for (int i = 0; i < width; ++i) {
        if (!inside(x + i, y + j)) continue;
        std::int64_t s = fb_.stencil()[fb_.index(x + i, y + j)];
        s = t.index_shift >= 0 ? s * (std::int64_t{1} << t.index_shift) : s >> -t.index_shift;
        s += t.index_offset;
        if (t.map_stencil) s = t.stencil_map[static_cast<std::size_t>(s & static_cast<std::int64_t>(t.stencil_map.size() - 1))];
        v[static_cast<std::size_t>(j) * width + i] = static_cast<std::uint32_t>(s);
      }
    pixel::pack_indices(v, width, height, type, pk, data);
  } else if (format == gl::DEPTH_COMPONENT) {
    pixel::pack_depth(depth_transfer(read_depth_rect(fb_, x, y, width, height), pixel_transfer_), width, height, type,
                      pk, data);
  } else {
    pixel::pack_rgba(transfer(read_color_rect<T>(x, y, width, height), pixel::ImageDims::TwoD), format, type, pk,
                     data);
  }
}

void Context::readPixels(int x, int y, int width, int height, GLenum format, GLenum type, void* data) {
  if (reject_in_begin("glReadPixels")) return;
  static const char* fn = "glReadPixels";
  if (width < 0 || height < 0) {
    error(gl::INVALID_VALUE, fn, "width and height must not be negative");
    return;
  }
  if (format == gl::COLOR_INDEX) {  // GL121 §4.3.2: colour indices from an RGBA buffer
    error(gl::INVALID_OPERATION, fn, "COLOR_INDEX from an RGBA colour buffer");
    return;
  }
  if (pixel::color_format_components(format) == 0 && format != gl::STENCIL_INDEX && format != gl::DEPTH_COMPONENT) {
    error(gl::INVALID_ENUM, fn, gl::enum_name(format) + " is not a pixel format ffsim reads");
    return;
  }
  if (pixel::type_size(type) == 0) {
    error(gl::INVALID_ENUM, fn, gl::enum_name(type) + " is not a pixel type ffsim packs");
    return;
  }
  if (!rectangle_buffers_ok(*this, fn, format, width, height)) return;
  if (width == 0 || height == 0) return;
  if (!data) {
    error(gl::INVALID_VALUE, fn, "no destination");
    return;
  }
  // REDUCE convolution may leave nothing to write (§3.6.5): pack_rgba handles an empty image.
  if (profile_.arithmetic == Arithmetic::Float64) read_pixels<double>(x, y, width, height, format, type, data);
  else read_pixels<float>(x, y, width, height, format, type, data);
}

template <class T>
void Context::copy_pixels(int x, int y, int width, int height, GLenum type) {
  // §4.3.3: every source pixel is read before any write (read into an image first).
  const auto inside = [&](int fx, int fy) { return fx >= 0 && fy >= 0 && fx < fb_.width() && fy < fb_.height(); };
  if (type == gl::STENCIL) {
    std::vector<std::int64_t> idx(static_cast<std::size_t>(width) * height, 0);
    for (int j = 0; j < height; ++j)
      for (int i = 0; i < width; ++i)
        if (inside(x + i, y + j)) idx[static_cast<std::size_t>(j) * width + i] = fb_.stencil()[fb_.index(x + i, y + j)];
    write_stencil_rect(0, 0, width, height, idx);
  } else if (type == gl::DEPTH) {
    write_depth_fragments(width, height, depth_transfer(read_depth_rect(fb_, x, y, width, height), pixel_transfer_));
  } else if (fast_paths_ && profile_.is_fixed() && !fb_.format().float_color() &&
             pixel::plan_transfer(transfer_inputs(), pixel::ImageDims::TwoD).empty()) {
    // No transfer operation can change a value (the plan is empty): each
    // component's final code is a function of its framebuffer code alone, the
    // reference's read_color_rect then final_code, tabulated once for the 2^m
    // codes. The whole source is read before any fragment is written (§4.3.3).
    const int bits = fb_.format().color_bits;
    const T maxc = static_cast<T>(fb_.color_max());
    std::vector<std::uint16_t> code_of(static_cast<std::size_t>(fb_.color_max()) + 1);
    for (std::size_t k = 0; k < code_of.size(); ++k) code_of[k] = pixel::final_code(static_cast<T>(k) / maxc, bits);
    const std::uint16_t outside = pixel::final_code(T(0), bits);  // pixels outside the window read as 0
    // (In 64 bits: x and y may be any int.)
    const auto i0 = static_cast<int>(std::clamp<std::int64_t>(-std::int64_t{x}, 0, width));
    const auto i1 = static_cast<int>(std::clamp<std::int64_t>(std::int64_t{fb_.width()} - x, i0, width));
    // Every code its own final code (8 bits: k/255 converts back to k): rows copied.
    bool identity = true;
    for (std::size_t k = 0; k < code_of.size(); ++k) identity = identity && code_of[k] == k;
    // No snapshot is needed when no fragment can write a source pixel before it is
    // read: the colour mask keeps every channel (nothing writes colour), or each
    // image pixel lands on the pixel it was read from (zoom 1, the raster position
    // on the source corner: image row m is read just before its fragments are
    // written, into that same row, and no other row writes it). Each row is then
    // read from the framebuffer itself (the paper's step "CopyPixels the window
    // onto itself"; docs/performance.md 31.3).
    int gx0, gx1, gy0, gy1;
    group_extent(0, 0, gx0, gx1, gy0, gy1);
    const bool colour_kept = masks_.color == std::array<bool, 4>{false, false, false, false};
    const bool in_place = pixel_zoom_[0] == 1 && pixel_zoom_[1] == 1 && gx0 == x && gy0 == y;
    if (identity && (colour_kept || in_place)) {
      const std::uint16_t* const fb_codes = fb_.codes().data();  // (taken here: the bands only read through it)
      const int fb_w = fb_.width(), fb_h = fb_.height();
      emit_color_code_rows(width, height, [=](int m, std::uint16_t* to) {
        const std::int64_t fy = std::int64_t{y} + m;
        if (fy < 0 || fy >= fb_h) {
          std::fill_n(to, 4 * static_cast<std::size_t>(width), outside);
          return;
        }
        std::fill_n(to, 4 * static_cast<std::size_t>(i0), outside);
        if (i1 > i0)
          std::copy_n(fb_codes + 4 * (static_cast<std::size_t>(fy) * static_cast<std::size_t>(fb_w) + static_cast<std::size_t>(x + i0)),
                      4 * static_cast<std::size_t>(i1 - i0), to + 4 * static_cast<std::size_t>(i0));
        std::fill_n(to + 4 * static_cast<std::size_t>(i1), 4 * static_cast<std::size_t>(width - i1), outside);
      });
      return;
    }
    std::vector<std::uint16_t> codes(4 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height), outside);
    for (int j = 0; j < height; ++j) {
      const std::int64_t fy = std::int64_t{y} + j;
      if (fy < 0 || fy >= fb_.height()) continue;
      if (identity) {
        std::copy_n(fb_.codes().data() + 4 * fb_.index(x + i0, static_cast<int>(fy)), 4 * static_cast<std::size_t>(i1 - i0),
                    codes.data() + 4 * (static_cast<std::size_t>(j) * static_cast<std::size_t>(width) + static_cast<std::size_t>(i0)));
        continue;
      }
      for (int i = i0; i < i1; ++i) {
        const std::uint16_t* src = fb_.codes().data() + 4 * fb_.index(x + i, static_cast<int>(fy));
        std::uint16_t* dst = codes.data() + 4 * (static_cast<std::size_t>(j) * static_cast<std::size_t>(width) + static_cast<std::size_t>(i));
        for (int c = 0; c < 4; ++c) dst[c] = code_of[src[c]];
      }
    }
    emit_color_code_rows(width, height, [&](int m, std::uint16_t* to) {
      std::copy_n(codes.data() + 4 * static_cast<std::size_t>(m) * static_cast<std::size_t>(width),
                  4 * static_cast<std::size_t>(width), to);
    });
  } else {
    emit_color_rect(transfer(read_color_rect<T>(x, y, width, height), pixel::ImageDims::TwoD));
  }
}

void Context::copyPixels(int x, int y, int width, int height, GLenum type) {
  if (reject_in_begin("glCopyPixels")) return;
  static const char* fn = "glCopyPixels";
  if (type != gl::COLOR && type != gl::STENCIL && type != gl::DEPTH) {
    error(gl::INVALID_ENUM, fn, gl::enum_name(type) + " is not COLOR, STENCIL or DEPTH");
    return;
  }
  if (width < 0 || height < 0) {
    error(gl::INVALID_VALUE, fn, "width and height must not be negative");
    return;
  }
  if (type == gl::STENCIL && !fb_.has_stencil()) {
    error(gl::INVALID_OPERATION, fn, "STENCIL with no stencil buffer");
    return;
  }
  if (type == gl::DEPTH && !fb_.has_depth()) {
    error(gl::INVALID_OPERATION, fn, "DEPTH with no depth buffer");
    return;
  }
  if (too_large(width, height)) {
    error(gl::OUT_OF_MEMORY, fn, "a " + std::to_string(width) + "x" + std::to_string(height) + " rectangle is too large");
    return;
  }
  if (profile_.arithmetic == Arithmetic::Float64) copy_pixels<double>(x, y, width, height, type);
  else copy_pixels<float>(x, y, width, height, type);
}

}  // namespace ffsim

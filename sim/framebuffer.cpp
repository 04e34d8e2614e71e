#include "sim/framebuffer.h"

#include <algorithm>

#include "pipeline/number/unorm.h"

namespace ffsim {

namespace {

// dst[i] = pattern[i mod 4] where mask[i mod 4], for the n components of one row
// of pixels (n a multiple of 4).
template <class T>
void copy_masked(const T* pattern, const std::array<bool, 4>& mask, T* dst, std::size_t n) {
  const std::array<T, 4> p{pattern[0], pattern[1], pattern[2], pattern[3]};
  if (mask[0] && mask[1] && mask[2] && mask[3]) {
    for (std::size_t i = 0; i < n; i += 4)
      for (std::size_t c = 0; c < 4; ++c) dst[i + c] = p[c];
    return;
  }
  for (std::size_t i = 0; i < n; i += 4)
    for (std::size_t c = 0; c < 4; ++c)
      if (mask[c]) dst[i + c] = p[c];
}

}  // namespace

FramebufferFormat FramebufferFormat::from_profile(const Profile& p, int width, int height) {
  FramebufferFormat f;
  f.width = width;
  f.height = height;
  f.color_bits = p.color_bits;
  f.color_arith = p.arithmetic;
  f.stencil_bits = p.stencil_bits;
  f.depth_bits = p.depth_bits;
  return f;
}

Framebuffer::Framebuffer(const FramebufferFormat& format) : fmt_(format) {
  const auto fail = [&](const std::string& why) { throw FramebufferError("framebuffer " +
      std::to_string(fmt_.width) + "x" + std::to_string(fmt_.height) + ": " + why); };
  if (fmt_.width < 1 || fmt_.height < 1 || fmt_.width > kMaxFramebufferSide || fmt_.height > kMaxFramebufferSide)
    fail("each side must be 1.." + std::to_string(kMaxFramebufferSide));
  if (static_cast<long long>(fmt_.width) * fmt_.height > kMaxFramebufferPixels)
    fail("more than " + std::to_string(kMaxFramebufferPixels) + " pixels");
  if (fmt_.color_bits < kMinUnormBits || fmt_.color_bits > kMaxColorBits) fail("color_bits must be 1..16");
  if (fmt_.stencil_bits < 0 || fmt_.stencil_bits > 8) fail("stencil_bits must be 0..8");
  if (fmt_.depth_bits != 0 && fmt_.depth_bits != 16 && fmt_.depth_bits != 24) fail("depth_bits must be 0, 16 or 24");
  const std::size_t n = static_cast<std::size_t>(fmt_.width) * fmt_.height;
  // Sized, not filled: the zero fill is owed (fill_zero) until a whole-buffer clear.
  if (fmt_.float_color()) values_.resize(4 * n);
  else codes_.resize(4 * n);
  if (fmt_.stencil_bits > 0) stencil_.resize(n);
  if (fmt_.depth_bits > 0) depth_.resize(n);
  unfilled_ = kColor | (fmt_.stencil_bits > 0 ? kStencil : 0u) | (fmt_.depth_bits > 0 ? kDepth : 0u);
}

void Framebuffer::fill_zero(unsigned buffers) const {
  buffers &= unfilled_;
  if (buffers & kColor) {
    std::fill(codes_.begin(), codes_.end(), std::uint16_t{0});
    std::fill(values_.begin(), values_.end(), 0.0);
  }
  if (buffers & kStencil) std::fill(stencil_.begin(), stencil_.end(), std::uint8_t{0});
  if (buffers & kDepth) std::fill(depth_.begin(), depth_.end(), std::uint32_t{0});
  unfilled_ &= ~buffers;
}

std::uint64_t Framebuffer::next_epoch() {
  static std::atomic<std::uint64_t> counter{0};
  return counter.fetch_add(1, std::memory_order_relaxed) + 1;
}

std::uint32_t Framebuffer::color_max() const { return unorm_max(fmt_.color_bits); }
std::uint32_t Framebuffer::stencil_max() const { return fmt_.stencil_bits ? unorm_max(fmt_.stencil_bits) : 0; }
std::uint32_t Framebuffer::depth_max() const { return fmt_.depth_bits ? unorm_max(fmt_.depth_bits) : 0; }

double Framebuffer::color_value(int x, int y, int c) const {
  const std::size_t i = 4 * index(x, y) + c;
  return fmt_.float_color() ? values()[i] : unorm_to_double(codes()[i], fmt_.color_bits);
}

std::array<double, 4> Framebuffer::color(int x, int y) const {
  return {color_value(x, y, 0), color_value(x, y, 1), color_value(x, y, 2), color_value(x, y, 3)};
}

std::uint16_t Framebuffer::color_code_of(double v) const {
  return static_cast<std::uint16_t>(unorm_from_double(v, fmt_.color_bits));
}

double Framebuffer::color_float_of(double v) const {
  const double c = std::clamp(v, 0.0, 1.0);
  return fmt_.color_arith == Arithmetic::Float32 ? static_cast<float>(c) : c;
}

void Framebuffer::store_color_value(int x, int y, int c, double v) {
  const std::size_t i = 4 * index(x, y) + c;
  if (fmt_.float_color()) values()[i] = color_float_of(v);
  else codes()[i] = color_code_of(v);
}

Rect intersect(const Rect& a, const Rect& b) {
  const int x0 = std::max(a.x, b.x), y0 = std::max(a.y, b.y);
  const int x1 = std::min(a.x + a.width, b.x + b.width), y1 = std::min(a.y + a.height, b.y + b.height);
  return {x0, y0, std::max(0, x1 - x0), std::max(0, y1 - y0)};
}

void Framebuffer::clear_color(const Rect& r, const std::array<double, 4>& rgba, const std::array<bool, 4>& mask) {
  ClearValues v;
  v.color = true;
  v.rgba = rgba;
  v.color_mask = mask;
  clear(r, v);
}

void Framebuffer::clear_stencil(const Rect& r, std::uint32_t value, std::uint32_t writemask) {
  ClearValues v;
  v.stencil = true;
  v.stencil_value = value;
  v.stencil_mask = writemask;
  clear(r, v);
}

void Framebuffer::clear_depth(const Rect& r, double depth01) {
  ClearValues v;
  v.depth = true;
  v.depth01 = depth01;
  clear(r, v);
}

ClearPlan Framebuffer::plan_clear(const Rect& r0, const ClearValues& v) {
  ClearPlan p;
  p.r = intersect(r0, bounds());
  if (p.r.width == 0 || p.r.height == 0) return p;
  const bool all = covers_all(p.r);
  if (v.color) {
    p.color = true;
    p.color_mask = v.color_mask;
    const bool every_channel = v.color_mask[0] && v.color_mask[1] && v.color_mask[2] && v.color_mask[3];
    // A clear of every pixel and channel writes every value: the owed fill is
    // not needed (any other clear keeps some zeros, so it is done first).
    if (all && every_channel) unfilled_ &= ~kColor;
    else fill_zero(kColor);
    // Converted once with store_color_value's rule (a code, or a clamped
    // binary32/64 value); every pixel gets the same bits.
    for (std::size_t c = 0; c < 4; ++c) {
      if (fmt_.float_color()) p.values[c] = color_float_of(v.rgba[c]);
      else p.codes[c] = color_code_of(v.rgba[c]);
    }
  }
  if (v.stencil && has_stencil()) {
    p.stencil = true;
    const std::uint32_t m = v.stencil_mask & stencil_max();
    p.stencil_mask = static_cast<std::uint8_t>(m);
    p.stencil_bits = static_cast<std::uint8_t>(v.stencil_value & m);
    // Owed zeros under every pixel and every written bit: (0 & ~m) | (value & m)
    // everywhere (the bits above stencil_bits stay 0, as in a filled buffer).
    p.stencil_overwrite = (unfilled_ & kStencil) && all && m == stencil_max();
    if (p.stencil_overwrite) unfilled_ &= ~kStencil;
    else fill_zero(kStencil);
  }
  if (v.depth && has_depth()) {
    p.depth = true;
    depth_changed();
    p.depth_code = unorm_from_double(std::clamp(v.depth01, 0.0, 1.0), fmt_.depth_bits);
    if (all) unfilled_ &= ~kDepth;  // (as the colour)
    else fill_zero(kDepth);
  }
  return p;
}

void Framebuffer::clear_rows(const ClearPlan& p, int y0, int y1) {
  y0 = std::max(y0, p.r.y);
  y1 = std::min(y1, p.r.y + p.r.height);
  // Row by row: a row of the rectangle is contiguous (4 components per pixel in
  // the colour buffer).
  const std::size_t row = static_cast<std::size_t>(p.r.width);
  for (int y = y0; y < y1; ++y) {
    const std::size_t i0 = index(p.r.x, y);
    if (p.color) {
      if (fmt_.float_color()) copy_masked(p.values.data(), p.color_mask, values_.data() + 4 * i0, 4 * row);
      else copy_masked(p.codes.data(), p.color_mask, codes_.data() + 4 * i0, 4 * row);
    }
    if (p.stencil) {
      std::uint8_t* s = stencil_.data() + i0;
      if (p.stencil_overwrite) std::fill_n(s, row, p.stencil_bits);
      else
        for (std::size_t x = 0; x < row; ++x)
          s[x] = static_cast<std::uint8_t>((s[x] & ~p.stencil_mask) | p.stencil_bits);  // §4.2.2: through StencilMask
    }
    if (p.depth) std::fill_n(depth_.data() + i0, row, p.depth_code);
  }
}

}  // namespace ffsim

#include "sim/framebuffer.h"

#include <algorithm>

#include "pipeline/number/unorm.h"

namespace ffsim {

namespace {

// dst[i] = pattern[i mod 4] where mask[i mod 4], for the n components of one row
// of pixels (n a multiple of 4). The pattern is copied first: it may lie in dst.
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

void Framebuffer::store_color_value(int x, int y, int c, double v) {
  const std::size_t i = 4 * index(x, y) + c;
  switch (fmt_.color_arith) {
    case Arithmetic::Fixed: codes()[i] = static_cast<std::uint16_t>(unorm_from_double(v, fmt_.color_bits)); break;
    case Arithmetic::Float32: values()[i] = static_cast<float>(std::clamp(v, 0.0, 1.0)); break;
    case Arithmetic::Float64: values()[i] = std::clamp(v, 0.0, 1.0); break;
  }
}

Rect intersect(const Rect& a, const Rect& b) {
  const int x0 = std::max(a.x, b.x), y0 = std::max(a.y, b.y);
  const int x1 = std::min(a.x + a.width, b.x + b.width), y1 = std::min(a.y + a.height, b.y + b.height);
  return {x0, y0, std::max(0, x1 - x0), std::max(0, y1 - y0)};
}

void Framebuffer::clear_color(const Rect& r0, const std::array<double, 4>& rgba, const std::array<bool, 4>& mask) {
  const Rect r = intersect(r0, bounds());
  if (r.width == 0 || r.height == 0) return;
  // A clear of every pixel and channel writes every value: the owed fill is
  // not needed (any other clear keeps some zeros, so it is done first).
  if (covers_all(r) && mask[0] && mask[1] && mask[2] && mask[3]) unfilled_ &= ~kColor;
  else fill_zero(kColor);
  // The clear colour is converted once (store_color_value's rule: a code, or a
  // clamped binary32/64 value) and copied; every pixel gets the same bits.
  const int x0 = r.x, y0 = r.y;
  for (int c = 0; c < 4; ++c)
    if (mask[c]) store_color_value(x0, y0, c, rgba[c]);
  const std::size_t first = 4 * index(x0, y0);
  // Row by row: a row of the rectangle is contiguous, 4 components per pixel.
  const std::size_t row = 4 * static_cast<std::size_t>(r.width);
  for (int y = r.y; y < r.y + r.height; ++y) {
    const std::size_t i0 = 4 * index(x0, y);
    if (fmt_.float_color()) copy_masked(values_.data() + first, mask, values_.data() + i0, row);
    else copy_masked(codes_.data() + first, mask, codes_.data() + i0, row);
  }
}

void Framebuffer::clear_stencil(const Rect& r0, std::uint32_t value, std::uint32_t writemask) {
  if (!has_stencil()) return;
  const Rect r = intersect(r0, bounds());
  const std::uint32_t m = writemask & stencil_max();
  if ((unfilled_ & kStencil) && covers_all(r) && m == stencil_max()) {
    // Owed zeros under every pixel and every written bit: (0 & ~m) | (value & m)
    // everywhere (the bits above stencil_bits stay 0, as in a filled buffer).
    unfilled_ &= ~kStencil;
    std::fill(stencil_.begin(), stencil_.end(), static_cast<std::uint8_t>(value & m));
    return;
  }
  std::uint8_t* const base = stencil().data();
  for (int y = r.y; y < r.y + r.height; ++y) {
    std::uint8_t* s = base + index(r.x, y);
    for (int x = 0; x < r.width; ++x)
      s[x] = static_cast<std::uint8_t>((s[x] & ~m) | (value & m));  // §4.2.2: writes through StencilMask
  }
}

void Framebuffer::clear_depth(const Rect& r0, double depth01) {
  if (!has_depth()) return;
  depth_changed();
  const Rect r = intersect(r0, bounds());
  const std::uint32_t code = unorm_from_double(std::clamp(depth01, 0.0, 1.0), fmt_.depth_bits);
  if (covers_all(r)) unfilled_ &= ~kDepth;  // (as clear_color)
  std::uint32_t* const base = depth_untracked();
  for (int y = r.y; y < r.y + r.height; ++y) std::fill_n(base + index(r.x, y), r.width, code);
}

}  // namespace ffsim

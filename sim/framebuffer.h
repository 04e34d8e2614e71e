// The framebuffer: RGBA color at the profile's width, a stencil buffer and an
// optional depth buffer. Rows are stored bottom to top (row 0 is window y = 0,
// as in GL window coordinates); image files are flipped on write/read.
#pragma once
#include <array>
#include <atomic>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "pipeline/number/profile.h"
#include "sim/uninitialized_allocator.h"

namespace ffsim {

inline constexpr int kMaxFramebufferSide = 16384;
inline constexpr long long kMaxFramebufferPixels = 1LL << 26;  // 64 Mpixel

struct FramebufferFormat {
  int width = 256;
  int height = 256;
  int color_bits = 8;                       // Fixed profiles: code width per channel (1..16)
  Arithmetic color_arith = Arithmetic::Fixed;  // Float32/Float64: color held as binary64 values
  int stencil_bits = 8;                     // 0 = no stencil buffer
  int depth_bits = 24;                      // 0 = no depth buffer; else 16 or 24

  static FramebufferFormat from_profile(const Profile& p, int width, int height);
  bool float_color() const { return color_arith != Arithmetic::Fixed; }
};

struct FramebufferError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The buffers' storage: sized without a fill (Framebuffer fills its buffers
// itself, or leaves that to the first clear that covers them).
template <class T>
using BufferVector = std::vector<T, UninitializedAllocator<T>>;

struct Rect {
  int x = 0, y = 0, width = 0, height = 0;  // window coordinates, bottom-left origin
};

// What one glClear writes (GL 1.2.1 §4.2.3), for Framebuffer::clear.
struct ClearValues {
  bool color = false, stencil = false, depth = false;  // the buffers cleared
  std::array<double, 4> rgba{};                        // clamped clear colour
  std::array<bool, 4> color_mask{true, true, true, true};
  std::uint32_t stencil_value = 0, stencil_mask = ~0u;  // clear value, StencilMask
  double depth01 = 1;                                   // clamped clear depth
};

// A clear ready to be written by rows (Framebuffer::plan_clear).
struct ClearPlan {
  Rect r;  // clipped to the framebuffer; empty: nothing to write
  bool color = false, stencil = false, depth = false;
  std::array<bool, 4> color_mask{};
  std::array<std::uint16_t, 4> codes{};  // fixed colour: the clear colour's codes
  std::array<double, 4> values{};        // float colour: its stored binary32/64 values
  std::uint8_t stencil_bits = 0;         // value & mask: the bits written
  std::uint8_t stencil_mask = 0;         // StencilMask & stencil_max
  bool stencil_overwrite = false;        // owed zeros under every bit: written, not merged
  std::uint32_t depth_code = 0;          // the clear depth as a depth code
};

class Framebuffer {
 public:
  // Validates the format (sizes 1..16384 per side, at most 2^26 pixels; bit widths
  // in range) and throws FramebufferError with the reason otherwise. Contents start
  // as zero (color 0, stencil 0, depth 0).
  explicit Framebuffer(const FramebufferFormat& format);

  const FramebufferFormat& format() const { return fmt_; }
  int width() const { return fmt_.width; }
  int height() const { return fmt_.height; }
  bool has_stencil() const { return fmt_.stencil_bits > 0; }
  bool has_depth() const { return fmt_.depth_bits > 0; }
  std::uint32_t color_max() const;    // 2^color_bits - 1 (fixed color)
  std::uint32_t stencil_max() const;  // 2^stencil_bits - 1
  std::uint32_t depth_max() const;    // 2^depth_bits - 1

  // Raw storage: 4 values (R, G, B, A) per pixel, row-major from the bottom row.
  // Fixed color uses codes(); float color uses values(). A buffer is zero-filled
  // when first taken, unless a clear covering all of it came first (filled()).
  BufferVector<std::uint16_t>& codes() { return filled(kColor, codes_); }
  const BufferVector<std::uint16_t>& codes() const { return filled(kColor, codes_); }
  BufferVector<double>& values() { return filled(kColor, values_); }
  const BufferVector<double>& values() const { return filled(kColor, values_); }
  BufferVector<std::uint8_t>& stencil() { return filled(kStencil, stencil_); }
  const BufferVector<std::uint8_t>& stencil() const { return filled(kStencil, stencil_); }
  // The depth codes. Taking them to write marks the buffer changed
  // (depth_epoch); a writer that keeps the reference across draws calls
  // depth_changed() after writing.
  BufferVector<std::uint32_t>& depth() {
    depth_changed();
    return filled(kDepth, depth_);
  }
  const BufferVector<std::uint32_t>& depth() const { return filled(kDepth, depth_); }
  // The depth codes for a writer that reports each change through depth_changed
  // (the draw path's fragment operations).
  std::uint32_t* depth_untracked() { return filled(kDepth, depth_).data(); }

  // A number naming the depth buffer's contents (docs/performance.md 17.1): a
  // new one, never used before by any framebuffer, whenever they may change; a
  // copy keeps it with the contents. Equal epochs mean equal depth codes.
  std::uint64_t depth_epoch() const { return depth_epoch_.value.load(std::memory_order_relaxed); }
  void depth_changed() { depth_epoch_.value.store(next_epoch(), std::memory_order_relaxed); }

  std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * fmt_.width + x; }

  // Real value of channel c (0..3) at (x, y): code / (2^bits - 1) or the stored float.
  double color_value(int x, int y, int c) const;
  std::array<double, 4> color(int x, int y) const;
  // Store a real value: clamp to [0,1] and round (unorm_from_double) for fixed
  // color; round to binary32 for Float32; as is for Float64 (still clamped to [0,1]).
  void store_color_value(int x, int y, int c, double v);
  // That rule for one value: the code (fixed colour) or the stored value (float).
  std::uint16_t color_code_of(double v) const;
  double color_float_of(double v) const;

  // glClear semantics (GL 1.2.1 §4.2.3): the rectangle is already intersected with
  // the scissor box by the caller; per-channel color mask; stencil write mask.
  // `rgba` is the clamped clear color; stored with store_color_value's rule.
  void clear(const Rect& r, const ClearValues& v) {
    const ClearPlan p = plan_clear(r, v);
    clear_rows(p, p.r.y, p.r.y + p.r.height);
  }
  void clear_color(const Rect& r, const std::array<double, 4>& rgba, const std::array<bool, 4>& mask);
  void clear_stencil(const Rect& r, std::uint32_t value, std::uint32_t writemask);
  void clear_depth(const Rect& r, double depth01);
  // clear() in two steps, so that several threads can write the rows
  // (Context::clear, docs/performance.md 27.1): plan_clear settles the owed zero
  // fills and converts the values (once, on one thread); clear_rows writes the
  // rows [y0, y1) of the plan's rectangle. Calls of clear_rows on disjoint row
  // ranges may run concurrently; together over every row they write what
  // clear() writes.
  ClearPlan plan_clear(const Rect& r, const ClearValues& v);
  void clear_rows(const ClearPlan& p, int y0, int y1);

  Rect bounds() const { return {0, 0, fmt_.width, fmt_.height}; }

 private:
  // Buffers whose zero fill is still owed (bits kColor, kStencil, kDepth): a new
  // framebuffer reads as zero, but its first whole-buffer glClear (a trace's
  // first command, typically) writes every value anyway, so the fill is done
  // only if something else takes the buffer first (docs/performance.md 20.5).
  static constexpr unsigned kColor = 1, kStencil = 2, kDepth = 4;
  template <class V>
  V& filled(unsigned buffer, V& v) const {
    if (unfilled_ & buffer) fill_zero(buffer);
    return v;
  }
  void fill_zero(unsigned buffers) const;
  // Whether a rectangle already clipped to the bounds is all of them.
  bool covers_all(const Rect& r) const { return r.width == fmt_.width && r.height == fmt_.height; }

  FramebufferFormat fmt_;
  // (mutable: the owed zero fill happens when a const reader first takes a buffer)
  mutable BufferVector<std::uint16_t> codes_;
  mutable BufferVector<double> values_;
  mutable BufferVector<std::uint8_t> stencil_;
  mutable BufferVector<std::uint32_t> depth_;
  mutable unsigned unfilled_ = 0;
  // (atomic: the threads' bands report their changes concurrently; copied as a
  // value; a framebuffer moved from has other contents: a new epoch)
  struct Epoch {
    std::atomic<std::uint64_t> value{next_epoch()};
    Epoch() = default;
    Epoch(const Epoch& o) : value(o.value.load(std::memory_order_relaxed)) {}
    Epoch(Epoch&& o) noexcept : value(o.value.load(std::memory_order_relaxed)) {
      o.value.store(next_epoch(), std::memory_order_relaxed);
    }
    Epoch& operator=(const Epoch& o) {
      value.store(o.value.load(std::memory_order_relaxed), std::memory_order_relaxed);
      return *this;
    }
    Epoch& operator=(Epoch&& o) noexcept {
      if (this != &o) {
        value.store(o.value.load(std::memory_order_relaxed), std::memory_order_relaxed);
        o.value.store(next_epoch(), std::memory_order_relaxed);
      }
      return *this;
    }
  };
  static std::uint64_t next_epoch();
  Epoch depth_epoch_;
};

// Intersection of two rectangles (empty rectangles have width or height 0).
Rect intersect(const Rect& a, const Rect& b);

}  // namespace ffsim

// An allocator whose value-less construct leaves a trivial element as it is:
// resize() then allocates without writing. For arrays whose owner writes every
// element before reading it: the raster cache's recordings (filled whole right
// away by the span path), the framebuffer's buffers (zero-filled when first
// taken, or wholly written by a clear; sim/framebuffer.h), the draw path's
// window vertices (every member written by Context::window_position and
// window_attributes; sim/draw_span.h), a batch's triangles (a memo'd glEnd's
// sized, then each written: Context::end) and the span path's per-group scratch
// (sim/context.h SpanScratch). The memcheck CTests (tests/CMakeLists.txt) check
// that nothing is read before it is written.
#pragma once
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace ffsim {

template <class T>
struct UninitializedAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = UninitializedAllocator<U>;
  };
  UninitializedAllocator() = default;
  template <class U>
  UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept {
    static_assert(std::is_trivially_copyable_v<U> && std::is_nothrow_default_constructible_v<U>);
    ::new (static_cast<void*>(p)) U;  // default-initialization: no write (but a member's own initializer)
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

// Arrays filled whole right away (the span path's scratch, the window
// vertices): sized without a write.
template <class T>
using FilledVector = std::vector<T, UninitializedAllocator<T>>;

}  // namespace ffsim

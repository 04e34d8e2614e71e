// A raster recording's arrays in a few large blocks (docs/performance.md 30.1).
//
// A recording (sim/raster_cache.h) holds, per group of runs, ten small arrays
// written once while the first pass draws and read by every replay: as
// std::vectors each was one malloc and one free, about 3 % of a terrain frame's
// samples. The arena hands out uninitialised storage by bumping a pointer in
// blocks that never move, so an array's address is stable while later groups
// are recorded, and frees everything at once with the recording.
//
// Like UninitializedAllocator, nothing is written: the owner writes every
// element before reading it (the memcheck CTests check that).
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <new>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

namespace ffsim {

// A length and a pointer into an arena: the read side of a recorded array.
template <class T>
struct ArenaArray {
  T* ptr = nullptr;
  std::uint32_t count = 0;

  T* data() const { return ptr; }
  std::size_t size() const { return count; }
  bool empty() const { return count == 0; }
  T* begin() const { return ptr; }
  T* end() const { return ptr + count; }
  T& operator[](std::size_t i) const { return ptr[i]; }
};

class RecordingArena {
 public:
  // Blocks start at kFirstBlock bytes and double up to kMaxBlock; a request
  // larger than the next block gets a block of its own size.
  static constexpr std::size_t kFirstBlock = std::size_t{16} << 10;
  static constexpr std::size_t kMaxBlock = std::size_t{1} << 20;
  static constexpr std::size_t kAlign = 32;  // (an AVX2 register)

  RecordingArena() = default;
  // A move takes the blocks (the arrays stay where they are) and leaves the
  // source empty, so that it cannot hand out the rest of a block it gave away.
  RecordingArena(RecordingArena&& o) noexcept { take(o); }
  RecordingArena& operator=(RecordingArena&& o) noexcept {
    if (this != &o) take(o);
    return *this;
  }
  RecordingArena(const RecordingArena&) = delete;
  RecordingArena& operator=(const RecordingArena&) = delete;

  // n elements of T, not initialised. Throws std::length_error beyond 2^32 - 1
  // elements (ArenaArray's count) and std::bad_alloc when memory runs out.
  template <class T>
  ArenaArray<T> make(std::size_t n) {
    static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);
    static_assert(alignof(T) <= kAlign);
    if (n > UINT32_MAX || n > SIZE_MAX / sizeof(T) - kAlign) throw std::length_error("recording arena: array too large");
    if (n == 0) return {};
    return {static_cast<T*>(bytes(n * sizeof(T))), static_cast<std::uint32_t>(n)};
  }

  // A copy of [first, first + n).
  template <class T>
  ArenaArray<T> copy(const T* first, std::size_t n) {
    ArenaArray<T> a = make<T>(n);
    if (n) std::memcpy(a.ptr, first, n * sizeof(T));
    return a;
  }

  // Bytes held in blocks (used or not): what the recording costs in memory.
  std::size_t capacity() const { return capacity_; }

 private:
  void* bytes(std::size_t n);
  void take(RecordingArena& o) noexcept {
    blocks_ = std::move(o.blocks_);
    o.blocks_.clear();
    next_ = std::exchange(o.next_, nullptr);
    left_ = std::exchange(o.left_, 0);
    capacity_ = std::exchange(o.capacity_, 0);
    next_block_ = std::exchange(o.next_block_, kFirstBlock);
  }

  struct Free {  // (blocks are allocated kAlign-aligned)
    void operator()(std::byte* p) const { ::operator delete(p, std::align_val_t{kAlign}); }
  };
  std::vector<std::unique_ptr<std::byte, Free>> blocks_;
  std::byte* next_ = nullptr;  // the current block's first free byte (aligned)
  std::size_t left_ = 0;       // bytes after next_ in the current block
  std::size_t capacity_ = 0;
  std::size_t next_block_ = kFirstBlock;
};

}  // namespace ffsim

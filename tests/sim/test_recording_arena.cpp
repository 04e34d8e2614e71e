// The recording arena (sim/recording_arena.h): a raster recording's arrays in
// blocks that never move. Checked here directly: every array aligned and
// disjoint from the others, its contents unchanged while many more arrays are
// made and after the arena is moved, block sizes as documented, and requests
// it cannot hold refused with an error instead of a short array.
#include <doctest/doctest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include "sim/recording_arena.h"

using namespace ffsim;

namespace {

bool aligned(const void* p) { return reinterpret_cast<std::uintptr_t>(p) % RecordingArena::kAlign == 0; }

}  // namespace

TEST_CASE("recording arena: arrays are aligned, disjoint and keep their contents") {
  std::mt19937 rng(20261206);
  std::uniform_int_distribution<std::size_t> len(0, 3000);
  RecordingArena arena;
  struct Made {
    ArenaArray<std::uint32_t> a;
    std::uint32_t seed;
  };
  std::vector<Made> made;
  std::size_t bytes = 0;
  for (std::uint32_t i = 0; i < 2000; ++i) {
    const std::size_t n = i % 97 == 0 ? 70000 : len(rng);  // (some larger than a block)
    Made m{arena.make<std::uint32_t>(n), i * 2654435761u};
    REQUIRE(m.a.size() == n);
    REQUIRE(m.a.empty() == (n == 0));
    if (n) REQUIRE(aligned(m.a.data()));
    for (std::size_t k = 0; k < n; ++k) m.a[k] = m.seed + static_cast<std::uint32_t>(k);
    bytes += n * sizeof(std::uint32_t);
    made.push_back(m);
  }
  CHECK(arena.capacity() >= bytes);
  CHECK(arena.capacity() < bytes + bytes / 2 + 2 * RecordingArena::kMaxBlock);  // (no block per array)
  RecordingArena moved = std::move(arena);  // (a recording is moved into the cache)
  for (const Made& m : made)
    for (std::size_t k = 0; k < m.a.size(); ++k)
      REQUIRE(m.a[k] == m.seed + static_cast<std::uint32_t>(k));  // an overlap or a moved block would change some
  CHECK(moved.capacity() >= bytes);
  // The source is left empty: what it makes next comes from a block of its own.
  CHECK(arena.capacity() == 0);
  const ArenaArray<std::uint32_t> fresh = arena.make<std::uint32_t>(1000);
  for (std::size_t k = 0; k < fresh.size(); ++k) fresh[k] = 0xDEADBEEFu;
  for (const Made& m : made)
    for (std::size_t k = 0; k < m.a.size(); ++k) REQUIRE(m.a[k] == m.seed + static_cast<std::uint32_t>(k));
  // Move assignment frees the target's blocks and takes the source's.
  moved = std::move(arena);
  CHECK(moved.capacity() == RecordingArena::kFirstBlock);
  CHECK(fresh[999] == 0xDEADBEEFu);
}

TEST_CASE("recording arena: block sizes, copies and the empty array") {
  RecordingArena arena;
  CHECK(arena.capacity() == 0);
  CHECK(arena.make<int>(0).data() == nullptr);
  CHECK(arena.capacity() == 0);  // (an empty array takes no block)
  const ArenaArray<std::uint8_t> one = arena.make<std::uint8_t>(1);
  CHECK(arena.capacity() == RecordingArena::kFirstBlock);
  const ArenaArray<std::uint8_t> two = arena.make<std::uint8_t>(1);
  CHECK(two.data() == one.data() + RecordingArena::kAlign);  // rounded up: the next array stays aligned
  // The rest of the first block, then a second one of twice the size.
  arena.make<std::uint8_t>(RecordingArena::kFirstBlock - 2 * RecordingArena::kAlign);
  CHECK(arena.capacity() == RecordingArena::kFirstBlock);
  arena.make<std::uint8_t>(1);
  CHECK(arena.capacity() == 3 * RecordingArena::kFirstBlock);
  // A request larger than the next block: a block of its own size.
  const std::size_t big = 5 * RecordingArena::kMaxBlock + 3;
  arena.make<std::uint8_t>(big);
  CHECK(arena.capacity() == 3 * RecordingArena::kFirstBlock + (big + RecordingArena::kAlign - 1) / RecordingArena::kAlign * RecordingArena::kAlign);
  // Copies of a trivially copyable array.
  const std::array<std::array<std::int64_t, 3>, 4> w{{{1, -2, 3}, {4, 5, -6}, {INT64_MIN, 0, INT64_MAX}, {7, 8, 9}}};
  const ArenaArray<std::array<std::int64_t, 3>> c = arena.copy(w.data(), w.size());
  REQUIRE(c.size() == 4);
  CHECK(aligned(c.data()));
  CHECK(std::memcmp(c.data(), w.data(), sizeof w) == 0);
  CHECK(arena.copy(w.data(), 0).empty());
}

TEST_CASE("recording arena: sizes it cannot hold are refused") {
  RecordingArena arena;
  CHECK_THROWS_AS(arena.make<std::uint8_t>(std::size_t{UINT32_MAX} + 1), std::length_error);
  CHECK_THROWS_AS(arena.make<std::uint64_t>(SIZE_MAX / 4), std::length_error);
  CHECK(arena.capacity() == 0);  // nothing was allocated
}

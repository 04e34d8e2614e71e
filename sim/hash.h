// Stable content hashes of buffers, so bit-exactness can be checked across
// machines, compilers and builds. Algorithm (docs/numerics.md §5, "Content hash"):
//
//   FNV-1a, 64-bit (offset basis 0xcbf29ce484222325, prime 0x100000001b3), over
//   the byte string
//     "ffsim1" | kind (1 byte: 'C' color, 'A' alpha, 'S' stencil, 'D' depth)
//     | width (u32 LE) | height (u32 LE) | channels (u8) | encoding (u8) | bits (u8)
//     | the values, rows bottom to top, pixels left to right, channels R,G,B,A
//   encoding 0: unsigned codes, 1 byte each when bits <= 8, 2 bytes LE when
//               bits <= 16, else 4 bytes LE (24-bit depth);
//   encoding 1: binary64 values, 8 bytes LE (negative zero written as +0).
//   Printed as 16 lower-case hex digits.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "sim/framebuffer.h"

namespace ffsim {

enum class BufferKind { Color, Alpha, Stencil, Depth };

// Throws FramebufferError if the buffer does not exist (no stencil/depth buffer).
std::uint64_t buffer_hash(const Framebuffer& fb, BufferKind kind);
std::string hash_hex(std::uint64_t h);

// One multiply-xorshift step, for the in-memory caches' keys (sim/raster_cache,
// sim/geometry_memo; not a stable format: nothing outside a run sees these).
inline void hash_mix(std::uint64_t& h, std::uint64_t v) {
  h = (h ^ v) * 0xBF58476D1CE4E5B9ull;
  h ^= h >> 29;
}

// A fast hash of a byte string for the in-memory caches (sim/upload_cache: the
// client bytes of an upload): eight 32-bit lanes of multiply-xorshift over 32-byte
// blocks (one vector; four vectors over 128-byte blocks), then the lanes, the tail
// and the length through hash_mix. Not a stable format, and a collision costs only a
// comparison: the caches compare the bytes themselves.
std::uint64_t bytes_hash(const void* data, std::size_t n, std::uint64_t seed = 0);

// FNV-1a 64 incremental helper (exposed for tests and for hashing other data).
struct Fnv1a64 {
  std::uint64_t state = 0xcbf29ce484222325ull;
  void byte(std::uint8_t b) { state = (state ^ b) * 0x100000001b3ull; }
  void bytes(const void* p, std::size_t n) {
    const auto* b = static_cast<const std::uint8_t*>(p);
    for (std::size_t i = 0; i < n; ++i) byte(b[i]);
  }
  void u32(std::uint32_t v) { for (int i = 0; i < 4; ++i) byte(static_cast<std::uint8_t>(v >> (8 * i))); }
  void u64(std::uint64_t v) { for (int i = 0; i < 8; ++i) byte(static_cast<std::uint8_t>(v >> (8 * i))); }
};

}  // namespace ffsim

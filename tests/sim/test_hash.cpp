// Content hashes are stable across machines and builds. The expected values were
// computed independently from the algorithm in sim/hash.h with this Python,
// which re-implements both FNV-1a and the fill of sim/test_pattern.h:
//
//   def fnv(d):
//       h = 0xcbf29ce484222325
//       for b in d: h = ((h ^ b) * 0x100000001b3) & (2**64 - 1)
//       return h
//   W, H = 64, 32
//   def hdr(k, ch, enc, bits):
//       return b"ffsim1" + k + W.to_bytes(4, "little") + H.to_bytes(4, "little") + bytes([ch, enc, bits])
//   col, alp, st, de = hdr(b"C",4,0,8), hdr(b"A",1,0,8), hdr(b"S",1,0,8), hdr(b"D",1,0,24)
//   for y in range(H):
//       for x in range(W):
//           R, G = 255*x//(W-1), 255*y//(H-1)
//           B, A = 255*((x//8 + y//8) % 2), (x ^ y) & 255
//           col += bytes([R, G, B, A]); alp += bytes([A]); st += bytes([(x + 2*y) & 255])
//           de += ((2*(x+y)*16777215 + (W+H-2)) // (2*(W+H-2))).to_bytes(4, "little")
//   print(["%016x" % fnv(d) for d in (col, alp, st, de)])
//
// The same test runs in the Release and the sanitizer builds (CI runs both), so
// equal hashes there are asserted by this one expectation.
#include <doctest/doctest.h>

#include <set>
#include <vector>

#include "sim/hash.h"
#include "sim/test_pattern.h"

using namespace ffsim;

TEST_CASE("hash: known hashes of the 64x32 test pattern (geforce256 formats)") {
  FramebufferFormat f;
  f.width = 64;
  f.height = 32;
  Framebuffer fb(f);
  fill_test_pattern(fb);
  CHECK(hash_hex(buffer_hash(fb, BufferKind::Color)) == "de6cdbea06575ef4");
  CHECK(hash_hex(buffer_hash(fb, BufferKind::Alpha)) == "93023a039bd3f3b9");
  CHECK(hash_hex(buffer_hash(fb, BufferKind::Stencil)) == "5d7ff19c127ba1d7");
  CHECK(hash_hex(buffer_hash(fb, BufferKind::Depth)) == "1acd08175725e9d0");
}

TEST_CASE("hash: any single changed value changes the hash, kinds and sizes are distinguished") {
  FramebufferFormat f;
  f.width = 16;
  f.height = 16;
  Framebuffer fb(f);
  fill_test_pattern(fb);
  const auto h0 = buffer_hash(fb, BufferKind::Color);
  fb.codes()[4 * fb.index(5, 9) + 2] ^= 1;
  CHECK(buffer_hash(fb, BufferKind::Color) != h0);
  f.width = 8;
  f.height = 32;  // same number of pixels, different shape
  Framebuffer fb2(f);
  Framebuffer fb3(FramebufferFormat{16, 16});
  CHECK(buffer_hash(fb2, BufferKind::Color) != buffer_hash(fb3, BufferKind::Color));
  CHECK(buffer_hash(fb3, BufferKind::Color) != buffer_hash(fb3, BufferKind::Alpha));
}

TEST_CASE("hash: a missing buffer is an error, not a silent hash") {
  FramebufferFormat f;
  f.stencil_bits = 0;
  f.depth_bits = 0;
  Framebuffer fb(f);
  CHECK_THROWS_AS(buffer_hash(fb, BufferKind::Stencil), FramebufferError);
  CHECK_THROWS_AS(buffer_hash(fb, BufferKind::Depth), FramebufferError);
}

TEST_CASE("bytes_hash: every byte, the length and the seed change it") {
  // The upload cache's hash (sim/hash.h): 128-byte blocks in four vectors of
  // eight lanes, then 32-byte blocks, then a tail. 300 bytes: two 128-byte blocks,
  // one 32-byte block and a 12-byte tail; each single-bit change, in every
  // position, must change the hash (a lane, a vector or the tail dropped would not).
  std::vector<unsigned char> b(300);
  for (std::size_t i = 0; i < b.size(); ++i) b[i] = static_cast<unsigned char>(i * 37 + 11);
  const std::uint64_t h = bytes_hash(b.data(), b.size());
  CHECK(bytes_hash(b.data(), b.size()) == h);  // deterministic
  std::set<std::uint64_t> seen{h};
  for (std::size_t i = 0; i < b.size(); ++i)
    for (int bit : {0, 7}) {
      b[i] ^= static_cast<unsigned char>(1 << bit);
      seen.insert(bytes_hash(b.data(), b.size()));
      b[i] ^= static_cast<unsigned char>(1 << bit);
    }
  CHECK(seen.size() == 1 + 2 * b.size());
  // Trailing zeros are not the shorter string; the seed separates equal bytes.
  std::vector<unsigned char> z(64, 0);
  CHECK(bytes_hash(z.data(), 32) != bytes_hash(z.data(), 64));
  CHECK(bytes_hash(z.data(), 0) != bytes_hash(z.data(), 1));
  CHECK(bytes_hash(b.data(), b.size(), 1) != h);
}

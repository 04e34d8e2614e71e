#include "sim/hash.h"

#include <bit>
#include <cstdio>
#include <cstring>

namespace ffsim {

namespace {
void header(Fnv1a64& h, char kind, const Framebuffer& fb, int channels, int encoding, int bits) {
  h.bytes("ffsim1", 6);
  h.byte(static_cast<std::uint8_t>(kind));
  h.u32(static_cast<std::uint32_t>(fb.width()));
  h.u32(static_cast<std::uint32_t>(fb.height()));
  h.byte(static_cast<std::uint8_t>(channels));
  h.byte(static_cast<std::uint8_t>(encoding));
  h.byte(static_cast<std::uint8_t>(bits));
}
void code(Fnv1a64& h, std::uint32_t v, int bits) {
  h.byte(static_cast<std::uint8_t>(v));
  if (bits > 8) h.byte(static_cast<std::uint8_t>(v >> 8));
  if (bits > 16) { h.byte(static_cast<std::uint8_t>(v >> 16)); h.byte(static_cast<std::uint8_t>(v >> 24)); }
}
void value(Fnv1a64& h, double v) { h.u64(std::bit_cast<std::uint64_t>(v == 0.0 ? 0.0 : v)); }
}  // namespace

std::uint64_t buffer_hash(const Framebuffer& fb, BufferKind kind) {
  Fnv1a64 h;
  const std::size_t n = static_cast<std::size_t>(fb.width()) * fb.height();
  const auto& f = fb.format();
  switch (kind) {
    case BufferKind::Color:
    case BufferKind::Alpha: {
      const bool alpha = kind == BufferKind::Alpha;
      const int first = alpha ? 3 : 0;
      header(h, alpha ? 'A' : 'C', fb, alpha ? 1 : 4, f.float_color() ? 1 : 0, f.float_color() ? 64 : f.color_bits);
      for (std::size_t i = 0; i < n; ++i)
        for (int c = first; c < 4; ++c) {
          if (f.float_color()) value(h, fb.values()[4 * i + c]);
          else code(h, fb.codes()[4 * i + c], f.color_bits);
        }
      break;
    }
    case BufferKind::Stencil:
      if (!fb.has_stencil()) throw FramebufferError("the framebuffer has no stencil buffer");
      header(h, 'S', fb, 1, 0, f.stencil_bits);
      for (std::size_t i = 0; i < n; ++i) code(h, fb.stencil()[i], f.stencil_bits);
      break;
    case BufferKind::Depth:
      if (!fb.has_depth()) throw FramebufferError("the framebuffer has no depth buffer");
      header(h, 'D', fb, 1, 0, f.depth_bits);
      for (std::size_t i = 0; i < n; ++i) code(h, fb.depth()[i], f.depth_bits);
      break;
  }
  return h.state;
}

std::string hash_hex(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

std::uint64_t bytes_hash(const void* data, std::size_t n, std::uint64_t seed) {
  // Eight 32-bit lanes as one vector (GCC/Clang vector extension: one AVX2
  // register, two SSE ones, or scalar code, as the target has); four of them over
  // 128-byte blocks, so that the multiplies do not wait for each other.
  using Lanes = std::uint32_t __attribute__((vector_size(32)));
  const Lanes init = {0x9E3779B9u, 0x3C6EF372u, 0xDAA66D2Bu, 0x78DDE6E4u,
                      0x1715609Du, 0xB54CDA56u, 0x5384540Fu, 0xF1BBCDC8u};
  Lanes acc[4] = {init, init + 1u, init + 2u, init + 3u};
  const auto step = [](Lanes& a, const unsigned char* p) {
    Lanes w;
    std::memcpy(&w, p, sizeof w);
    const Lanes x = (a ^ w) * 0x85EBCA6Bu;
    a = x ^ (x >> 13);
  };
  const auto* b = static_cast<const unsigned char*>(data);
  std::size_t i = 0;
  for (; i + 4 * sizeof(Lanes) <= n; i += 4 * sizeof(Lanes))
    for (int a = 0; a < 4; ++a) step(acc[a], b + i + a * sizeof(Lanes));
  for (; i + sizeof(Lanes) <= n; i += sizeof(Lanes)) step(acc[0], b + i);
  std::uint64_t h = seed ^ n;
  for (const Lanes& a : acc)
    for (int k = 0; k < 8; ++k) hash_mix(h, a[k]);
  for (; i < n; ++i) hash_mix(h, b[i]);  // the tail, under 32 bytes
  return h;
}

}  // namespace ffsim

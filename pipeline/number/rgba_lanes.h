// Interleaved RGBA codes (4 × 16 bits per pixel, as the framebuffer and the span
// buffers hold them) to and from four channel arrays of 32-bit lanes, four pixels
// at a time in SSE registers. Pure data movement: the same integers.
#pragma once
#include <cstdint>

#ifdef __SSE4_1__
#include <immintrin.h>

namespace ffsim {

// Pixels 0, 1 in x01 and 2, 3 in x23 (R, G, B, A each) -> r[0..3], g[0..3],
// b[0..3], a[0..3], zero-extended (T: a 32-bit integer type).
template <class T>
inline void rgba16_to_lanes(__m128i x01, __m128i x23, T* r, T* g, T* b, T* a) {
  static_assert(sizeof(T) == 4);
  const __m128i t0 = _mm_unpacklo_epi16(x01, x23), t1 = _mm_unpackhi_epi16(x01, x23);  // r0 r2 g0 g2 .., r1 r3 ..
  const __m128i rg = _mm_unpacklo_epi16(t0, t1), ba = _mm_unpackhi_epi16(t0, t1);      // r0..r3 g0..g3, b0..b3 a0..a3
  _mm_storeu_si128(reinterpret_cast<__m128i*>(r), _mm_cvtepu16_epi32(rg));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(g), _mm_cvtepu16_epi32(_mm_srli_si128(rg, 8)));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(b), _mm_cvtepu16_epi32(ba));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(a), _mm_cvtepu16_epi32(_mm_srli_si128(ba, 8)));
}

// Four interleaved pixels from RGBA codes of 8 consecutive 16-bit values.
inline void rgba16_to_lanes(const std::uint16_t* codes, std::int32_t* r, std::int32_t* g, std::int32_t* b,
                            std::int32_t* a) {
  rgba16_to_lanes(_mm_loadu_si128(reinterpret_cast<const __m128i*>(codes)),
                  _mm_loadu_si128(reinterpret_cast<const __m128i*>(codes + 8)), r, g, b, a);
}

}  // namespace ffsim

#endif

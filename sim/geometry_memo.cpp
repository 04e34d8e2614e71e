#include "sim/geometry_memo.h"

#include <cstddef>
#include <cstring>

#ifdef __AVX2__
#include <immintrin.h>
#endif

namespace ffsim {

std::uint64_t GeometryMemo::hash_key(const GeometryKey& key, std::size_t n) {
  std::uint64_t h = 0x9E3779B97F4A7C15ull ^ n;
  h = (h ^ (std::uint64_t{key.mode} << 16 ^ static_cast<std::uint64_t>(key.subpixel_bits) << 8 ^
            static_cast<std::uint64_t>(key.depth_bits))) * 0xBF58476D1CE4E5B9ull;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      mix(h, key.modelview[c][r]);
      mix(h, key.projection[c][r]);
    }
  for (const double v : {key.hw, key.hh, key.depth_near, key.depth_far}) mix(h, v);
  return h;
}

bool GeometryMemo::same_key(const GeometryKey& a, const GeometryKey& b) {
  auto same = [](const auto& x, const auto& y) { return std::memcmp(&x, &y, sizeof x) == 0; };  // bit for bit
  return a.mode == b.mode && a.subpixel_bits == b.subpixel_bits && a.depth_bits == b.depth_bits &&
         same(a.modelview, b.modelview) && same(a.projection, b.projection) && same(a.hw, b.hw) && same(a.hh, b.hh) &&
         same(a.depth_near, b.depth_near) && same(a.depth_far, b.depth_far);
}

void rebase_triangles(const BatchMemo::Triangle* in_triangles, std::size_t n, std::uint32_t base,
                      BatchMemo::Triangle* out_triangles) {
  static_assert(sizeof(BatchMemo::Triangle) == 5 * sizeof(std::uint32_t) && offsetof(BatchMemo::Triangle, r0) == 12,
                "five words, the indices first");
  const auto* in = reinterpret_cast<const std::uint32_t*>(in_triangles);  // (int rows: the same bits as uint32_t)
  auto* out = reinterpret_cast<std::uint32_t*>(out_triangles);
  std::size_t t = 0;
#ifdef __AVX2__
  // Word w of a block of eight triangles is a vertex index when w mod 5 < 3:
  // vector k (words 8k .. 8k + 7) adds base in those lanes, 0 in the others.
  __m256i add[5];
  for (int k = 0; k < 5; ++k) {
    alignas(32) std::uint32_t lane[8];
    for (int j = 0; j < 8; ++j) lane[j] = (8 * k + j) % 5 < 3 ? base : 0u;
    add[k] = _mm256_load_si256(reinterpret_cast<const __m256i*>(lane));
  }
  for (; t + 8 <= n; t += 8) {
    const std::uint32_t* src = in + 5 * t;
    std::uint32_t* dst = out + 5 * t;
    for (int k = 0; k < 5; ++k)
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(dst + 8 * k),
                          _mm256_add_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(src + 8 * k)), add[k]));
  }
#endif
  for (; t < n; ++t) {
    const std::uint32_t* src = in + 5 * t;
    std::uint32_t* dst = out + 5 * t;
    for (int k = 0; k < 3; ++k) dst[k] = base + src[k];
    dst[3] = src[3];
    dst[4] = src[4];
  }
}

void GeometryMemo::clear() {
  entries_.clear();
  vertices_ = 0;
}

}  // namespace ffsim

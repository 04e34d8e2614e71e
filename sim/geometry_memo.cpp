#include "sim/geometry_memo.h"

#include <cstring>

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

void GeometryMemo::clear() {
  entries_.clear();
  vertices_ = 0;
}

}  // namespace ffsim

#include "sim/raster_cache.h"

#include <utility>

#include "sim/hash.h"

namespace ffsim {

namespace {

template <class T, class A>
std::size_t bytes_of(const std::vector<T, A>& v) {
  return v.size() * sizeof(T);
}

}  // namespace

std::size_t RasterRecording::bytes() const {
  return sizeof(*this) + bytes_of(steps) + bytes_of(groups) + bytes_of(long_runs) + bytes_of(band_triangles) + arena.capacity();
}

std::uint64_t RasterCache::hash(const std::vector<std::int64_t>& key) {
  // Four independent multiply-xorshift lanes (a key is a few thousand words per
  // glEnd; one serial chain of multiplies was 2 % of a terrain frame), folded at
  // the end. The key itself is compared on a match.
  constexpr std::uint64_t kAdd = 0x9E3779B97F4A7C15ull;
  std::array<std::uint64_t, 4> h{kAdd ^ key.size(), kAdd * 3, kAdd * 5, kAdd * 7};
  auto mix = [](std::uint64_t& a, std::int64_t k) { hash_mix(a, static_cast<std::uint64_t>(k)); };
  std::size_t i = 0;
  for (; i + 4 <= key.size(); i += 4)
    for (std::size_t j = 0; j < 4; ++j) mix(h[j], key[i + j]);
  for (std::size_t j = 0; i < key.size(); ++i, ++j) mix(h[j], key[i]);
  std::uint64_t r = h[0];
  for (std::size_t j = 1; j < 4; ++j) mix(r, static_cast<std::int64_t>(h[j]));
  return r;
}

const std::vector<RasterRecording>* RasterCache::find(const std::vector<std::int64_t>& key) {
  const auto it = entries_.find(hash(key));
  if (it == entries_.end() || it->second.key != key) {
    ++misses_;
    return nullptr;
  }
  ++hits_;
  return &it->second.recordings;
}

void RasterCache::insert(std::vector<std::int64_t> key, std::vector<RasterRecording> recordings) {
  Entry e;
  e.bytes = bytes_of(key);
  for (const RasterRecording& r : recordings) e.bytes += r.bytes();
  if (e.bytes > kMaxBytes) return;  // never kept
  if (bytes_ + e.bytes > kMaxBytes) clear();
  const std::uint64_t h = hash(key);
  e.key = std::move(key);
  e.recordings = std::move(recordings);
  const auto it = entries_.find(h);
  if (it != entries_.end()) {  // another key of the same hash: replaced
    bytes_ -= it->second.bytes;
    entries_.erase(it);
  }
  bytes_ += e.bytes;
  entries_.emplace(h, std::move(e));
}

void RasterCache::clear() {
  entries_.clear();
  bytes_ = 0;
}

}  // namespace ffsim

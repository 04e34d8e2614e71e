#include "sim/raster_cache.h"

#include <utility>

namespace ffsim {

namespace {

template <class T>
std::size_t bytes_of(const std::vector<T>& v) {
  return v.size() * sizeof(T);
}

}  // namespace

std::size_t RasterRecording::bytes() const {
  std::size_t b = sizeof(*this) + bytes_of(steps) + bytes_of(groups) + bytes_of(long_runs);
  for (const RecordedGroup& g : groups)
    b += bytes_of(g.weight) + bytes_of(g.run_y) + bytes_of(g.run_x0) + bytes_of(g.run_length) + bytes_of(g.triangles) +
         bytes_of(g.depth);
  return b;
}

std::uint64_t RasterCache::hash(const std::vector<std::int64_t>& key) {
  // A 64-bit multiply-xorshift mix per word (the key is compared on a match).
  std::uint64_t h = 0x9E3779B97F4A7C15ull ^ key.size();
  for (const std::int64_t k : key) {
    h ^= static_cast<std::uint64_t>(k) + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    h *= 0xBF58476D1CE4E5B9ull;
    h ^= h >> 31;
  }
  return h;
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

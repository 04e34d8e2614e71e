#include "sim/upload_cache.h"

#include <iterator>
#include <utility>

#include "sim/hash.h"

namespace ffsim {

namespace {

template <class T>
void append_vector(std::string& key, const std::vector<T>& v) {
  append_bytes(key, v.size());  // the size first: [1, 2] + [3] differs from [1] + [2, 3]
  key.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

void append_table(std::string& key, const pixel::ColorTable& t) {
  append_bytes(key, t.enabled);
  append_bytes(key, t.internal_format);
  append_bytes(key, t.base);
  append_bytes(key, t.width);
  append_vector(key, t.entries);
  append_bytes(key, t.scale);
  append_bytes(key, t.bias);
}

void append_filter(std::string& key, const pixel::ConvolutionFilter& f) {
  append_bytes(key, f.enabled);
  append_bytes(key, f.internal_format);
  append_bytes(key, f.base);
  append_bytes(key, f.width);
  append_bytes(key, f.height);
  append_vector(key, f.taps);
  append_vector(key, f.row);
  append_vector(key, f.column);
  append_bytes(key, f.border_mode);
  append_bytes(key, f.border_color);
  append_bytes(key, f.filter_scale);
  append_bytes(key, f.filter_bias);
}

// Every field of these structs is written out below, one by one. A field added to
// them changes their size: these fail until it is added to the key too (x86-64
// sizes; other targets skip the check).
#if defined(__x86_64__) && defined(__GLIBCXX__)
static_assert(sizeof(pixel::PixelStoreModes) == 20, "a new unpack mode: add it to append_transfer_key");
static_assert(sizeof(pixel::PixelTransferState) == 344, "a new transfer field: add it to append_transfer_key");
static_assert(sizeof(pixel::ColorTable) == 104, "a new colour-table field: add it to append_table");
static_assert(sizeof(pixel::ConvolutionFilter) == 200, "a new filter field: add it to append_filter");
static_assert(sizeof(pixel::ImagingState) == 912, "a new imaging field: add it to append_transfer_key");
#endif

}  // namespace

void append_transfer_key(std::string& key, const pixel::PixelStoreModes& u, const pixel::TransferInputs& in) {
  append_bytes(key, u.swap_bytes);
  append_bytes(key, u.lsb_first);
  append_bytes(key, u.row_length);
  append_bytes(key, u.skip_rows);
  append_bytes(key, u.skip_pixels);
  append_bytes(key, u.alignment);
  const pixel::PixelTransferState& p = in.transfer;
  append_bytes(key, p.map_color);
  append_bytes(key, p.map_stencil);
  append_bytes(key, p.index_shift);
  append_bytes(key, p.index_offset);
  append_bytes(key, p.scale);
  append_bytes(key, p.bias);
  append_bytes(key, p.depth_scale);
  append_bytes(key, p.depth_bias);
  append_bytes(key, p.post_convolution_scale);
  append_bytes(key, p.post_convolution_bias);
  append_bytes(key, p.post_color_matrix_scale);
  append_bytes(key, p.post_color_matrix_bias);
  for (const auto& m : p.color_maps) append_vector(key, m);
  append_vector(key, p.stencil_map);
  for (const auto& t : in.imaging.tables) append_table(key, t);
  append_filter(key, in.imaging.conv1d);
  append_filter(key, in.imaging.conv2d);
  append_filter(key, in.imaging.separable2d);
  append_bytes(key, in.color_matrix);
}

UploadKey UploadKey::make(std::string head, std::string_view data) {
  UploadKey k{std::move(head), data, 0};
  k.hash = bytes_hash(k.data.data(), k.data.size(), bytes_hash(k.head.data(), k.head.size()));
  return k;
}

std::size_t UploadCache::cost(std::size_t head, std::size_t data, const TextureImage& im) {
  return head + data + im.codes.size() * sizeof(std::uint16_t) + im.values.size() * sizeof(double);
}

UploadCache::Order::iterator UploadCache::lookup(const UploadKey& key) {
  const auto [lo, hi] = index_.equal_range(key.hash);
  for (auto it = lo; it != hi; ++it) {
    const Entry& e = *it->second;
    if (e.head == key.head && e.data == key.data) return it->second;  // every input equal
  }
  return order_.end();
}

const TextureImage* UploadCache::find(const UploadKey& key) {
  const auto it = lookup(key);
  if (it == order_.end()) {
    ++misses_;
    return nullptr;
  }
  ++hits_;
  return &it->image;
}

void UploadCache::insert(const UploadKey& key, const TextureImage& image) {
  // Admission: stored on the second offer of the same inputs (by hash; a collision
  // only stores an entry early).
  if (seen_.erase(key.hash) == 0) {
    if (seen_.size() >= kSeenLimit) seen_.clear();
    seen_.insert(key.hash);
    return;
  }
  const std::size_t c = cost(key.head.size(), key.data.size(), image);
  if (c > budget_ || lookup(key) != order_.end()) return;
  while (bytes_ + c > budget_ && !order_.empty()) {  // oldest first
    const Entry& old = order_.front();
    const auto [lo, hi] = index_.equal_range(old.hash);
    for (auto it = lo; it != hi; ++it)
      if (&*it->second == &old) {
        index_.erase(it);
        break;
      }
    bytes_ -= cost(old.head.size(), old.data.size(), old.image);
    order_.pop_front();
  }
  bytes_ += c;
  order_.push_back({key.hash, key.head, std::string(key.data), image});
  index_.emplace(key.hash, std::prev(order_.end()));
}

void UploadCache::clear() {
  order_.clear();
  index_.clear();
  seen_.clear();
  bytes_ = 0;
}

}  // namespace ffsim

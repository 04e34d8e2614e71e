// The texture-upload cache (docs/performance.md §10.3, §24.1): glTexImage1D/2D of
// client data stores a pure function of (the client bytes the unpack reads, the
// call's arguments, the unpack modes, the whole pixel-transfer state, the colour
// matrix) in a fixed profile. A trace that uploads the same image under the same
// state again (the paper's passes re-specify their maps every frame) gets the
// stored TextureImage back instead of unpacking, transferring and converting it
// anew.
//
// A hit compares the inputs themselves, byte for byte (the serialised arguments
// and state, then the client bytes), not only their hash: a hash collision cannot
// return a wrong image. An upload is stored the second time its inputs are seen
// (admission: the first time only its 64-bit hash is remembered), so an image
// uploaded once costs a hash, not a copy of its bytes and of its level. Entries
// are evicted oldest first beyond a byte budget.
#pragma once
#include <cstddef>
#include <cstdint>
#include <list>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>

#include "pipeline/pixel_transfer/pixel_state.h"
#include "pipeline/pixel_transfer/transfer_plan.h"
#include "pipeline/texture/texture_object.h"

namespace ffsim {

// The inputs of one upload: `head` the call's arguments and the state,
// serialised (append_bytes, append_transfer_key); `data` the client bytes the
// unpack reads (not copied); `hash` of both (UploadKey::make).
struct UploadKey {
  std::string head;
  std::string_view data;
  std::uint64_t hash = 0;
  static UploadKey make(std::string head, std::string_view data);
};

class UploadCache {
 public:
  explicit UploadCache(std::size_t budget_bytes = std::size_t{64} << 20) : budget_(budget_bytes) {}

  // The stored image for `key`, or nullptr.
  const TextureImage* find(const UploadKey& key);
  // Offers `image` as the result of `key`: the first offer of a key remembers its
  // hash only; a later one stores a copy (evicting the oldest entries beyond the
  // budget; an entry larger than the whole budget is not stored).
  void insert(const UploadKey& key, const TextureImage& image);
  void clear();

  std::uint64_t hits() const { return hits_; }
  std::uint64_t misses() const { return misses_; }
  std::size_t bytes() const { return bytes_; }  // inputs + texels held
  std::size_t entries() const { return order_.size(); }

  // The hashes remembered for admission are forgotten all at once beyond this many.
  static constexpr std::size_t kSeenLimit = 4096;

 private:
  struct Entry {
    std::uint64_t hash;
    std::string head, data;
    TextureImage image;
  };
  using Order = std::list<Entry>;  // oldest first
  static std::size_t cost(std::size_t head, std::size_t data, const TextureImage& im);
  Order::iterator lookup(const UploadKey& key);
  std::size_t budget_;
  std::size_t bytes_ = 0;
  std::uint64_t hits_ = 0, misses_ = 0;
  Order order_;
  std::unordered_multimap<std::uint64_t, Order::iterator> index_;  // hash -> entries
  std::unordered_set<std::uint64_t> seen_;                          // offered once, not stored
};

// Appends to `key` every input of a client-data texture upload but the call's own
// arguments (which the caller appends): the unpack modes and the pixel-transfer
// state that plan_transfer / run_plan read.
void append_transfer_key(std::string& key, const pixel::PixelStoreModes& unpack, const pixel::TransferInputs& in);

// Appends the raw bytes of a trivially copyable value.
template <class T>
void append_bytes(std::string& key, const T& v) {
  key.append(reinterpret_cast<const char*>(&v), sizeof v);
}

}  // namespace ffsim

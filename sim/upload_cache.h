// The texture-upload cache (docs/performance.md §10): glTexImage1D/2D of client
// data stores a pure function of (the client bytes the unpack reads, the call's
// arguments, the unpack modes, the whole pixel-transfer state, the colour matrix)
// in a fixed profile. A trace that uploads the same image under the same state
// again (the paper's passes re-specify their maps every frame) gets the stored
// TextureImage back instead of unpacking, transferring and converting it anew.
//
// The key is those inputs themselves, serialised byte for byte, not a hash of
// them: a hit means every input is equal (a hash collision cannot return a wrong
// image). Entries are evicted oldest first beyond a byte budget.
#pragma once
#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <unordered_map>

#include "pipeline/pixel_transfer/pixel_state.h"
#include "pipeline/pixel_transfer/transfer_plan.h"
#include "pipeline/texture/texture_object.h"

namespace ffsim {

class UploadCache {
 public:
  explicit UploadCache(std::size_t budget_bytes = std::size_t{64} << 20) : budget_(budget_bytes) {}

  // The stored image for `key`, or nullptr.
  const TextureImage* find(const std::string& key);
  // Stores `image` under `key` (evicting the oldest entries beyond the budget; an
  // entry larger than the whole budget is not stored).
  void insert(std::string key, const TextureImage& image);
  void clear();

  std::uint64_t hits() const { return hits_; }
  std::uint64_t misses() const { return misses_; }
  std::size_t bytes() const { return bytes_; }  // keys + texels held
  std::size_t entries() const { return map_.size(); }

 private:
  static std::size_t cost(const std::string& key, const TextureImage& im);
  std::size_t budget_;
  std::size_t bytes_ = 0;
  std::uint64_t hits_ = 0, misses_ = 0;
  std::unordered_map<std::string, TextureImage> map_;
  std::deque<const std::string*> order_;  // the map's keys (stable in its nodes), oldest first
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

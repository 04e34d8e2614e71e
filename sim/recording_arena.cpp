#include "sim/recording_arena.h"

#include <algorithm>
#include <utility>

namespace ffsim {

void* RecordingArena::bytes(std::size_t n) {
  const std::size_t rounded = (n + kAlign - 1) / kAlign * kAlign;  // (the next array stays aligned)
  if (rounded > left_) {
    const std::size_t size = std::max(next_block_, rounded);
    std::unique_ptr<std::byte, Free> block(static_cast<std::byte*>(::operator new(size, std::align_val_t{kAlign})));
    next_ = block.get();
    blocks_.push_back(std::move(block));  // (frees the block if this throws)
    left_ = size;
    capacity_ += size;
    next_block_ = std::min(next_block_ * 2, kMaxBlock);
  }
  void* p = next_;
  next_ += rounded;
  left_ -= rounded;
  return p;
}

}  // namespace ffsim

#pragma once
// Open-addressing map from a 64-bit key to a dense index, for deduplicating millions of items (trip
// requests, vehicle ids) where node-based maps spend their time chasing pointers. Keys are expected to be
// well mixed. Equal keys do not have to mean equal items: the caller's `same` check decides, so a key
// may be a hash.
#include <cstdint>
#include <vector>

#include "kernels/rng.hpp"

namespace lpsim {

class FlatIndex {
 public:
  static constexpr uint32_t kEmpty = 0xFFFFFFFFu;

  explicit FlatIndex(size_t expected = 16) { rehash(capacity_for(expected)); }

  /// The index already stored under `key` for which same(index) holds, or else stores `index` and
  /// returns it.
  template <class Same>
  uint32_t find_or_insert(uint64_t key, uint32_t index, Same&& same) {
    if (2 * (size_ + 1) > keys_.size()) rehash(keys_.size() * 2);
    for (size_t slot = rng_mix64(key) & mask_;; slot = (slot + 1) & mask_) {
      if (values_[slot] == kEmpty) {
        keys_[slot] = key;
        values_[slot] = index;
        ++size_;
        return index;
      }
      if (keys_[slot] == key && same(values_[slot])) return values_[slot];
    }
  }

  /// The index stored under `key` for which same(index) holds, or kEmpty.
  template <class Same>
  uint32_t find(uint64_t key, Same&& same) const {
    for (size_t slot = rng_mix64(key) & mask_;; slot = (slot + 1) & mask_) {
      if (values_[slot] == kEmpty) return kEmpty;
      if (keys_[slot] == key && same(values_[slot])) return values_[slot];
    }
  }

 private:
  static size_t capacity_for(size_t n) {
    size_t c = 16;
    while (c < 2 * n) c *= 2;
    return c;
  }
  void rehash(size_t capacity) {
    std::vector<uint64_t> old_keys = std::move(keys_);
    std::vector<uint32_t> old_values = std::move(values_);
    keys_.assign(capacity, 0);
    values_.assign(capacity, kEmpty);
    mask_ = capacity - 1;
    for (size_t i = 0; i < old_values.size(); ++i) {
      if (old_values[i] == kEmpty) continue;
      size_t slot = rng_mix64(old_keys[i]) & mask_;
      while (values_[slot] != kEmpty) slot = (slot + 1) & mask_;
      keys_[slot] = old_keys[i];
      values_[slot] = old_values[i];
    }
  }

  std::vector<uint64_t> keys_;
  std::vector<uint32_t> values_;
  size_t mask_ = 0, size_ = 0;
};

}  // namespace lpsim

#pragma once
// Host emulation of cub::DeviceRadixSort::SortPairs (see tests/cuda_emulation/cuda_runtime.h).
#include <cuda_runtime.h>

#include <algorithm>
#include <numeric>
#include <vector>

#include "cub/device/temp_storage.hpp"

namespace cub {

struct DeviceRadixSort {
  /// (key, value) pairs sorted by key into the out arrays, stably, as a radix sort is.
  template <class Key, class Value>
  static cudaError_t SortPairs(void* temp, size_t& bytes, const Key* keys_in, Key* keys_out,
                               const Value* values_in, Value* values_out, int64_t n, int = 0,
                               int = static_cast<int>(sizeof(Key) * 8), cudaStream_t = nullptr) {
    if (cuda_emulation::temp_storage_query(temp, bytes, static_cast<size_t>(n))) return cudaSuccess;
    std::vector<size_t> order(static_cast<size_t>(n));
    std::iota(order.begin(), order.end(), size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](size_t x, size_t y) { return keys_in[x] < keys_in[y]; });
    for (size_t i = 0; i < order.size(); ++i) {
      keys_out[i] = keys_in[order[i]];
      values_out[i] = values_in[order[i]];
    }
    return cudaSuccess;
  }
};

}  // namespace cub

#pragma once
// Host emulation of cub::DeviceMerge::MergeKeys (see tests/cuda_emulation/cuda_runtime.h).
#include <cuda_runtime.h>

#include <algorithm>

#include "cub/device/temp_storage.hpp"

namespace cub {

struct DeviceMerge {
  /// The two sorted sequences merged into `out`, stably (ties: the first sequence's items first).
  template <class In1, class In2, class Out, class Less>
  static cudaError_t MergeKeys(void* temp, size_t& bytes, In1 a, int64_t na, In2 b, int64_t nb, Out out,
                               Less less = {}, cudaStream_t = nullptr) {
    if (cuda_emulation::temp_storage_query(temp, bytes, static_cast<size_t>(na + nb))) return cudaSuccess;
    std::merge(a, a + na, b, b + nb, out, less);
    return cudaSuccess;
  }
};

}  // namespace cub

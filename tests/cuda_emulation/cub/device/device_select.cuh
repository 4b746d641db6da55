#pragma once
// Host emulation of cub::DeviceSelect::Flagged (see tests/cuda_emulation/cuda_runtime.h).
#include <cuda_runtime.h>

#include <type_traits>

#include "cub/device/temp_storage.hpp"

namespace cub {

struct DeviceSelect {
  /// The items whose flag is set, in order; their count into *num_selected.
  template <class In, class Flags, class Out, class Count>
  static cudaError_t Flagged(void* temp, size_t& bytes, In in, Flags flags, Out out, Count num_selected,
                             int64_t n, cudaStream_t = nullptr) {
    if (cuda_emulation::temp_storage_query(temp, bytes, static_cast<size_t>(n))) return cudaSuccess;
    int64_t k = 0;
    for (int64_t i = 0; i < n; ++i)
      if (flags[i]) out[k++] = in[i];
    *num_selected = static_cast<std::remove_reference_t<decltype(*num_selected)>>(k);
    return cudaSuccess;
  }
};

}  // namespace cub

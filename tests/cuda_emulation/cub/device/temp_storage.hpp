#pragma once
// cub's two-call protocol: a null `temp` asks how many bytes of scratch a call needs. The emulation needs
// none, but asks for some in proportion to the items, so that the callers' scratch growth runs as on a GPU.
#include <cstddef>

namespace cuda_emulation {

/// True (bytes set) for the sizing call; false when the call is to run.
inline bool temp_storage_query(void* temp, size_t& bytes, size_t items) {
  if (temp != nullptr) return false;
  bytes = 16 + 4 * items;
  return true;
}

}  // namespace cuda_emulation

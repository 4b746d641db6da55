#pragma once
// The only read-modify-write operations the step uses, on integers, so the result does not depend on the
// order threads arrive in: max for lane-entry claims, add for output counters, min for the shortest stand
// on a junction lane (its reset stores one constant, whoever stores it).
#include <stdint.h>

#include "kernels/hd.hpp"

namespace lpsim {

LPSIM_HD void atomic_max_u64(uint64_t* p, uint64_t v) {
#if defined(__CUDA_ARCH__)
  atomicMax(reinterpret_cast<unsigned long long*>(p), static_cast<unsigned long long>(v));
#else
  uint64_t cur = __atomic_load_n(p, __ATOMIC_RELAXED);
  while (cur < v && !__atomic_compare_exchange_n(p, &cur, v, true, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) {
  }
#endif
}

LPSIM_HD void atomic_add_i64(int64_t* p, int64_t v) {
#if defined(__CUDA_ARCH__)
  atomicAdd(reinterpret_cast<unsigned long long*>(p), static_cast<unsigned long long>(v));
#else
  __atomic_fetch_add(p, v, __ATOMIC_RELAXED);
#endif
}

LPSIM_HD void atomic_min_u32(uint32_t* p, uint32_t v) {
#if defined(__CUDA_ARCH__)
  atomicMin(reinterpret_cast<unsigned int*>(p), static_cast<unsigned int>(v));
#else
  uint32_t cur = __atomic_load_n(p, __ATOMIC_RELAXED);
  while (cur > v && !__atomic_compare_exchange_n(p, &cur, v, true, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) {
  }
#endif
}

LPSIM_HD void atomic_store_u32(uint32_t* p, uint32_t v) {
#if defined(__CUDA_ARCH__)
  atomicExch(reinterpret_cast<unsigned int*>(p), static_cast<unsigned int>(v));
#else
  __atomic_store_n(p, v, __ATOMIC_RELAXED);
#endif
}

}  // namespace lpsim

#pragma once
// LPSIM_HD marks functions that run on the CPU and, compiled by nvcc, on the GPU. Step logic is written once.
#if defined(__CUDACC__)
#define LPSIM_HD __host__ __device__ __forceinline__
#else
#define LPSIM_HD inline
#endif

// Maximum / minimum written inline, one definition on host and device so the backends stay bit-identical
// (GCC otherwise calls libm's fmaxf for every use). Equal values (+0 and -0 included) give `a`; a NaN `b`
// gives `a`, as fmaxf does. A NaN `a` is passed through rather than dropped: the model's quantities are
// finite, and this form compiles to a single maxss/minss, with no branches.
LPSIM_HD float lp_fmaxf(float a, float b) { return b > a ? b : a; }
LPSIM_HD float lp_fminf(float a, float b) { return b < a ? b : a; }

// floor of a non-negative value: truncation below 2^23, and every float from 2^23 up is an integer already.
// Without SSE4.1, GCC calls libm's floorf for each use; this is a compare and two conversions.
LPSIM_HD float lp_floor_nonneg(float x) {
  return x < 8388608.0f ? static_cast<float>(static_cast<int>(x)) : x;
}

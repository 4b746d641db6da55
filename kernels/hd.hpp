#pragma once
// LPSIM_HD marks functions that run on the CPU and, compiled by nvcc, on the GPU. Step logic is written once.
// LPSIM_HD_INLINED also forces the function into its callers on the host, where GCC would leave a call: for
// the few hot ones whose call costs more than the copies of their body (measured with callgrind).
#if defined(__CUDACC__)
#define LPSIM_HD __host__ __device__ __forceinline__
#define LPSIM_HD_INLINED LPSIM_HD
#else
#define LPSIM_HD inline
#define LPSIM_HD_INLINED inline __attribute__((always_inline))
#endif

// Maximum / minimum written inline, one definition on host and device so the backends stay bit-identical
// (GCC otherwise calls libm's fmaxf for every use). Equal values (+0 and -0 included) give `a`; a NaN `b`
// gives `a`, as fmaxf does. A NaN `a` is passed through rather than dropped: the model's quantities are
// finite. On x86 hosts the instruction that computes exactly this (maxss/minss: the first operand if it is
// greater/less, else the second) is written out: GCC turns many of the ternaries into compare-and-branch
// instead (the IDM sub-steps' clamps at zero among them), and those branches are data-dependent.
#if defined(__CUDA_ARCH__) || !defined(__SSE__)
LPSIM_HD float lp_fmaxf(float a, float b) { return b > a ? b : a; }
LPSIM_HD float lp_fminf(float a, float b) { return b < a ? b : a; }
#else
LPSIM_HD float lp_fmaxf(float a, float b) {
  __asm__("maxss %1, %0" : "+x"(b) : "x"(a));
  return b;
}
LPSIM_HD float lp_fminf(float a, float b) {
  __asm__("minss %1, %0" : "+x"(b) : "x"(a));
  return b;
}
#endif

// floor of a non-negative value: truncation below 2^23, and every float from 2^23 up is an integer already.
// Without SSE4.1, GCC calls libm's floorf for each use; this is a compare and two conversions.
LPSIM_HD float lp_floor_nonneg(float x) {
  return x < 8388608.0f ? static_cast<float>(static_cast<int>(x)) : x;
}

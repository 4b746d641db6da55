#pragma once
// LPSIM_HD marks functions that run on the CPU and, compiled by nvcc, on the GPU. Step logic is written once.
#if defined(__CUDACC__)
#define LPSIM_HD __host__ __device__ __forceinline__
#else
#define LPSIM_HD inline
#endif

// fmaxf / fminf exactly as glibc computes them (NaN and signed-zero cases included), written inline: GCC
// otherwise calls libm for every use (it may inline only under fast-math), and one definition on host and
// device keeps the backends bit-identical.
// One comparison and a select (no branches on the hot path).
LPSIM_HD float lp_fmaxf(float a, float b) { return (a >= b) | (b != b) ? a : b; }
LPSIM_HD float lp_fminf(float a, float b) { return (a <= b) | (b != b) ? a : b; }

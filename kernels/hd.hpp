#pragma once
// LPSIM_HD marks functions that run on the CPU and, compiled by nvcc, on the GPU. Step logic is written once.
#if defined(__CUDACC__)
#define LPSIM_HD __host__ __device__ __forceinline__
#else
#define LPSIM_HD inline
#endif
